// GraphEditor, adding where the person works and explaining what is added: the quick-add box at
// the cursor (Tab, Space, a double-click on empty canvas, a link let go on empty canvas; between
// two boxes for a link's "Insert node...") and the help window of a node type (a palette entry's
// F1 or menu, a node's menu or F1).
#include "apex_rviz_plugin/graph_editor.hpp"

#include <QCursor>
#include <QGraphicsView>

#include <map>

#include "apex_rviz_plugin/help_view.hpp"
#include "apex_rviz_plugin/quick_add.hpp"

#include <algorithm>

namespace apex_rviz_plugin {

QPointF GraphEditor::cursorPosition() const {
  const QRect port = view_->viewport()->rect();
  const QPoint cursor = view_->viewport()->mapFromGlobal(QCursor::pos());
  if (port.contains(cursor)) return view_->mapToScene(cursor);
  if (port.contains(last_mouse_)) return view_->mapToScene(last_mouse_);  // no cursor (offscreen), or it left the view
  return view_->mapToScene(port.center());
}

QuickAdd* GraphEditor::ensureQuickAdd() {
  if (quick_add_) return quick_add_;
  quick_add_ = new QuickAdd(this);
  connect(quick_add_, &QuickAdd::chosen, this, &GraphEditor::addChosen);
  connect(quick_add_, &QuickAdd::helpRequested, this, &GraphEditor::showTypeHelp);
  return quick_add_;
}

void GraphEditor::openQuickAdd(QPointF at) {
  if (types_.empty()) return showMessage("the runtime has listed no node types yet (Reload types)", true);
  std::vector<QuickAdd::Offer> offers;
  for (const auto& t : types_) offers.push_back({t, QString()});
  quick_at_ = at;
  quick_link_.reset(), quick_insert_.reset();
  ensureQuickAdd()->open(std::move(offers), view_->viewport()->mapToGlobal(view_->mapFromScene(at)), "Add a node here");
}

namespace {

/** The required inputs a new node of `type` would still lack with only its port `linked` fed (""
 *  none): the types that run with the one link are offered first (from a threshold's output,
 *  FindContours before DrawContours, which needs contours too). */
int stillNeeded(const apex::NodeTypeInfo& type, const QString& linked) {
  int n = 0;
  for (const auto& p : type.ports) n += p.kind == "input" && !p.optional && QString::fromStdString(p.name) != linked;
  return n;
}

}  // namespace

void GraphEditor::openLinkAdd(const QString& node, const QString& port, bool source, QPointF at) {
  if (!model_) return;
  const std::string n = node.toStdString(), p = port.toStdString();
  std::map<std::string, const apex::NodeTypeInfo*> by_id;
  for (const auto& t : types_) by_id[t.id] = &t;
  std::vector<QuickAdd::Offer> offers;
  for (const NewLink& l : model_->linkable(types_, n, p, source))
    offers.push_back({*by_id.at(l.type), QString::fromStdString(l.port)});
  std::stable_sort(offers.begin(), offers.end(), [source](const QuickAdd::Offer& a, const QuickAdd::Offer& b) {
    return stillNeeded(a.type, source ? a.port : "") < stillNeeded(b.type, source ? b.port : "");
  });
  const apex::PortInfo* info = model_->port(n, p, "");
  const QString what = node + "/" + port + (info && !info->type.empty() ? " (" + QString::fromStdString(info->type) + ")" : "");
  if (offers.empty()) return showMessage("no node type has a port that can be linked with " + what, true);
  apex::Connection link;  // its end at the new node: the port only, named when chosen
  if (source) link.from_node = n, link.from_port = p;
  else link.to_node = n, link.to_port = p;
  quick_at_ = at;
  quick_link_ = link, quick_insert_.reset();
  ensureQuickAdd()->open(std::move(offers), view_->viewport()->mapToGlobal(view_->mapFromScene(at)),
                         (source ? "Add a node fed by " : "Add a node feeding ") + what);
}

void GraphEditor::openInsertAdd(const apex::Connection& link) {
  if (!model_) return;
  const QString what = QString::fromStdString(link.from_node + "/" + link.from_port + " -> " + link.to_node + "/" + link.to_port);
  std::vector<QuickAdd::Offer> offers;
  quick_inserts_ = model_->insertable(types_, link);
  for (const NewInsert& i : quick_inserts_)
    if (const apex::NodeTypeInfo* t = listedType(i.type))
      offers.push_back({*t, QString::fromStdString(i.in + " \u2192 " + i.out)});
  if (offers.empty()) return showMessage("no node type can go into " + what, true);
  const NodeItem* from = scene_->node(link.from_node);
  const NodeItem* to = scene_->node(link.to_node);
  quick_at_ = from && to ? (from->sceneBoundingRect().center() + to->sceneBoundingRect().center()) / 2 : cursorPosition();
  quick_link_.reset(), quick_insert_ = link;
  ensureQuickAdd()->open(std::move(offers), view_->viewport()->mapToGlobal(view_->mapFromScene(quick_at_)),
                         "Insert a node into " + what);
}

void GraphEditor::addChosen(const QString& type, const QString& port) {
  if (quick_insert_) {
    for (const NewInsert& i : quick_inserts_)
      if (i.type == type.toStdString())
        emit insertNewRequested(type, quick_at_, *quick_insert_, QString::fromStdString(i.in), QString::fromStdString(i.out));
    return;
  }
  if (!quick_link_) return emit addRequested(type, quick_at_);
  apex::Connection link = *quick_link_;
  (link.from_node.empty() ? link.from_port : link.to_port) = port.toStdString();
  emit addLinkedRequested(type, quick_at_, link);
}

HelpView* GraphEditor::ensureHelp() {
  if (!help_) help_ = new HelpView(this);
  return help_;
}

const apex::NodeTypeInfo* GraphEditor::listedType(const std::string& id) const {
  for (const auto& t : types_)
    if (t.id == id) return &t;
  return nullptr;
}

void GraphEditor::showTypeHelp(const QString& type) {
  const apex::NodeTypeInfo* t = listedType(type.toStdString());
  if (!t) return showMessage("the runtime has not listed a node type " + type, true);
  ensureHelp()->showType(*t);
}

apex::NodeTypeInfo GraphEditor::typeOf(const apex::NodeInfo& node) const {
  if (const apex::NodeTypeInfo* t = node.subgraph.empty() ? listedType(node.type) : nullptr) return *t;
  apex::NodeTypeInfo t;  // what the node itself shows: its ports (parameters apart) and parameters
  t.id = node.type;
  t.description = node.subgraph.empty()       ? "(a type the runtime does not list: the ports and parameters the node has)"
                  : node.subgraph == "inline" ? "A subgraph written in the graph file: the ports and parameters it exports."
                                              : "A subgraph from " + node.subgraph + ": the ports and parameters it exports.";
  for (const auto& p : node.ports)
    if (p.kind != "param_in" && p.kind != "param_out") t.ports.push_back(p);
  t.parameters = node.parameters;
  return t;
}

void GraphEditor::showNodeHelp(const QString& node) {
  const apex::NodeInfo* info = model_ ? model_->node(node.toStdString()) : nullptr;
  if (!info) return;
  ensureHelp()->showType(typeOf(*info), node);
}

}  // namespace apex_rviz_plugin
