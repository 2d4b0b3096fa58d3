// PanelWidget, the editor's requests that become edits: each handler turns one signal of the
// editor or its scene (connected in connectEdits) into an edit of the model, made through
// perform(): sent to the runtime, recorded in the history once it accepts it.
#include "apex_rviz_plugin/panel_widget.hpp"

#include <QClipboard>
#include <QGuiApplication>

#include <algorithm>
#include <variant>

namespace apex_rviz_plugin {
namespace {

std::vector<std::string> stdNames(const QStringList& nodes) {
  std::vector<std::string> out;
  for (const auto& n : nodes) out.push_back(n.toStdString());
  return out;
}

}  // namespace

void PanelWidget::connectEdits() {
  GraphEditor* e = editor_;
  GraphScene* s = e->scene();
  connect(e, &GraphEditor::addRequested, this, &PanelWidget::onAddRequested);
  connect(e, &GraphEditor::addLinkedRequested, this, &PanelWidget::onAddLinkedRequested);
  connect(e, &GraphEditor::insertNewRequested, this, &PanelWidget::onInsertNewRequested);
  connect(e, &GraphEditor::removeRequested, this, &PanelWidget::onRemoveRequested);
  connect(e, &GraphEditor::groupIntoSubgraphRequested, this, &PanelWidget::onGroupIntoSubgraphRequested);
  connect(e, &GraphEditor::ungroupRequested, this, &PanelWidget::onUngroupRequested);
  connect(e, &GraphEditor::duplicateRequested, this, &PanelWidget::onDuplicateRequested);
  connect(e, &GraphEditor::copyRequested, this, &PanelWidget::onCopyRequested);
  connect(e, &GraphEditor::pasteRequested, this, &PanelWidget::onPasteRequested);
  connect(e, &GraphEditor::renameRequested, this, &PanelWidget::onRenameRequested);
  connect(e, &GraphEditor::resetRequested, this, &PanelWidget::onResetRequested);
  connect(e, &GraphEditor::enabledRequested, this, &PanelWidget::onEnabledRequested);
  connect(e, &GraphEditor::groupRequested, this, &PanelWidget::onThreadGroupRequested);
  connect(s, &GraphScene::connectRequested, this, &PanelWidget::onConnectRequested);
  connect(s, &GraphScene::disconnectRequested, this, &PanelWidget::onDisconnectRequested);
  connect(s, &GraphScene::parameterEdited, this, &PanelWidget::onParameterEdited);
  connect(s, &GraphScene::interactiveToggled, this, &PanelWidget::onInteractiveToggled);
  connect(s, &GraphScene::nodeMoved, this, &PanelWidget::onNodeMoved);
  connect(s, &GraphScene::expandToggled, this, &PanelWidget::onExpandToggled);
  connect(e, &GraphEditor::pinRequested, this, &PanelWidget::onPinRequested);
  connect(s, &GraphScene::insertRequested, this, &PanelWidget::onInsertRequested);
  connect(e, &GraphEditor::optimiseRequested, this, &PanelWidget::onOptimiseRequested);
  connect(e, &GraphEditor::applyBestRequested, this, &PanelWidget::onApplyBestRequested);
  connect(e, &GraphEditor::applyFrontPointRequested, this, &PanelWidget::onApplyFrontPointRequested);
}

void PanelWidget::perform(const std::optional<Edit>& edit) {
  if (!edit) return editor_->showMessage("that node or parameter is no longer in the graph", true);
  placement_.reserve(edit->apply);
  announceMoves(edit->apply);
  history_.sent();
  link_.run(edit->apply, [this, edit = *edit, epoch = history_.epoch()](bool ok, const std::string& message) {
    history_.answered(edit, ok, epoch);
    if (ok) model_.took(edit.apply);  // a ui edit right after builds on this one
    if (ok && GraphModel::regroups(edit.apply)) inspectAgain();  // the runtime ended every inspection
    if (!ok) placement_.release(edit.apply);  // its places are free again
    report(ok, message, QString::fromStdString(edit.label));
    if (!ok) editor_->showGraph(model_);  // widgets back to the values the runtime holds
    while (const auto undo = history_.nextWaiting()) historyStep(*undo);  // the undos and redos asked for meanwhile
  });
}

void PanelWidget::pasted(const Pasted& p) {
  if (!p.edit) return editor_->showMessage(QString::fromStdString(p.error), true);
  QStringList names;
  for (const auto& n : p.names) names << QString::fromStdString(n);
  editor_->selectWhenShown(names);  // the copies, not the originals: Delete and Ctrl+D act on them
  perform(p.edit);
  if (!p.error.empty()) editor_->showMessage(QString::fromStdString(p.error), true);
}

void PanelWidget::onAddRequested(const QString& type_name, QPointF at) {
  const std::string type = type_name.toStdString();
  const auto [path, free] = placement_.placeNew(type, typeBox(type), at);
  editor_->reveal(QRectF(free.x, free.y, free.width, free.height));  // a free place may be below the view
  perform(model_.addNode(type, path, free.x, free.y));
}

void PanelWidget::onAddLinkedRequested(const QString& type_name, QPointF at, const apex::Connection& link) {
  const std::string type = type_name.toStdString();
  const bool feeds = link.from_node.empty();  // the new node is the link's source: left of where it was let go
  const auto [path, free] =
      placement_.placeNew(type, typeBox(type), at - QPointF(0, 40), feeds);  // its first ports about level with `at`
  apex::Connection c = link;
  (feeds ? c.from_node : c.to_node) = path;
  perform(model_.addLinked(type, path, free.x, free.y, c));
}

void PanelWidget::onInsertNewRequested(const QString& type_name, QPointF at, const apex::Connection& link, const QString& in,
                                       const QString& out) {
  const std::string type = type_name.toStdString();
  const Box size = typeBox(type);
  const auto [path, free] =
      placement_.placeNew(type, size, at - QPointF(size.width / 2, size.height / 2));  // centred between the two
  editor_->reveal(QRectF(free.x, free.y, free.width, free.height));  // a free place may be below the view
  perform(model_.addInserted(type, path, free.x, free.y, link, in.toStdString(), out.toStdString()));
}

void PanelWidget::onRemoveRequested(const QString& node) { perform(model_.removeNode(node.toStdString())); }

void PanelWidget::onGroupIntoSubgraphRequested(const QStringList& nodes) { perform(model_.group(stdNames(nodes))); }

void PanelWidget::onUngroupRequested(const QString& subgraph) { perform(model_.ungroup(subgraph.toStdString())); }

std::map<std::string, std::pair<double, double>> PanelWidget::shownPositions() const {
  std::map<std::string, std::pair<double, double>> at;
  for (const auto& [name, box] : editor_->scene()->boxes()) at[name] = {box.x, box.y};
  return at;
}

void PanelWidget::onDuplicateRequested(const QStringList& nodes) {
  if (!nodes.isEmpty()) pasted(model_.duplicate(stdNames(nodes), 40, 40, shownPositions()));
}

void PanelWidget::onCopyRequested(const QStringList& nodes) {
  if (nodes.isEmpty()) return;
  std::string left_out;
  QGuiApplication::clipboard()->setText(QString::fromStdString(model_.copy(stdNames(nodes), &left_out, shownPositions())));
  if (!left_out.empty())
    return editor_->showMessage(QString::fromStdString(left_out + " is an inline subgraph: save it to a file to copy it"), true);
  editor_->showMessage(nodes.size() == 1 ? "copied " + nodes.front() : QString("copied %1 nodes").arg(nodes.size()), false);
}

void PanelWidget::onPasteRequested(QPointF at) {
  const std::string text = QGuiApplication::clipboard()->text().toStdString();
  const std::string& level = editor_->scene()->level();
  Pasted p = model_.paste(text, level, at.x(), at.y());
  if (!p.edit) return pasted(p);
  Box group{at.x(), at.y(), 0, 0};  // where the copies go, as boxes of a usual size
  for (const auto& call : p.edit->apply)
    if (const auto* ui = std::get_if<apex::SetUi::Request>(&call.request)) {
      const auto [x, y] = GraphModel::positionIn(ui->ui);
      group.width = std::max(group.width, x + NodeItem::kMinWidth - at.x());
      group.height = std::max(group.height, y + 150 - at.y());
    }
  const Box free = freePlace(group, placement_.takenPlaces());  // not on top of what is there
  pasted(free.x == at.x() && free.y == at.y() ? p : model_.paste(text, level, free.x, free.y));
}

void PanelWidget::onRenameRequested(const QString& node, const QString& new_name) {
  perform(model_.rename(node.toStdString(), new_name.toStdString()));
}

void PanelWidget::onResetRequested(const QString& node, const QString& param) {
  perform(model_.resetToDefault(node.toStdString(), param.toStdString()));
}

void PanelWidget::onEnabledRequested(const QString& node, bool enabled) {
  perform(model_.setEnabled(node.toStdString(), enabled));
}

void PanelWidget::onThreadGroupRequested(const QString& node, const QString& group) {
  perform(model_.setThreadGroup(node.toStdString(), group.toStdString()));
}

void PanelWidget::onConnectRequested(const apex::Connection& c) { perform(model_.connect(c)); }

void PanelWidget::onDisconnectRequested(const apex::Connection& c) { perform(model_.disconnect(c)); }

void PanelWidget::onParameterEdited(const QString& node, const QString& param, const QString& yaml, bool dragging) {
  perform(model_.setParameter(node.toStdString(), param.toStdString(), yaml.toStdString(), dragging));
}

void PanelWidget::onInteractiveToggled(const QString& node, const QString& param, bool interactive) {
  perform(model_.setInteractive(node.toStdString(), param.toStdString(), interactive));
}

void PanelWidget::onNodeMoved(const QString& node, QPointF at) { perform(model_.move(node.toStdString(), at.x(), at.y())); }

void PanelWidget::onExpandToggled(const QString& node, bool expanded) {
  perform(model_.setExpanded(node.toStdString(), expanded));
}

void PanelWidget::onPinRequested(const QString& node, const QString& param, bool pinned) {
  perform(model_.setPinned(node.toStdString(), param.toStdString(), pinned));
}

void PanelWidget::onInsertRequested(const QString& node, const apex::Connection& c, QPointF at) {
  perform(model_.insert(node.toStdString(), c, at.x(), at.y()));
}

void PanelWidget::onOptimiseRequested(const QString& node, const QString& param, const QString& optimizer) {
  // The Optimizer type as the runtime listed it: a new dimension is named after none of its ports or parameters.
  const auto t = types_.find(kOptimizerType);
  const apex::NodeTypeInfo* type = t == types_.end() ? nullptr : &t->second;
  if (optimizer.isEmpty() && !type)
    return editor_->showMessage("the runtime has not listed an Optimizer node type: no new Optimizer", true);
  const auto [x, y] = model_.position(node.toStdString());
  perform(model_.optimise(node.toStdString(), param.toStdString(), optimizer.toStdString(), x, y + 320, type));
}

void PanelWidget::onApplyBestRequested(const QString& optimizer) {
  const auto edit = model_.applyBest(optimizer.toStdString());
  if (!edit) return editor_->showMessage(optimizer + " has no best values yet: run it first", true);
  perform(edit);
}

void PanelWidget::onApplyFrontPointRequested(const QString& optimizer, int evaluation) {
  const auto edit = model_.applyFrontPoint(optimizer.toStdString(), evaluation);
  if (!edit)
    return editor_->showMessage(optimizer + ": its front has no evaluation " + QString::number(evaluation) + " now", true);
  perform(edit);
}

}  // namespace apex_rviz_plugin
