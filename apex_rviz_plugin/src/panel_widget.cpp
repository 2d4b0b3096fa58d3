#include "apex_rviz_plugin/panel_widget.hpp"

#include <QPointer>
#include <QDir>
#include <QFileInfo>
#include <QGraphicsView>
#include <QSaveFile>
#include <QTimer>
#include <QToolButton>
#include <QVBoxLayout>

#include "apex_rviz_plugin/histogram_view.hpp"
#include "apex_rviz_plugin/recovery_bar.hpp"
#include "apex_rviz_plugin/rviz_displays.hpp"

namespace apex_rviz_plugin {

PanelWidget::PanelWidget(QWidget* parent) : QWidget(parent), editor_(new GraphEditor) {
  auto* column = new QVBoxLayout(this);
  column->setContentsMargins(0, 0, 0, 0);
  column->addWidget(recovery_ = new RecoveryBar);
  column->addWidget(editor_);
  connect(recovery_, &RecoveryBar::restoreRequested, this, &PanelWidget::onRecoveryRestore);
  connect(recovery_, &RecoveryBar::discardRequested, this, &PanelWidget::onRecoveryDiscard);
  connect(&link_, &RuntimeLink::graphReceived, this, &PanelWidget::onGraph);
  connect(&link_, &RuntimeLink::statusReceived, this, [this](const apex::RuntimeStatus& s) {
    editor_->scene()->showStatus(s);
    editor_->showUnsaved(s.unsaved);
    editor_->showTracing(s.tracing);
    emit statusShown();
  });
  connect(&link_, &RuntimeLink::scalarReceived, editor_->scene(), &GraphScene::showValue);
  connect(&link_, &RuntimeLink::imageReceived, editor_->scene(), &GraphScene::showImage);
  connect(&link_, &RuntimeLink::aboutReceived, editor_->scene(), &GraphScene::showAbout);
  connect(&link_, &RuntimeLink::frameReceived, this, &PanelWidget::onFrameReceived);  // panel_labels.cpp
  connect(&link_, &RuntimeLink::frameReceived, this, &PanelWidget::onTrackerFrame);  // panel_tracker.cpp
  preview_timer_ = new QTimer(this);
  connect(preview_timer_, &QTimer::timeout, this, &PanelWidget::updatePreviews);
  connect(&link_, &RuntimeLink::answerOverdue, this, [this](const QString& text) { editor_->showConnection(true, text); });
  connect(&link_, &RuntimeLink::connectionChanged, this, [this](bool up, const QString& text) {
    editor_->showConnection(up, text);
    if (!up) return forgetRuntime(), recovery_->withdraw();  // a runtime that comes back starts anew
    meetRuntime();
  });
  // Killed, or stuck: said, and what is shown stays (a stuck one may speak again, the same runtime).
  connect(&link_, &RuntimeLink::silenceChanged, this,
          [this](bool silent, const QString& text) { editor_->showConnection(!silent, text); });
  connect(&link_, &RuntimeLink::runtimeReplaced, this, [this] {  // killed and started again, between two heartbeats
    forgetRuntime();
    meetRuntime();
  });
  connectEditor();
}

void PanelWidget::setNamespace(const QString& ns) {
  const bool changed = link_.setNamespace(ns.toStdString());
  editor_->setNamespace(QString::fromStdString(link_.ns()));  // a refused one goes back to the current
  if (!changed) return;
  model_.reset();
  watched_.clear();
  inspected_.clear();
  previewing_.clear();  // the link dropped its subscriptions with the namespace
  pending_ = 0, replaying_ = 0;  // and drops the answers of the runtime left: nothing of it is waited for
  placing_.clear(), sizes_.clear(), untangle_from_ = 0;
  forgetHistory();
  recovery_->withdraw();  // the runtime left's copy: the new one is asked once connected
  editor_->showGraph(model_);
  emit namespaceChanged(QString::fromStdString(link_.ns()));
}

void PanelWidget::connectEditor() {
  GraphEditor* e = editor_;
  GraphScene* s = e->scene();
  // edits of the model (panel_edits.cpp)
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
  connect(e, &GraphEditor::tidyRequested, this, &PanelWidget::tidy);  // panel_placement.cpp
  connect(e, &GraphEditor::balanceRequested, this, &PanelWidget::balance);  // panel_placement.cpp
  // the namespace, the history, the runtime's controls and files
  connect(e, &GraphEditor::namespaceChanged, this, &PanelWidget::onNamespaceEdited);
  connect(e, &GraphEditor::undoRequested, this, &PanelWidget::onUndoRequested);
  connect(e, &GraphEditor::redoRequested, this, &PanelWidget::onRedoRequested);
  connect(e, &GraphEditor::controlRequested, this, &PanelWidget::onControlRequested);
  connect(s, &GraphScene::slotFired, e, &GraphEditor::fireSlotRequested);  // a player's transport bar
  connect(e, &GraphEditor::fireSlotRequested, this, &PanelWidget::onFireSlotRequested);
  connect(e, &GraphEditor::saveRequested, this, &PanelWidget::onSaveRequested);
  connect(e, &GraphEditor::loadRequested, this, &PanelWidget::onLoadRequested);
  connect(e, &GraphEditor::traceRequested, this, [this](const QString& command, const QString& path, double seconds) {
    link_.trace(command.toStdString(), path.toStdString(), seconds, [this, command](bool ok, const std::string& m, bool on) {
      if (!ok) return report(ok, m, "trace " + command);
      editor_->showTracing(on);
      editor_->showMessage(QString::fromStdString(m), false);
    });
  });
  connect(e, &GraphEditor::profileRequested, this, &PanelWidget::showProfile);
  connect(e, &GraphEditor::newRequested, this, &PanelWidget::onNewRequested);
  connect(e, &GraphEditor::typesRequested, this, &PanelWidget::refreshTypes);
  // what is shown: inspections, previews, presets, the level
  connect(e, &GraphEditor::inspectRequested, this, &PanelWidget::onInspect);
  connect(e, &GraphEditor::labelRequested, this, &PanelWidget::labelFrames);
  connect(e, &GraphEditor::trackerStartRequested, this, &PanelWidget::startTrackerOnDrawnBox);
  connect(e, &GraphEditor::previewsToggled, this, &PanelWidget::onPreviewsToggled);
  connect(e, &GraphEditor::presetSaveRequested, this, &PanelWidget::savePreset);
  connect(e, &GraphEditor::presetRestoreRequested, this, &PanelWidget::onPresetRestoreRequested);
  connect(e, &GraphEditor::presetCompareRequested, this, &PanelWidget::onPresetCompareRequested);
  listPresets();
  connect(s, &GraphScene::levelChanged, this, &PanelWidget::onLevelChanged);
}

void PanelWidget::onNamespaceEdited(const QString& ns) {
  if (ns.toStdString() != link_.ns()) setNamespace(ns);
}

void PanelWidget::onUndoRequested() { historyStep(true); }

void PanelWidget::onRedoRequested() { historyStep(false); }

void PanelWidget::historyStep(bool undo) {
  if (pending_ > 0) return waiting_steps_.push_back(undo);  // the edit it would undo is not in the history yet
  const std::string label = undo ? history_.undoLabel() : history_.redoLabel();  // the step's own name
  replay(undo ? history_.undo() : history_.redo(), undo, label);
}

void PanelWidget::onControlRequested(const QString& command) {
  link_.control(command.toStdString(), [this, command](bool ok, const std::string& m) { report(ok, m, command); });
}

void PanelWidget::onFireSlotRequested(const QString& node, const QString& slot) {
  link_.fireSlot(node.toStdString(), slot.toStdString(),
                 [this, node, slot](bool ok, const std::string& m) { report(ok, m, "fire " + node + "/" + slot); });
}

void PanelWidget::onSaveRequested(const QString& path) {
  link_.saveGraph(path.toStdString(), [this, path](bool ok, const std::string& m) { report(ok, m, "saved " + path); });
}

void PanelWidget::onLoadRequested(const QString& path) {
  const auto done = replacingGraph("loaded " + path);
  link_.loadGraph(path.toStdString(), [this, done](bool ok, const std::string& m, std::uint64_t revision) {
    done(ok, m);
    if (!ok) return;
    // Positions written for other box sizes (by hand, another panel) are laid out again once the
    // loaded graph is shown (its revision or a later one): now, or when its ~graph comes.
    untangle_from_ = revision;
    if (model_.graph().revision >= revision) untangleLoaded();
  });
}

void PanelWidget::onNewRequested() { link_.control("clear", replacingGraph("new graph")); }

void PanelWidget::onPreviewsToggled(bool on) {
  previews_ = on;
  if (on) preview_timer_->start(300);
  else preview_timer_->stop();
  updatePreviews();
  if (on) place(pushDown(editor_->scene()->boxes()));  // the boxes grew: none lies on another
}

void PanelWidget::onPresetRestoreRequested(const QString& name) {
  const std::string text = readPreset(name);
  if (text.empty()) return;
  std::string error;
  auto edit = model_.restore(text, name.toStdString(), &error);
  if (!edit)
    return editor_->showMessage(
        error.empty() ? "the parameters are as preset " + name + " has them already" : QString::fromStdString(error),
        !error.empty());
  perform(edit);
}

void PanelWidget::onPresetCompareRequested(const QString& name) {
  const std::string text = readPreset(name);
  if (text.empty()) return;
  std::string error;
  const auto changes = model_.compare(text, &error);
  if (!error.empty()) return editor_->showMessage(QString::fromStdString(error), true);
  QString out = changes.empty() ? "Every parameter is as the preset has it." : "now -> preset " + name + ":\n";
  for (const auto& c : changes)
    out += QString::fromStdString("\n" + c.node + "/" + c.param + ": " + (c.now.empty() ? "(not in the graph)" : c.now) + " -> " +
                                  c.then);
  editor_->showPresetDiff(name, out);
}

void PanelWidget::onLevelChanged() {
  untangle_ = true;
  QTimer::singleShot(0, this, [this] { placeUnplaced(); });  // once the level's nodes are shown
}

void PanelWidget::replay(std::vector<Call> calls, bool undo, const std::string& label) {
  editor_->showHistory(QString::fromStdString(history_.undoLabel()), history_.canUndo(), history_.canRedo());
  if (calls.empty()) return;
  announceMoves(calls);
  ++replaying_;
  redo_base_.reset();
  const bool regroups = GraphModel::regroups(calls);
  link_.runThenRead(std::move(calls),
                    [this, undo, label, regroups](bool ok, const std::string& m, const apex::GraphState& after) {
                      if (ok && regroups) inspectAgain();
                      stepDone(undo, label, ok, m, after);
                    });
}

void PanelWidget::announceMoves(const std::vector<Call>& calls) {
  for (const auto& [from, to] : model_.moves(calls)) {
    emit renameSent(QString::fromStdString(from), QString::fromStdString(to));
    std::set<std::pair<std::string, std::string>> followed;  // the ports inspected, under the names they will have
    for (const auto& [node, port] : inspected_) {
      const bool inside = node.size() > from.size() && node.compare(0, from.size() + 1, from + "/") == 0;
      followed.insert({node == from || inside ? to + node.substr(from.size()) : node, port});
    }
    inspected_ = std::move(followed);
  }
}

void PanelWidget::listPresets() {
  QStringList names;
  for (const QFileInfo& f : QDir(presetFolder()).entryInfoList({"*.yaml"}, QDir::Files, QDir::Name))
    names << f.completeBaseName();
  editor_->showPresets(names);
}

void PanelWidget::savePreset(const QString& name, const QStringList& nodes) {
  if (name.contains('/') || name.startsWith('.'))
    return editor_->showMessage("a preset's name cannot hold '/' or start with '.': " + name, true);
  std::vector<std::string> names;
  for (const auto& n : nodes) names.push_back(n.toStdString());
  QDir().mkpath(presetFolder());
  QSaveFile file(presetFolder() + "/" + name + ".yaml");  // whole or not at all
  const std::string text = model_.preset(names) + "\n";
  if (!file.open(QIODevice::WriteOnly) || file.write(text.data(), static_cast<qint64>(text.size())) < 0 || !file.commit())
    return editor_->showMessage("cannot save preset " + name + ": " + file.errorString(), true);
  listPresets();
  editor_->showMessage("saved preset " + name + " in " + presetFolder(), false);
}

std::string PanelWidget::readPreset(const QString& name) {
  QFile file(presetFolder() + "/" + name + ".yaml");
  if (!file.open(QIODevice::ReadOnly)) {
    editor_->showMessage("cannot read preset " + name + ": " + file.errorString(), true);
    return "";
  }
  return file.readAll().toStdString();
}

void PanelWidget::setPreviews(bool on) {
  if (auto* b = editor_->findChild<QToolButton*>("previews")) b->setChecked(on);  // its toggle does the rest
}

void PanelWidget::updatePreviews() {
  QGraphicsView* view = editor_->view();
  const QRectF seen = view->mapToScene(view->viewport()->rect()).boundingRect();
  std::set<std::string> wanted;
  for (const auto& [name, item] : editor_->scene()->nodes()) {
    item->setPreviews(previews_);
    if (!previews_ || !seen.intersects(item->sceneBoundingRect())) continue;  // out of view: not previewed
    for (const auto& port : item->previewPorts()) wanted.insert(name + "/" + port);
  }
  for (auto it = previewing_.begin(); it != previewing_.end();) {  // no longer wanted: unsubscribed
    if (wanted.count(*it)) {
      ++it;
      continue;
    }
    const auto slash = it->rfind('/');
    link_.unwatchPreview(it->substr(0, slash), it->substr(slash + 1));
    it = previewing_.erase(it);
  }
  for (const auto& key : wanted) {
    if (!previewing_.insert(key).second) continue;
    const auto slash = key.rfind('/');
    const std::string node = key.substr(0, slash), port = key.substr(slash + 1);
    link_.inspect(
        node, port,
        [this, node, port, key](bool ok, const std::string&, const std::string& topic, const std::string& type) {
          if (ok) editor_->showMessageType(QString::fromStdString(node), QString::fromStdString(port), type);
          if (!ok || !previewing_.count(key) || !previews_) return previewing_.erase(key), void();
          link_.watchPreview(node, port, topic, type);
        },
        true);
  }
}

void PanelWidget::forgetHistory() {
  history_.clear();
  waiting_steps_.clear();
  ++history_epoch_;
  editor_->showHistory("", false, false);
}

std::function<void(bool, const std::string&)> PanelWidget::replacingGraph(const QString& what) {
  // A fresh history from the request on: the link runs calls in order, so an edit asked for
  // after this one is an edit of the new graph, even if its answer comes first.
  auto before = std::make_shared<EditHistory>(history_);
  forgetHistory();
  placing_.clear();  // of nodes of the graph before; a node added after this request keeps its place
  sizes_.clear();
  untangle_from_ = 0;
  return [this, what, before](bool ok, const std::string& message) {
    report(ok, message, what);
    if (ok) return inspectAgain();
    if (!history_.canUndo() && !history_.canRedo()) {  // refused, and nothing done since: the old history stands
      history_ = *before;
      editor_->showHistory(QString::fromStdString(history_.undoLabel()), history_.canUndo(), history_.canRedo());
    }
  };
}

void PanelWidget::inspectAgain() {
  for (const auto& key : previewing_) link_.unwatchPreview(key.substr(0, key.rfind('/')), key.substr(key.rfind('/') + 1));
  previewing_.clear();  // a load ends the runtime's previews: asked for again by the next update
  watched_.clear();  // a load, group or ungroup ends every inspection: the Optimizers' progress and the displays
  watchOptimizers();  // the loaded graph may be shown already: no other ~graph may follow
  for (const auto& [node, port] : inspected_)  // displays showing a port go on if the new graph has it
    link_.inspect(node, port, [](bool, const std::string&, const std::string&, const std::string&) {});
  watchLabelledAgain();
}

void PanelWidget::report(bool ok, const std::string& message, const QString& what) {
  editor_->showMessage(ok ? what : what + " refused: " + QString::fromStdString(message), !ok);
}

void PanelWidget::forgetRuntime() {
  model_.reset(), watched_.clear(), previewing_.clear(), forgetHistory();
  editor_->showUnsaved(false);
}

void PanelWidget::meetRuntime() {
  refreshTypes(), editor_->fitNextGraph(), untangle_ = true;
  askRecovery();  // a copy its previous run left: the bar at once
  watchLabelledAgain();  // a runtime started anew inspects nothing
  // Its graph as it is now: the latched ~graph may have come before this (and no other until it changes).
  readGraph(40);
}

void PanelWidget::readGraph(int tries) {
  link_.runThenRead({}, [this, tries](bool, const std::string&, const apex::GraphState& g) {
    // (A restarted runtime's latched ~graph may have come before the status that said it was a new
    // one, which reset what was shown: its graph at revision 0 must be taken from here then.)
    if (answered(g)) return onGraph(g);
    if (tries > 0 && link_.connected() && !model_.hasGraph())
      QTimer::singleShot(250, this, [this, tries] { readGraph(tries - 1); });
  });
}

void PanelWidget::onGraph(const apex::GraphState& graph) {
  if (!model_.update(graph)) {
    if (graph.revision >= model_.graph().revision) return;
    model_.reset();  // older than what is shown: a restarted runtime
    forgetHistory();
    model_.update(graph);
    askRecovery();
  }
  editor_->showGraph(model_);
  dropRedoIfEditedElsewhere();
  if (untangle_from_ && graph.revision >= untangle_from_) untangleLoaded();
  else arrangeShown();
  watchOptimizers();
  emit graphShown(graph.revision);
}

void PanelWidget::watchOptimizers() {
  for (const auto& name : model_.optimizers()) {
    if (!watched_.insert(name).second) continue;
    for (const char* port : {"evaluations", "best_fitness"})  // the node's box draws its progress from them
      link_.inspect(name, port,
                    [this, name, port](bool ok, const std::string& m, const std::string& topic, const std::string& type) {
                      if (!ok) return report(false, m, QString::fromStdString("watch " + name + "/" + port));
                      link_.watchScalar(name, port, topic, type);
                    });
  }
}

void PanelWidget::refreshTypes() {
  link_.listTypes([this](bool ok, const std::string& message, const std::vector<apex::NodeTypeInfo>& types) {
    if (!ok) return report(false, message, "list node types");
    type_count_ = static_cast<int>(types.size());
    types_.clear();
    for (const auto& t : types) types_[t.id] = t;
    editor_->showTypes(types);
    if (!message.empty()) editor_->showMessage(QString::fromStdString("some node types are missing: " + message), true);
  });
}

void PanelWidget::onInspect(const QString& node, const QString& port) {
  inspected_.insert({node.toStdString(), port.toStdString()});
  link_.inspect(
      node.toStdString(), port.toStdString(),
      [this, node, port](bool ok, const std::string& m, const std::string& topic, const std::string& type) {
        if (!ok) return report(false, m, "inspect " + node + "/" + port);
        const QString t = QString::fromStdString(topic), name = node + "/" + port;
        editor_->showMessageType(node, port, type);  // for the port menu's "Show in rviz"
        if (rvizDisplayFor(type)) emit displayRequested(node, port, t, QString::fromStdString(type));
        else if (type.empty())  // a port of any type: its first message decides
          return report(
              true, "",
              node + "/" + port + " is published on " + t + " from its first message on; inspect it again then to see it here");
        else link_.watchScalar(node.toStdString(), port.toStdString(), topic, type);
        report(true, "", "inspecting " + name + " on " + t + (type.empty() ? "" : " (" + QString::fromStdString(type) + ")"));
      });
}

void PanelWidget::showProfile(const QString& node) {
  auto* view = findChild<HistogramView*>("histogram_" + node);
  if (!view) {
    view = new HistogramView(node, this);
    connect(view, &HistogramView::refreshRequested, this, [this, view = QPointer<HistogramView>(view)](const QString& name) {
      link_.profile(name.toStdString(), [view](bool ok, const std::string& m, const apex::GetNodeProfile::Response& res) {
        if (view) view->showProfile(ok, m, res);
      });
    });
  }
  view->show();
  view->raise();
}

}  // namespace apex_rviz_plugin
