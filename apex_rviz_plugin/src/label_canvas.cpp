#include "apex_rviz_plugin/label_canvas.hpp"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>

#include <algorithm>
#include <cmath>

namespace apex_rviz_plugin {
namespace {

constexpr double kClickJitter = 3;  // widget pixels a click may move and stay a click

QColor boxColour(bool selected) { return selected ? QColor(255, 210, 0) : QColor(0, 230, 90); }

}  // namespace

LabelCanvas::LabelCanvas(QWidget* parent) : QWidget(parent) {
  setObjectName("label_canvas");
  setMinimumSize(320, 240);
  setFocusPolicy(Qt::ClickFocus);  // a click on the frame: the arrows, Delete and typing are the canvas's
  setCursor(Qt::CrossCursor);
  setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
}

void LabelCanvas::setImage(const QImage& image) {
  const bool resized = image.size() != image_.size();
  image_ = image;
  if (resized) updateGeometry();
  update();
}

void LabelCanvas::setBoxes(std::vector<LabelBox> boxes, int selected) {
  boxes_ = std::move(boxes);
  selected_ = selected >= 0 && selected < static_cast<int>(boxes_.size()) ? selected : -1;
  update();
}

QSize LabelCanvas::sizeHint() const { return image_.isNull() ? QSize(640, 480) : image_.size().expandedTo(minimumSize()); }

QRectF LabelCanvas::imageRect() const {
  if (image_.isNull()) return QRectF(rect());
  const double scale = std::min(width() / double(image_.width()), height() / double(image_.height()));
  const QSizeF size(image_.width() * scale, image_.height() * scale);
  return QRectF(QPointF((width() - size.width()) / 2, (height() - size.height()) / 2), size);
}

QPointF LabelCanvas::toWidget(QPointF p) const {
  const QRectF r = imageRect();
  if (image_.isNull()) return p;
  return r.topLeft() + QPointF(p.x() * r.width() / image_.width(), p.y() * r.height() / image_.height());
}

QPointF LabelCanvas::toImage(QPointF p) const {
  const QRectF r = imageRect();
  if (image_.isNull() || r.isEmpty()) return p;
  return QPointF((p.x() - r.left()) * image_.width() / r.width(), (p.y() - r.top()) * image_.height() / r.height());
}

int LabelCanvas::boxAt(QPointF p) const {
  const QPointF at = toImage(p);
  for (int i = static_cast<int>(boxes_.size()) - 1; i >= 0; --i) {  // the last drawn lies on top
    const LabelBox& b = boxes_[static_cast<std::size_t>(i)];
    if (QRectF(b.x, b.y, b.width, b.height).contains(at)) return i;
  }
  return -1;
}

void LabelCanvas::paintEvent(QPaintEvent*) {
  QPainter painter(this);
  painter.fillRect(rect(), QColor(40, 40, 40));
  if (image_.isNull()) {
    painter.setPen(Qt::lightGray);
    painter.drawText(rect(), Qt::AlignCenter | Qt::TextWordWrap, "no frame yet: play or step the graph's source");
    return;
  }
  painter.setRenderHint(QPainter::SmoothPixmapTransform);
  painter.drawImage(imageRect(), image_);
  const QFontMetrics metrics(font());
  for (std::size_t i = 0; i < boxes_.size(); ++i) {
    const LabelBox& b = boxes_[i];
    const bool selected = static_cast<int>(i) == selected_;
    const QRectF r(toWidget(QPointF(b.x, b.y)), toWidget(QPointF(b.x + b.width, b.y + b.height)));
    painter.setPen(QPen(boxColour(selected), selected ? 3 : 2));
    painter.setBrush(Qt::NoBrush);
    painter.drawRect(r);
    const QString label = QString::fromStdString(b.label);  // its class, on a tab above its corner
    const QRectF tab(r.left(), std::max(0.0, r.top() - metrics.height() - 2), metrics.horizontalAdvance(label) + 6,
                     metrics.height() + 2);
    painter.fillRect(tab, boxColour(selected));
    painter.setPen(Qt::black);
    painter.drawText(tab, Qt::AlignCenter, label);
  }
  if (press_ && moved_) {  // the box being drawn
    painter.setPen(QPen(Qt::white, 1, Qt::DashLine));
    painter.drawRect(QRectF(*press_, now_).normalized());
  }
}

void LabelCanvas::mousePressEvent(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return QWidget::mousePressEvent(event);
  press_ = event->localPos(), now_ = event->localPos(), moved_ = false;
}

void LabelCanvas::mouseMoveEvent(QMouseEvent* event) {
  if (!press_) return;
  now_ = event->localPos();
  moved_ = moved_ || std::hypot(now_.x() - press_->x(), now_.y() - press_->y()) > kClickJitter;
  update();
}

void LabelCanvas::mouseReleaseEvent(QMouseEvent* event) {
  if (!press_ || event->button() != Qt::LeftButton) return QWidget::mouseReleaseEvent(event);
  const QPointF from = *press_, to = event->localPos();
  const bool drag = moved_ || std::hypot(to.x() - from.x(), to.y() - from.y()) > kClickJitter;
  press_.reset(), moved_ = false;
  update();
  if (!drag) return emit boxClicked(boxAt(from));
  // the corners in whole pixels: the pixels the drag covers
  const QPointF a = toImage(from), b = toImage(to);
  const int x0 = static_cast<int>(std::lround(std::min(a.x(), b.x()))),
            y0 = static_cast<int>(std::lround(std::min(a.y(), b.y())));
  const int x1 = static_cast<int>(std::lround(std::max(a.x(), b.x()))),
            y1 = static_cast<int>(std::lround(std::max(a.y(), b.y())));
  emit boxDrawn(QRect(x0, y0, x1 - x0, y1 - y0));
}

void LabelCanvas::keyPressEvent(QKeyEvent* event) {
  const QString text = event->text();
  if (text.isEmpty() || !text.at(0).isPrint() || (event->modifiers() & (Qt::ControlModifier | Qt::AltModifier)))
    return QWidget::keyPressEvent(event);
  emit textTyped(text);
}

}  // namespace apex_rviz_plugin
