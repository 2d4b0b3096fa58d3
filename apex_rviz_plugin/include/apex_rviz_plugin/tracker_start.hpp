// Starting a Tracker (kTrackerType) on a box drawn on its frame, from its node's menu ("Start on a
// box drawn on the frame..."): a window showing one frame the Tracker saw, held still, scaled to
// fit (LabelCanvas, the labelling view's canvas). The person drags a box around the object; the
// box, in the image's pixels and cut to it, is handed on (boxChosen) and the window closes. It
// makes no calls: the panel brings the frame and sets the Tracker's x, y, width and height from
// the box as one edit (TrackerStarter, tracker_starter.cpp). The window deletes itself when closed.
#pragma once

#include <QDialog>
#include <QImage>
#include <QRect>

#include <optional>

class QLabel;

namespace apex_rviz_plugin {

class LabelCanvas;

/** @brief `drawn` (image pixels) cut to an image of `size`; nothing if no pixel of it is left
 *  (a box dragged beside the image, or a line). */
std::optional<QRect> boxInImage(const QRect& drawn, const QSize& size);

class TrackerStartView : public QDialog {
  Q_OBJECT
 public:
  /** @brief A window for `tracker`, whose frames come from output `source` ("node/port"). Hidden
   *  until showFrame gives it its frame. */
  TrackerStartView(const QString& tracker, const QString& source, QWidget* parent = nullptr);
  const QString& tracker() const { return tracker_; }
  const QString& source() const { return source_; }
  /** @brief The frame to draw on (not null): shown, and the window opened and raised. Once only:
   *  the box is drawn on a still frame. */
  void showFrame(const QImage& image);
  /** @brief Whether its frame came. */
  bool hasFrame() const;
  LabelCanvas* canvas() const { return canvas_; }
  /** @brief The status line: what to do, or what was wrong with the last drag (red). */
  QString status() const;

 signals:
  /** A box was dragged: `box`, in the image's pixels, inside it. The window closes. */
  void boxChosen(const QString& tracker, const QRect& box);

 private:
  void onBoxDrawn(const QRect& drawn);
  void showStatus(const QString& text, bool error);

  QString tracker_, source_;
  LabelCanvas* canvas_;
  QLabel* status_;
};

}  // namespace apex_rviz_plugin
