// The previews on the nodes (previews.cpp): while on, every node shown gets its preview area; the
// outputs of nodes in view are previewed (inspected with preview, subscribed), those out of view
// are not (unsubscribed: the runtime then publishes nothing for them). It owns whether they are
// on, the timer that follows the view, and the ports previewed.
#pragma once

#include <set>
#include <string>

#include <QObject>
#include <QTimer>

#include "apex_rviz_plugin/panel_context.hpp"

namespace apex_rviz_plugin {

class Previews : public QObject {
  Q_OBJECT
 public:
  explicit Previews(const PanelContext& context, QObject* parent = nullptr);

  bool on() const { return on_; }
  /** @brief Previews on (updated every 300 ms, as the view moves) or off (none asked for). */
  void setOn(bool on);
  /** @brief The ports of the nodes in view previewed, the others not. */
  void update();
  /** @brief The runtime ended its previews (a load, a group, an ungroup): asked for anew by the next update. */
  void again();
  /** @brief The runtime is gone or another one came: nothing is previewed (the link's
   *  subscriptions go with its runtime). */
  void reset() { previewing_.clear(); }

 private:
  /** Inspects node/port with preview and watches what it publishes, unless no longer wanted by then. */
  void start(const std::string& key);

  PanelContext ctx_;
  bool on_ = false;
  QTimer timer_;
  std::set<std::string> previewing_;  // "node/port" whose preview is asked for or watched
};

}  // namespace apex_rviz_plugin
