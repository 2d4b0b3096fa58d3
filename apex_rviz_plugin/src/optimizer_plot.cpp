#include "apex_rviz_plugin/optimizer_plot.hpp"

#include <QPainterPath>

#include <algorithm>

namespace apex_rviz_plugin {
namespace {

/** Where `v` in [lo, hi] falls between `from` and `to` (the middle if the span is empty). */
double along(double v, double lo, double hi, double from, double to) {
  return hi > lo ? from + (to - from) * (v - lo) / (hi - lo) : (from + to) / 2;
}

void paintCurve(QPainter* p, const QRectF& plot, int budget, const std::vector<double>& fitness) {
  if (fitness.size() < 2) return;
  const auto [lo, hi] = std::minmax_element(fitness.begin(), fitness.end());
  const double n = std::max<double>(budget, fitness.size()) - 1;
  QPolygonF curve;  // best fitness over evaluations, left to right up to the budget
  for (std::size_t i = 0; i < fitness.size(); ++i)
    curve << QPointF(plot.left() + plot.width() * i / n, along(fitness[i], *lo, *hi, plot.bottom() - 2, plot.top() + 2));
  p->setPen(QPen(QColor(110, 200, 120), 1.5));
  p->drawPolyline(curve);
}

void paintFront(QPainter* p, const QRectF& plot, const std::vector<FrontPoint>& front) {
  const auto [cheap, dear] = std::minmax_element(front.begin(), front.end(),
                                                 [](const auto& a, const auto& b) { return a.ms_per_frame < b.ms_per_frame; });
  const auto [worst, best] =
      std::minmax_element(front.begin(), front.end(), [](const auto& a, const auto& b) { return a.fitness < b.fitness; });
  QPolygonF line;
  for (const auto& f : front)
    line << QPointF(along(f.ms_per_frame, cheap->ms_per_frame, dear->ms_per_frame, plot.left() + 5, plot.right() - 5),
                    along(f.fitness, worst->fitness, best->fitness, plot.bottom() - 5, plot.top() + 5));
  p->setPen(QColor(150, 150, 150));  // first: the points go over it
  p->drawText(plot.adjusted(3, 1, -3, -1), Qt::AlignRight | Qt::AlignBottom, "ms/frame →");
  p->setPen(QPen(kFrontColor.darker(150), 1));
  p->drawPolyline(line);
  // One shape: points that overlap are filled once, so no antialiased edge of one cuts another.
  QPainterPath points;
  points.setFillRule(Qt::WindingFill);
  for (const auto& at : line) points.addEllipse(at, 3, 3);
  p->fillPath(points, kFrontColor);
}

}  // namespace

void paintOptimizerRun(QPainter* p, const QRectF& area, int evaluations, int budget, const std::vector<double>& fitness,
                       const std::vector<FrontPoint>& front) {
  QString line = QString("%1 / %2 evaluations").arg(evaluations).arg(budget);
  if (!fitness.empty()) line += QString(" · best %1").arg(fitness.back(), 0, 'g', 4);
  if (!front.empty()) line += QString(" · front %1").arg(front.size());
  p->setPen(QColor(200, 200, 200));
  p->drawText(QRectF(area.left(), area.top(), area.width(), 14), Qt::AlignLeft | Qt::AlignVCenter, line);
  QRectF plot(area.left(), area.top() + 16, area.width(), area.height() - 16);
  const QRectF beside = front.empty() ? QRectF() : plot.adjusted(plot.width() / 2 + 2, 0, 0, 0);
  if (!front.empty()) plot.setRight(plot.left() + plot.width() / 2 - 2);
  for (const QRectF& frame : {plot, beside}) {
    if (frame.isNull()) continue;
    p->setPen(QColor(90, 90, 90));
    p->setBrush(Qt::NoBrush);
    p->drawRect(frame);
  }
  paintCurve(p, plot, budget, fitness);
  if (!front.empty()) paintFront(p, beside, front);
}

}  // namespace apex_rviz_plugin
