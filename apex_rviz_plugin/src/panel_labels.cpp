// The panel's side of labelling frames (LabelView): a window per image output, fed with the
// output's whole images through an inspection (inspect/<node>/<port>), stepping the player that
// feeds it through the player's slots, as its transport bar does.
#include <deque>
#include <set>

#include "apex_rviz_plugin/label_view.hpp"
#include "apex_rviz_plugin/panel_widget.hpp"
#include "apex_rviz_plugin/transport_bar.hpp"

namespace apex_rviz_plugin {

void PanelWidget::labelFrames(const QString& node, const QString& port) {
  QPointer<LabelView>& view = label_views_[node.toStdString() + "/" + port.toStdString()];
  if (!view) {
    view = new LabelView(node, port, this);
    view->resize(900, 700);
    connect(view, &LabelView::stepRequested, this, &PanelWidget::onFireSlotRequested);
    connect(view, &LabelView::closed, this, [this, node, port] { link_.unwatchFrames(node.toStdString(), port.toStdString()); });
  }
  const QString player = playerFeeding(node.toStdString());
  view->setPlayer(player);
  view->show();
  view->raise();
  view->activateWindow();
  const apex::ParamInfo* playing = player.isEmpty() ? nullptr : model_.parameter(player.toStdString(), "playing");
  if (playing && playing->value == "true") {  // a frame to label holds still: paused as its transport bar pauses it
    onParameterEdited(player, "playing", "false", false);
    view->showStatus("paused " + player + " to label its frames: Next and Previous step it", false);
  }
  watchFrames(view);
}

LabelView* PanelWidget::labelView(const QString& node, const QString& port) const {
  const auto it = label_views_.find(node.toStdString() + "/" + port.toStdString());
  return it == label_views_.end() ? nullptr : it->second.data();
}

QString PanelWidget::playerFeeding(const std::string& node) const {
  // upstream through data links, nearest first (an export leads from a subgraph's port inside it)
  std::deque<std::string> next{node};
  std::set<std::string> seen{node};
  while (!next.empty()) {
    const std::string at = next.front();
    next.pop_front();
    if (const apex::NodeInfo* n = model_.node(at); n && TransportBar::isPlayer(*n)) return QString::fromStdString(at);
    for (const auto& c : model_.graph().connections)
      if (c.to_node == at && (c.kind == "data" || c.kind == "export") && seen.insert(c.from_node).second)
        next.push_back(c.from_node);
  }
  return QString();
}

void PanelWidget::watchFrames(LabelView* view) {
  const QPointer<LabelView> alive(view);
  const std::string node = view->node().toStdString(), port = view->port().toStdString();
  link_.inspect(
      node, port, [this, alive, node, port](bool ok, const std::string& m, const std::string& topic, const std::string&) {
        if (!alive || !alive->isVisible()) return;
        if (!ok) return alive->showStatus(QString::fromStdString("cannot show " + node + "/" + port + ": " + m), true);
        link_.watchFrames(node, port, topic);  // a held frame comes at once: the runtime sends it again to a new subscriber
      });
}

void PanelWidget::watchLabelledAgain() {
  for (const auto& [key, view] : label_views_)
    if (view && view->isVisible()) watchFrames(view);
}

void PanelWidget::onFrameReceived(const QString& node, const QString& port, const QImage& image, quint64 stamp,
                                  const QString& encoding) {
  if (LabelView* view = labelView(node, port); view && view->isVisible()) view->showFrame(image, stamp, encoding);
}

}  // namespace apex_rviz_plugin
