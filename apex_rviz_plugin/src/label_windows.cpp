// The labelling windows (LabelView): a window per image output, fed with the output's whole
// images through an inspection (inspect/<node>/<port>), stepping the player that feeds it through
// the player's slots, as its transport bar does.
#include "apex_rviz_plugin/label_windows.hpp"

#include <deque>
#include <set>

#include "apex_rviz_plugin/label_view.hpp"
#include "apex_rviz_plugin/transport_bar.hpp"

namespace apex_rviz_plugin {

LabelWindows::LabelWindows(const PanelContext& context, QWidget* owner) : ctx_(context), owner_(owner) {
  connect(&ctx_.link, &RuntimeLink::frameReceived, this, &LabelWindows::onFrame);
}

void LabelWindows::open(const QString& node, const QString& port) {
  QPointer<LabelView>& view = views_[node.toStdString() + "/" + port.toStdString()];
  if (!view) {
    view = new LabelView(node, port, owner_);
    view->resize(900, 700);
    connect(view, &LabelView::stepRequested, this, &LabelWindows::fireSlotRequested);
    connect(view, &LabelView::closed, this,
            [this, node, port] { ctx_.link.unwatchFrames(node.toStdString(), port.toStdString()); });
  }
  const QString player = playerFeeding(node.toStdString());
  view->setPlayer(player);
  view->show();
  view->raise();
  view->activateWindow();
  const apex::ParamInfo* playing = player.isEmpty() ? nullptr : ctx_.model.parameter(player.toStdString(), "playing");
  if (playing && playing->value == "true") {  // a frame to label holds still: paused as its transport bar pauses it
    emit editRequested(ctx_.model.setParameter(player.toStdString(), "playing", "false", false));
    view->showStatus("paused " + player + " to label its frames: Next and Previous step it", false);
  }
  watchFrames(view);
}

LabelView* LabelWindows::view(const QString& node, const QString& port) const {
  const auto it = views_.find(node.toStdString() + "/" + port.toStdString());
  return it == views_.end() ? nullptr : it->second.data();
}

bool LabelWindows::showing(const QString& node, const QString& port) const {
  const LabelView* v = view(node, port);
  return v && v->isVisible();
}

QString LabelWindows::playerFeeding(const std::string& node) const {
  // upstream through data links, nearest first (an export leads from a subgraph's port inside it)
  std::deque<std::string> next{node};
  std::set<std::string> seen{node};
  while (!next.empty()) {
    const std::string at = next.front();
    next.pop_front();
    if (const apex::NodeInfo* n = ctx_.model.node(at); n && TransportBar::isPlayer(*n)) return QString::fromStdString(at);
    for (const auto& c : ctx_.model.graph().connections)
      if (c.to_node == at && (c.kind == "data" || c.kind == "export") && seen.insert(c.from_node).second)
        next.push_back(c.from_node);
  }
  return QString();
}

void LabelWindows::watchFrames(LabelView* view) {
  const QPointer<LabelView> alive(view);
  const std::string node = view->node().toStdString(), port = view->port().toStdString();
  ctx_.link.inspect(
      node, port, [this, alive, node, port](bool ok, const std::string& m, const std::string& topic, const std::string&) {
        if (!alive || !alive->isVisible()) return;
        if (!ok) return alive->showStatus(QString::fromStdString("cannot show " + node + "/" + port + ": " + m), true);
        ctx_.link.watchFrames(node, port, topic);  // a held frame comes at once: the runtime sends it again to a new subscriber
      });
}

void LabelWindows::watchAgain() {
  for (const auto& [key, view] : views_)
    if (view && view->isVisible()) watchFrames(view);
}

void LabelWindows::onFrame(const QString& node, const QString& port, const QImage& image, quint64 stamp,
                           const QString& encoding) {
  if (LabelView* v = view(node, port); v && v->isVisible()) v->showFrame(image, stamp, encoding);
}

}  // namespace apex_rviz_plugin
