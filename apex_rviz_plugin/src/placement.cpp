// Where boxes go: new nodes on free places, a loaded graph laid out (graphviz), boxes that grew
// pushed off the ones below; positions are sent as set_ui outside the history, and reserved until
// the graph shows them. And where nodes run: Balance's thread groups, one edit.
#include "apex_rviz_plugin/placement.hpp"

#include <QTimer>

#include <algorithm>
#include <set>
#include <variant>

namespace apex_rviz_plugin {

void Placement::tidy() {
  const auto boxes = ctx_.editor.scene()->boxes();
  if (boxes.empty()) return;
  double left = 1e18, top = 1e18;
  std::map<std::string, std::pair<double, double>> shown;  // Undo puts back what the user saw
  for (const auto& [name, b] : boxes) left = std::min(left, b.x), top = std::min(top, b.y), shown[name] = {b.x, b.y};
  auto at = layeredLayout(boxes, ctx_.editor.scene()->edges());
  for (auto& [name, p] : at) p.first += left, p.second += top;
  emit editRequested(ctx_.model.arrange(at, "Tidy", shown));
}

void Placement::balance() {
  ctx_.editor.showMessage("Balance: asking the runtime for thread groups...", false);
  // The times measured so far (frames 0): the answer comes at once, and the call never waits for frames.
  ctx_.link.balance(0, 0, [this](bool ok, const std::string& m, const apex::Balance::Response& res) {
    if (!ok) return ctx_.report(false, m, "Balance");
    std::vector<std::pair<std::string, std::string>> moves;
    for (std::size_t i = 0; i < res.nodes.size() && i < res.groups.size(); ++i) moves.emplace_back(res.nodes[i], res.groups[i]);
    std::string text = res.message;
    for (const auto& note : res.notes) text += "; " + note;
    auto edit = ctx_.model.setThreadGroups(moves, "Balance: " + text);  // perform() shows the label once applied
    if (!edit)
      return ctx_.editor.showMessage(QString::fromStdString("Balance: the groups are so already. " + text), !res.notes.empty());
    emit editRequested(edit);
  });
}

std::pair<std::string, Box> Placement::placeNew(const std::string& type, const Box& size, QPointF at, bool left_of) {
  const std::string& inside = ctx_.editor.scene()->level();  // the subgraph shown gets the node
  std::set<std::string> sent;  // added a moment ago, not shown yet: their names are taken too
  for (const auto& [n, box] : placing_) sent.insert(n);
  const std::string name = ctx_.model.freshName(type, inside, sent);
  const std::string path = inside.empty() ? name : inside + "/" + name;
  Box wanted = size;  // as a new node of the type is shown
  wanted.x = left_of ? at.x() - wanted.width : at.x(), wanted.y = at.y();
  const Box free = freePlace(wanted, takenPlaces());  // on no other
  placing_[path] = free;
  return {path, free};
}

std::vector<Box> Placement::takenPlaces() const {
  const auto shown = ctx_.editor.scene()->boxes();
  std::vector<Box> taken;
  for (const auto& [n, box] : shown)
    if (!placing_.count(n)) taken.push_back(box);
  // Sent a place a moment ago: taken where it goes, not where it shows now (a ~graph between a
  // node's add_node and its set_ui shows it without a place), and at least as big as it shows.
  for (const auto& [n, box] : placing_) {
    Box b = box;
    if (const auto s = shown.find(n); s != shown.end())
      b.width = std::max(b.width, s->second.width), b.height = std::max(b.height, s->second.height);
    taken.push_back(b);
  }
  return taken;
}

void Placement::reserve(const std::vector<Call>& calls) {
  // A node an edit adds shows before its set_ui is applied: placeUnplaced must not place it again.
  const auto shown = ctx_.editor.scene()->boxes();
  for (const auto& call : calls)
    if (const auto* ui = std::get_if<apex::SetUi::Request>(&call.request)) {
      if (placing_.count(ui->node)) continue;  // placed with its type's size already (placeNew)
      const auto [x, y] = GraphModel::positionIn(ui->ui);
      const auto box = shown.find(ui->node);
      placing_[ui->node] =
          Box{x, y, box == shown.end() ? NodeItem::kMinWidth : box->second.width, box == shown.end() ? 150 : box->second.height};
    }
}

void Placement::release(const std::vector<Call>& calls) {
  for (const auto& call : calls)
    if (const auto* ui = std::get_if<apex::SetUi::Request>(&call.request)) placing_.erase(ui->node);
}

void Placement::graphShown(std::uint64_t revision) {
  if (untangle_from_ && revision >= untangle_from_) untangleLoaded();
  else arrangeShown();
}

void Placement::loaded(std::uint64_t revision) {
  // Positions written for other box sizes (by hand, another panel) are laid out again once the
  // loaded graph is shown (its revision or a later one): now, or when its ~graph comes.
  untangle_from_ = revision;
  if (ctx_.model.graph().revision >= revision) untangleLoaded();
}

void Placement::levelChanged() {
  untangle_ = true;
  QTimer::singleShot(0, this, [this] { placeUnplaced(); });  // once the level's nodes are shown
}

void Placement::pushApart() { place(pushDown(ctx_.editor.scene()->boxes())); }

void Placement::reset() {
  placing_.clear();  // of nodes of the graph before; a node added after this keeps its place
  sizes_.clear();
  untangle_from_ = 0;
}

bool Placement::untangle(const std::map<std::string, Box>& boxes) {
  if (!untangle_ || boxes.empty()) return false;  // positions written for other box sizes (by hand, another panel)
  untangle_ = false;
  bool overlap = false;
  for (auto a = boxes.begin(); a != boxes.end() && !overlap; ++a)
    for (auto b = std::next(a); b != boxes.end() && !overlap; ++b) overlap = a->second.overlaps(b->second);
  if (!overlap) return false;
  ctx_.editor.fitNextGraph();  // the view shows them where they go
  place(layeredLayout(boxes, ctx_.editor.scene()->edges()));
  return true;
}

void Placement::placeUnplaced() {
  const auto boxes = ctx_.editor.scene()->boxes();
  if (untangle(boxes)) return;
  std::map<std::string, Box> unplaced;
  std::vector<Box> placed;
  for (const auto& [name, box] : boxes) {
    auto sent = placing_.find(name);
    if (ctx_.model.hasPosition(name)) {
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
  auto at = layeredLayout(unplaced, ctx_.editor.scene()->edges());
  for (auto& [name, p] : at) {
    const Box& b = unplaced[name];
    const Box free = freePlace({right + p.first, top + p.second, b.width, b.height}, placed);
    placed.push_back(free);
    p = {free.x, free.y};
  }
  place(at);
}

void Placement::untangleLoaded() {
  untangle_from_ = 0;
  untangle_ = true;
  arrangeShown();
}

void Placement::arrangeShown() {
  const auto sent = placements_sent_;
  placeUnplaced();
  if (placements_sent_ == sent) pushDownUnderGrown();
  else rememberSizes();  // boxes being placed: pushed down from where they go, next time
}

void Placement::rememberSizes() { sizes_ = ctx_.editor.scene()->boxes(); }

void Placement::pushDownUnderGrown() {
  const auto boxes = ctx_.editor.scene()->boxes();
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

void Placement::place(const std::map<std::string, std::pair<double, double>>& positions) {
  auto edit = ctx_.model.arrange(positions, "");
  if (!edit) return;
  ++placements_sent_;
  const auto boxes = ctx_.editor.scene()->boxes();
  for (const auto& [name, p] : positions) {
    auto b = boxes.find(name);
    placing_[name] = Box{p.first, p.second, b == boxes.end() ? NodeItem::kMinWidth : b->second.width,
                         b == boxes.end() ? 120 : b->second.height};
  }
  ctx_.link.run(std::move(edit->apply), [this](bool ok, const std::string& m) {
    if (!ok) ctx_.report(false, m, "placing nodes");
  });
}

}  // namespace apex_rviz_plugin
