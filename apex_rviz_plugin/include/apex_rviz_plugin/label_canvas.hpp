// The frame in the labelling view (LabelView), scaled to fit the widget, with its boxes and their
// classes. A drag with the left button draws a box; a click on a box selects it, a click beside
// every box selects none; a letter typed on it starts a class name (the view's class field takes
// it). Boxes are in the image's pixels; the canvas maps them to the widget.
#pragma once

#include <QImage>
#include <QWidget>

#include <optional>
#include <vector>

#include "apex_rviz_plugin/frame_labels.hpp"

namespace apex_rviz_plugin {

class LabelCanvas : public QWidget {
  Q_OBJECT
 public:
  explicit LabelCanvas(QWidget* parent = nullptr);
  void setImage(const QImage& image);
  const QImage& image() const { return image_; }
  /** @brief The boxes to draw, and which is selected (-1: none). */
  void setBoxes(std::vector<LabelBox> boxes, int selected);
  int selected() const { return selected_; }
  /** @brief Whether a drag is under way (a frame that comes meanwhile waits for its end). */
  bool dragging() const { return press_.has_value(); }
  /** @brief Where the image's point `p` (pixels) is drawn in the widget, and back. */
  QPointF toWidget(QPointF p) const;
  QPointF toImage(QPointF p) const;
  QSize sizeHint() const override;

 signals:
  /** A drag ended: the box between its ends, in the image's pixels (possibly without width or
   *  height, or outside the image: FrameLabels::add says why it is ignored). */
  void boxDrawn(const QRect& box);
  /** A click selected box `index` (-1: a click beside every box). */
  void boxClicked(int index);
  /** Text typed while the canvas has the focus (a class name begun). */
  void textTyped(const QString& text);

 protected:
  void paintEvent(QPaintEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;

 private:
  /** Where the image is drawn: centred, as large as fits, its shape kept. */
  QRectF imageRect() const;
  /** The topmost box under widget point `p`, or -1. */
  int boxAt(QPointF p) const;

  QImage image_;
  std::vector<LabelBox> boxes_;
  int selected_ = -1;
  std::optional<QPointF> press_;  // where the left button went down (widget)
  QPointF now_;  // where the mouse is while it is held (widget)
  bool moved_ = false;  // the mouse went further than a click's jitter: a drag
};

}  // namespace apex_rviz_plugin
