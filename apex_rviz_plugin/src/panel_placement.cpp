// PanelWidget, where boxes go: new nodes on free places, a loaded graph laid out
// (graphviz), boxes that grew pushed off the ones below; positions are sent as
// set_ui outside the history, and reserved until the graph shows them. And where
// nodes run: Balance's thread groups, one edit.
#include "apex_rviz_plugin/panel_widget.hpp"

#include <variant>

namespace apex_rviz_plugin {

void PanelWidget::tidy() {
  const auto boxes = editor_->scene()->boxes();
  if (boxes.empty()) return;
  double left = 1e18, top = 1e18;
  std::map<std::string, std::pair<double, double>> shown;  // Undo puts back what the user saw
  for (const auto& [name, b] : boxes) left = std::min(left, b.x), top = std::min(top, b.y), shown[name] = {b.x, b.y};
  auto at = layeredLayout(boxes, editor_->scene()->edges());
  for (auto& [name, p] : at) p.first += left, p.second += top;
  perform(model_.arrange(at, "Tidy", shown));
}

void PanelWidget::balance() {
  editor_->showMessage("Balance: asking the runtime for thread groups...", false);
  // The times measured so far (frames 0): the answer comes at once, and the call never waits for frames.
  link_.balance(0, 0, [this](bool ok, const std::string& m, const apex::Balance::Response& res) {
    if (!ok) return report(false, m, "Balance");
    std::vector<std::pair<std::string, std::string>> moves;
    for (std::size_t i = 0; i < res.nodes.size() && i < res.groups.size(); ++i) moves.emplace_back(res.nodes[i], res.groups[i]);
    std::string text = res.message;
    for (const auto& note : res.notes) text += "; " + note;
    auto edit = model_.setThreadGroups(moves, "Balance: " + text);  // perform() shows the label once applied
    if (!edit)
      return editor_->showMessage(QString::fromStdString("Balance: the groups are so already. " + text), !res.notes.empty());
    perform(edit);
  });
}

void PanelWidget::placeUnplaced() {
  const auto boxes = editor_->scene()->boxes();
  if (untangle_ && !boxes.empty()) {  // positions written for other box sizes (by hand, another panel)
    untangle_ = false;
    bool overlap = false;
    for (auto a = boxes.begin(); a != boxes.end() && !overlap; ++a)
      for (auto b = std::next(a); b != boxes.end() && !overlap; ++b) overlap = a->second.overlaps(b->second);
    if (overlap) {
      editor_->fitNextGraph();  // the view shows them where they go
      return place(layeredLayout(boxes, editor_->scene()->edges()));
    }
  }
  std::map<std::string, Box> unplaced;
  std::vector<Box> placed;
  for (const auto& [name, box] : boxes) {
    auto sent = placing_.find(name);
    if (model_.hasPosition(name)) {
      if (sent != placing_.end()) placing_.erase(sent);
      placed.push_back(box);
    } else if (sent != placing_.end()) {
      placed.push_back(sent->second);  // where it goes: taken for the next ones
    } else {
      unplaced[name] = box;
    }
  }
  if (unplaced.empty()) return;
  double right = 0, top = 0;  // beside what has a place
  for (const Box& b : placed) right = std::max(right, b.x + b.width + 80);
  for (const Box& b : placed) top = std::min(top, b.y);
  auto at = layeredLayout(unplaced, editor_->scene()->edges());
  for (auto& [name, p] : at) {
    const Box& b = unplaced[name];
    const Box free = freePlace({right + p.first, top + p.second, b.width, b.height}, placed);
    placed.push_back(free);
    p = {free.x, free.y};
  }
  place(at);
}

void PanelWidget::reservePlaces(const std::vector<Call>& calls) {
  // A node an edit adds shows before its set_ui is applied: placeUnplaced must not place it again.
  const auto shown = editor_->scene()->boxes();
  for (const auto& call : calls)
    if (const auto* ui = std::get_if<apex::SetUi::Request>(&call.request)) {
      if (placing_.count(ui->node)) continue;  // placed with its type's size already (addRequested)
      const auto [x, y] = GraphModel::positionIn(ui->ui);
      const auto box = shown.find(ui->node);
      placing_[ui->node] =
          Box{x, y, box == shown.end() ? NodeItem::kMinWidth : box->second.width, box == shown.end() ? 150 : box->second.height};
    }
}

void PanelWidget::untangleLoaded() {
  untangle_from_ = 0;
  untangle_ = true;
  arrangeShown();
}

void PanelWidget::arrangeShown() {
  const auto sent = placements_sent_;
  placeUnplaced();
  if (placements_sent_ == sent) pushDownUnderGrown();
  else rememberSizes();  // boxes being placed: pushed down from where they go, next time
}

void PanelWidget::rememberSizes() { sizes_ = editor_->scene()->boxes(); }

void PanelWidget::pushDownUnderGrown() {
  const auto boxes = editor_->scene()->boxes();
  bool grew_onto = false;  // a box that grew (its node's name, ports or parameters changed) and now lies on another
  for (const auto& [name, box] : boxes) {
    const auto before = sizes_.find(name);
    if (before == sizes_.end() || (box.height <= before->second.height + 0.5 && box.width <= before->second.width + 0.5))
      continue;
    for (const auto& [other, b] : boxes) grew_onto = grew_onto || (other != name && box.overlaps(b));
  }
  rememberSizes();
  if (grew_onto) place(pushDown(boxes));
}

void PanelWidget::place(const std::map<std::string, std::pair<double, double>>& positions) {
  auto edit = model_.arrange(positions, "");
  if (!edit) return;
  ++placements_sent_;
  const auto boxes = editor_->scene()->boxes();
  for (const auto& [name, p] : positions) {
    auto b = boxes.find(name);
    placing_[name] = Box{p.first, p.second, b == boxes.end() ? NodeItem::kMinWidth : b->second.width,
                         b == boxes.end() ? 120 : b->second.height};
  }
  link_.run(std::move(edit->apply), [this](bool ok, const std::string& m) {
    if (!ok) report(false, m, "placing nodes");
  });
}

QString PanelWidget::presetFolder() { return GraphEditor::defaultGraphFolder() + "presets"; }

Box PanelWidget::typeBox(const std::string& type) const {
  const auto t = types_.find(type);
  if (t == types_.end()) return Box{0, 0, NodeItem::kMinWidth, 150};  // a usual box
  // as a new node of the type is shown: its ports (with those of parameters that have ports by
  // default), its parameters at their defaults
  const QRectF r = NodeItem(GraphModel::newNode(t->second)).boundingRect();
  return Box{0, 0, r.width(), r.height()};
}

}  // namespace apex_rviz_plugin
