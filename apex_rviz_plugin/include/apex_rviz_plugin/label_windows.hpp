// The labelling windows (label_windows.cpp): one LabelView per image output, fed with the output's
// whole images through an inspection (inspect/<node>/<port>), stepping the player that feeds it
// through the player's slots, as its transport bar does. It owns the windows, hidden when closed.
#pragma once

#include <map>
#include <optional>
#include <string>

#include <QObject>
#include <QPointer>

#include "apex_rviz_plugin/panel_context.hpp"

namespace apex_rviz_plugin {

class LabelView;

class LabelWindows : public QObject {
  Q_OBJECT
 public:
  /** The windows are `owner`'s children (closed with it). */
  LabelWindows(const PanelContext& context, QWidget* owner);

  /** @brief Opens (or raises) the labelling window of image output node/port: its frames come as
   *  the runtime inspects the port; its player, if one feeds it and plays, is paused. */
  void open(const QString& node, const QString& port);
  /** @brief The labelling window of node/port, or nullptr before it was opened. */
  LabelView* view(const QString& node, const QString& port) const;
  /** @brief Whether a labelling window on node/port is open (it keeps the port's frames coming). */
  bool showing(const QString& node, const QString& port) const;
  /** @brief The open windows' ports inspected again (the runtime ended every inspection, or is new). */
  void watchAgain();

 signals:
  /** The player's `playing` set to false as an edit: a frame to label holds still. */
  void editRequested(const std::optional<Edit>& edit);
  /** A window's Next or Previous: the player's slot fired. */
  void fireSlotRequested(const QString& node, const QString& slot);

 private:
  /** The player (a node with a transport bar) whose frames reach `node` through data links, the
   *  node itself if it is one; "" if none does. */
  QString playerFeeding(const std::string& node) const;
  /** Inspects the window's port and sends its images to it; a refusal is said in the window. */
  void watchFrames(LabelView* view);
  void onFrame(const QString& node, const QString& port, const QImage& image, quint64 stamp, const QString& encoding);

  PanelContext ctx_;
  QWidget* owner_;
  std::map<std::string, QPointer<LabelView>> views_;  // "node/port": labelling windows, hidden when closed
};

}  // namespace apex_rviz_plugin
