// Starting a Tracker on a box drawn on its frame (tracker_starter.cpp): the output feeding its
// image input is inspected, and the frame it holds (the one the Tracker last saw: the runtime sends
// it again to a new subscriber) opens a TrackerStartView; the box drawn becomes the Tracker's x, y,
// width and height in one edit, and setting them restarts it on that box. It owns the window while
// it is open; one at a time.
#pragma once

#include <optional>

#include <QObject>
#include <QPointer>
#include <QRect>

#include "apex_rviz_plugin/panel_context.hpp"

namespace apex_rviz_plugin {

class LabelWindows;
class TrackerStartView;

class TrackerStarter : public QObject {
  Q_OBJECT
 public:
  /** The window is `owner`'s child; `labels` keep a port's frames coming while one labels them. */
  TrackerStarter(const PanelContext& context, const LabelWindows& labels, QWidget* owner);

  /** @brief Opens the window for Tracker `tracker` on the frame held by the output feeding its
   *  image input. Nothing linked to its image input, no frame within a few seconds, or one that
   *  cannot be shown: the message line says so and no window opens. */
  void start(const QString& tracker);
  /** @brief The window, open or waiting for its frame; nullptr if none. */
  TrackerStartView* view() const;

 signals:
  /** The box drawn, as the Tracker's x, y, width and height set in one edit. */
  void editRequested(const std::optional<Edit>& edit);
  /** The same box again: the Tracker's restart slot fired. */
  void fireSlotRequested(const QString& node, const QString& slot);

 private:
  /** The frame for the window waiting for one (its source's): it opens on it. */
  void onFrame(const QString& node, const QString& port, const QImage& image, quint64 stamp, const QString& encoding);
  /** The frames of node/port no longer wanted for a Tracker (a labelling window on them keeps them). */
  void stopFrames(const QString& node, const QString& port);
  /** Watches the frames of from/port for the window `alive`, and closes it if none comes in time. */
  void watchSource(const QPointer<TrackerStartView>& alive, const QString& tracker, const QString& from, const QString& port,
                   const std::string& topic);
  /** The Tracker's x, y, width and height set to `box` (image pixels) as one edit. */
  void startOn(const QString& tracker, const QRect& box);

  PanelContext ctx_;
  const LabelWindows& labels_;
  QWidget* owner_;
  QPointer<TrackerStartView> view_;  // it deletes itself when closed
};

}  // namespace apex_rviz_plugin
