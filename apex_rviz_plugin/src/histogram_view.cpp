#include "apex_rviz_plugin/histogram_view.hpp"

#include <QLabel>
#include <QPainter>
#include <QTimer>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>

namespace apex_rviz_plugin {
namespace {

Bars barsOf(const std::vector<double>& lower, const std::vector<double>& upper, const std::vector<std::uint64_t>& counts) {
  Bars b;
  b.lower_ms = lower, b.upper_ms = upper, b.counts = counts;
  const std::size_t n = std::min({lower.size(), upper.size(), counts.size()});
  b.lower_ms.resize(n), b.upper_ms.resize(n), b.counts.resize(n);
  return b;
}

QString ms(double v) { return QString::number(v, 'g', v < 10 ? 2 : 3) + " ms"; }

}  // namespace

std::uint64_t Bars::total() const {
  std::uint64_t n = 0;
  for (auto c : counts) n += c;
  return n;
}

double Bars::quantileMs(double q) const {
  const std::uint64_t n = total();
  if (n == 0) return -1;
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    seen += counts[i];
    if (double(seen) >= q * double(n) && counts[i] > 0) return (lower_ms[i] + upper_ms[i]) / 2;
  }
  return (lower_ms.back() + upper_ms.back()) / 2;
}

QString Bars::summary(double window_s, const QString& none) const {
  if (total() == 0) return none;
  return QString("%1 over %2 s · p50 %3 · p95 %4 · max < %5")
      .arg(total())
      .arg(window_s, 0, 'f', 1)
      .arg(ms(quantileMs(0.5)), ms(quantileMs(0.95)), ms(upper_ms.back()));
}

HistogramChart::HistogramChart(QWidget* parent) : QWidget(parent) { setMinimumSize(320, 110); }

void HistogramChart::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.fillRect(rect(), QColor(30, 32, 36));
  const QRectF area = QRectF(rect()).adjusted(8, 6, -8, -18);
  p.setPen(QColor(200, 200, 200));
  if (bars_.total() == 0) return p.drawText(area, Qt::AlignCenter, "nothing in the window");
  // a log scale from the first bar's lower bound (at least 1 µs) to the last bar's upper one
  const double lo = std::log10(std::max(bars_.lower_ms.front(), 0.001)), hi = std::log10(bars_.upper_ms.back());
  const auto x = [&](double v) {
    return area.left() + area.width() * (std::log10(std::max(v, 0.001)) - lo) / std::max(hi - lo, 1e-9);
  };
  const double most = double(*std::max_element(bars_.counts.begin(), bars_.counts.end()));
  p.setPen(Qt::NoPen);
  p.setBrush(QColor(140, 190, 230));
  for (std::size_t i = 0; i < bars_.counts.size(); ++i) {
    const double h = std::max(2.0, area.height() * double(bars_.counts[i]) / most);  // one in thousands is seen too
    p.drawRect(QRectF(QPointF(x(bars_.lower_ms[i]), area.bottom() - h), QPointF(x(bars_.upper_ms[i]) - 1, area.bottom())));
  }
  for (const auto& [q, colour] : {std::pair{0.5, QColor(255, 220, 80)}, std::pair{0.95, QColor(255, 140, 0)}}) {
    p.setPen(QPen(colour, 1.5, Qt::DashLine));
    const double at = x(bars_.quantileMs(q));
    p.drawLine(QPointF(at, area.top()), QPointF(at, area.bottom()));
  }
  p.setPen(QColor(200, 200, 200));
  QFont f = p.font();
  f.setPointSizeF(7.5);
  p.setFont(f);
  const QRectF axis(area.left(), area.bottom() + 2, area.width(), 14);
  p.drawText(axis, Qt::AlignLeft | Qt::AlignVCenter, ms(std::max(bars_.lower_ms.front(), 0.001)));
  p.drawText(axis, Qt::AlignRight | Qt::AlignVCenter, ms(bars_.upper_ms.back()));
  p.drawText(axis, Qt::AlignHCenter | Qt::AlignVCenter, "log scale · p50 yellow, p95 orange");
}

HistogramView::HistogramView(const QString& node, QWidget* parent) : QDialog(parent), node_(node) {
  setObjectName("histogram_" + node);
  setWindowTitle("Latency of " + node);
  setAttribute(Qt::WA_DeleteOnClose);
  auto* column = new QVBoxLayout(this);
  const auto add = [&](const QString& title, HistogramChart*& chart, QLabel*& text) {
    column->addWidget(new QLabel("<b>" + title + "</b>", this));
    chart = new HistogramChart(this);
    column->addWidget(chart);
    text = new QLabel("asking the runtime...", this);
    column->addWidget(text);
  };
  add("Latency: from the frame's stamp to the end of its firing", latency_, latency_text_);
  add("Firing time", time_, time_text_);
  timer_ = new QTimer(this);
  timer_->setInterval(1000);
  connect(timer_, &QTimer::timeout, this, [this] { emit refreshRequested(node_); });
}

void HistogramView::showEvent(QShowEvent* e) {
  QDialog::showEvent(e);
  timer_->start();
  emit refreshRequested(node_);
}

void HistogramView::hideEvent(QHideEvent* e) {
  timer_->stop();
  QDialog::hideEvent(e);
}

void HistogramView::showProfile(bool ok, const std::string& message, const apex::GetNodeProfile::Response& res) {
  if (!ok) {
    time_text_->setText(QString::fromStdString(message));
    return;
  }
  time_->setBars(barsOf(res.time_lower_ms, res.time_upper_ms, res.time_counts));
  latency_->setBars(barsOf(res.latency_lower_ms, res.latency_upper_ms, res.latency_counts));
  time_text_->setText(time_->bars().summary(res.window_s, "no timed firing in the window") + " (firings)");
  latency_text_->setText(latency_->bars().summary(
      res.window_s, "none: no frame stamped within the last hour reached it (a bag at its recorded stamps, or unstamped data)"));
}

QString HistogramView::timeText() const { return time_text_->text(); }
QString HistogramView::latencyText() const { return latency_text_->text(); }

}  // namespace apex_rviz_plugin
