// apex_rviz_plugin/GraphPanel: the graph editor docked in rviz. Thin: it holds
// a PanelWidget, keeps the runtime's namespace in the .rviz config, and turns
// an inspected port into an rviz display (rviz_displays.hpp) that follows its
// node: renamed with it, removed with it, disabled while it cannot run.
#pragma once

#include <rviz/panel.h>

#include <QByteArray>
#include <QList>
#include <QPointer>
#include <map>

#include "apex_rviz_plugin/rviz_displays.hpp"

namespace rviz {
class Display;
}

namespace apex_rviz_plugin {

class PanelWidget;

class GraphPanel : public rviz::Panel {
  Q_OBJECT
 public:
  explicit GraphPanel(QWidget* parent = nullptr);
  void onInitialize() override;
  void load(const rviz::Config& config) override;
  void save(rviz::Config config) const override;

 private:
  /** node/port is published on `topic` as `message_type`: its display, made once (or the one a
   *  config kept under its name), shows `topic`, enabled if its node can run. */
  void showDisplay(const QString& node, const QString& port, const QString& topic, const QString& message_type);
  /** The graph shown changed: the displays made here follow it. */
  void followGraph();
  /** The editor over rviz's whole window (the 3D view and the other docks hidden), or rviz's
   *  layout as it was before. */
  void setWholeWindow(bool on);
  /** Removes a display from rviz as its Displays panel does. */
  void removeDisplay(rviz::Display* display);

  PanelWidget* widget_;
  FollowedDisplays followed_;
  std::map<int, QPointer<rviz::Display>> displays_;  // by followed_'s id; null once deleted in rviz
  QList<QPointer<QWidget>> hidden_;  // while the editor has the whole window: what it hid
  QByteArray layout_;  // rviz's window layout before
};

}  // namespace apex_rviz_plugin
