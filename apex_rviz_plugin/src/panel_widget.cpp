// PanelWidget: the parts joined. The runtime's signals and the editor's are connected here to the
// part that owns what they change; the model changes only in onGraph and forgetRuntime, and
// forgetRuntime is the one place that resets the parts when a runtime is gone or replaced.
#include "apex_rviz_plugin/panel_widget.hpp"

#include <QTimer>
#include <QVBoxLayout>

#include "apex_rviz_plugin/histogram_view.hpp"
#include "apex_rviz_plugin/recovery_bar.hpp"

namespace apex_rviz_plugin {

PanelWidget::PanelWidget(QWidget* parent)
    : QWidget(parent),
      editor_(new GraphEditor),
      ctx_{*editor_, model_, link_},
      history_(ctx_),
      placement_(ctx_),
      inspections_(ctx_),
      previews_(ctx_),
      presets_(ctx_),
      labels_(ctx_, this),
      tracker_(ctx_, labels_, this) {
  auto* column = new QVBoxLayout(this);
  column->setContentsMargins(0, 0, 0, 0);
  column->addWidget(recovery_ = new RecoveryBar);
  column->addWidget(editor_);
  connect(recovery_, &RecoveryBar::restoreRequested, this, &PanelWidget::onRecoveryRestore);
  connect(recovery_, &RecoveryBar::discardRequested, this, &PanelWidget::onRecoveryDiscard);
  connectLink();
  connectParts();
  connectEditor();
}

void PanelWidget::connectLink() {
  connect(&link_, &RuntimeLink::graphReceived, this, &PanelWidget::onGraph);
  connect(&link_, &RuntimeLink::statusReceived, this, &PanelWidget::onStatus);
  connect(&link_, &RuntimeLink::scalarReceived, editor_->scene(), &GraphScene::showValue);
  connect(&link_, &RuntimeLink::imageReceived, editor_->scene(), &GraphScene::showImage);
  connect(&link_, &RuntimeLink::aboutReceived, editor_->scene(), &GraphScene::showAbout);
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
}

void PanelWidget::connectParts() {
  connect(&placement_, &Placement::editRequested, this, &PanelWidget::perform);
  connect(&presets_, &PresetFiles::editRequested, this, &PanelWidget::perform);
  connect(&labels_, &LabelWindows::editRequested, this, &PanelWidget::perform);
  connect(&tracker_, &TrackerStarter::editRequested, this, &PanelWidget::perform);
  connect(&labels_, &LabelWindows::fireSlotRequested, this, &PanelWidget::onFireSlotRequested);
  connect(&tracker_, &TrackerStarter::fireSlotRequested, this, &PanelWidget::onFireSlotRequested);
  connect(&inspections_, &Inspections::displayRequested, this, &PanelWidget::displayRequested);
}

void PanelWidget::connectEditor() {
  GraphEditor* e = editor_;
  GraphScene* s = e->scene();
  connectEdits();  // edits of the model (panel_edits.cpp)
  connect(e, &GraphEditor::tidyRequested, &placement_, &Placement::tidy);
  connect(e, &GraphEditor::balanceRequested, &placement_, &Placement::balance);
  // the namespace, the history, the runtime's controls and files
  connect(e, &GraphEditor::namespaceChanged, this, &PanelWidget::onNamespaceEdited);
  connect(e, &GraphEditor::undoRequested, this, [this] { historyStep(true); });
  connect(e, &GraphEditor::redoRequested, this, [this] { historyStep(false); });
  connect(e, &GraphEditor::controlRequested, this, &PanelWidget::onControlRequested);
  connect(s, &GraphScene::slotFired, e, &GraphEditor::fireSlotRequested);  // a player's transport bar
  connect(e, &GraphEditor::fireSlotRequested, this, &PanelWidget::onFireSlotRequested);
  connect(e, &GraphEditor::saveRequested, this, &PanelWidget::onSaveRequested);
  connect(e, &GraphEditor::loadRequested, this, &PanelWidget::onLoadRequested);
  connect(e, &GraphEditor::traceRequested, this, &PanelWidget::onTraceRequested);
  connect(e, &GraphEditor::profileRequested, this, &PanelWidget::showProfile);
  connect(e, &GraphEditor::newRequested, this, &PanelWidget::onNewRequested);
  connect(e, &GraphEditor::typesRequested, this, &PanelWidget::refreshTypes);
  // what is shown: inspections, previews, presets, the level
  connect(e, &GraphEditor::inspectRequested, &inspections_, &Inspections::inspect);
  connect(e, &GraphEditor::labelRequested, &labels_, &LabelWindows::open);
  connect(e, &GraphEditor::trackerStartRequested, &tracker_, &TrackerStarter::start);
  connect(e, &GraphEditor::previewsToggled, this, &PanelWidget::onPreviewsToggled);
  connect(e, &GraphEditor::presetSaveRequested, &presets_, &PresetFiles::save);
  connect(e, &GraphEditor::presetRestoreRequested, &presets_, &PresetFiles::restore);
  connect(e, &GraphEditor::presetCompareRequested, &presets_, &PresetFiles::compare);
  presets_.list();
  connect(s, &GraphScene::levelChanged, &placement_, &Placement::levelChanged);
}

void PanelWidget::setNamespace(const QString& ns) {
  const bool changed = link_.setNamespace(ns.toStdString());
  editor_->setNamespace(QString::fromStdString(link_.ns()));  // a refused one goes back to the current
  if (!changed) return;
  forgetRuntime();
  // Leaving the namespace, beyond forgetting its runtime: the link dropped its subscriptions and
  // the answers of the runtime left (nothing of it is waited for), its displays and its copy go.
  history_.dropAnswers();
  inspections_.forgetPorts();
  recovery_->withdraw();  // the runtime left's copy: the new one is asked once connected
  editor_->showGraph(model_);
  emit namespaceChanged(QString::fromStdString(link_.ns()));
}

void PanelWidget::onNamespaceEdited(const QString& ns) {
  if (ns.toStdString() != link_.ns()) setNamespace(ns);
}

void PanelWidget::onControlRequested(const QString& command) {
  link_.control(command.toStdString(), [this, command](bool ok, const std::string& m) { report(ok, m, command); });
}

void PanelWidget::onFireSlotRequested(const QString& node, const QString& slot) {
  link_.fireSlot(node.toStdString(), slot.toStdString(),
                 [this, node, slot](bool ok, const std::string& m) { report(ok, m, "fire " + node + "/" + slot); });
}

void PanelWidget::onTraceRequested(const QString& command, const QString& path, double seconds) {
  link_.trace(command.toStdString(), path.toStdString(), seconds, [this, command](bool ok, const std::string& m, bool on) {
    if (!ok) return report(ok, m, "trace " + command);
    editor_->showTracing(on);
    editor_->showMessage(QString::fromStdString(m), false);
  });
}

void PanelWidget::onSaveRequested(const QString& path) {
  link_.saveGraph(path.toStdString(), [this, path](bool ok, const std::string& m) { report(ok, m, "saved " + path); });
}

void PanelWidget::onLoadRequested(const QString& path) {
  const auto done = replacingGraph("loaded " + path);
  link_.loadGraph(path.toStdString(), [this, done](bool ok, const std::string& m, std::uint64_t revision) {
    done(ok, m);
    if (ok) placement_.loaded(revision);
  });
}

void PanelWidget::onNewRequested() { link_.control("clear", replacingGraph("new graph")); }

void PanelWidget::onPreviewsToggled(bool on) {
  previews_.setOn(on);
  if (on) placement_.pushApart();  // the boxes grew: none lies on another
}

void PanelWidget::forgetRuntime() {
  model_.reset();
  history_.reset();
  placement_.reset();
  inspections_.reset();
  previews_.reset();
  editor_->showUnsaved(false);
}

void PanelWidget::meetRuntime() {
  refreshTypes(), editor_->fitNextGraph(), placement_.untangleNext();
  askRecovery();  // a copy its previous run left: the bar at once
  labels_.watchAgain();  // a runtime started anew inspects nothing
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
    forgetRuntime();  // older than what is shown: a restarted runtime
    model_.update(graph);
    askRecovery();
  }
  editor_->showGraph(model_);
  history_.dropRedoIfEditedElsewhere();
  placement_.graphShown(graph.revision);
  inspections_.watchOptimizers();
  emit graphShown(graph.revision);
}

void PanelWidget::onStatus(const apex::RuntimeStatus& s) {
  editor_->scene()->showStatus(s);
  editor_->showUnsaved(s.unsaved);
  editor_->showTracing(s.tracing);
  emit statusShown();
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

Box PanelWidget::typeBox(const std::string& type) const {
  const auto t = types_.find(type);
  if (t == types_.end()) return Box{0, 0, NodeItem::kMinWidth, 150};  // a usual box
  // as a new node of the type is shown: its ports (with those of parameters that have ports by
  // default), its parameters at their defaults
  const QRectF r = NodeItem(GraphModel::newNode(t->second)).boundingRect();
  return Box{0, 0, r.width(), r.height()};
}

void PanelWidget::historyStep(bool undo) {
  if (history_.deferred(undo)) return;
  PanelHistory::Step step = history_.take(undo);
  if (step.calls.empty()) return;
  announceMoves(step.calls);
  const bool regroups = GraphModel::regroups(step.calls);
  link_.runThenRead(std::move(step.calls),
                    [this, undo, label = step.label, regroups](bool ok, const std::string& m, const apex::GraphState& after) {
                      if (ok && regroups) inspectAgain();
                      history_.stepDone(undo, label, ok, m, after);
                    });
}

void PanelWidget::announceMoves(const std::vector<Call>& calls) {
  for (const auto& [from, to] : model_.moves(calls)) {
    emit renameSent(QString::fromStdString(from), QString::fromStdString(to));
    inspections_.follow(from, to);
  }
}

std::function<void(bool, const std::string&)> PanelWidget::replacingGraph(const QString& what) {
  // A fresh history from the request on: the link runs calls in order, so an edit asked for
  // after this one is an edit of the new graph, even if its answer comes first.
  auto before = std::make_shared<EditHistory>(history_.edits());
  history_.reset();
  placement_.reset();  // of nodes of the graph before; a node added after this request keeps its place
  return [this, what, before](bool ok, const std::string& message) {
    report(ok, message, what);
    if (ok) return inspectAgain();
    history_.restoreIfUntouched(*before);  // refused, and nothing done since: the old history stands
  };
}

void PanelWidget::inspectAgain() {
  previews_.again();
  inspections_.again();
  labels_.watchAgain();
}

void PanelWidget::showProfile(const QString& node) {
  QPointer<HistogramView>& view = profiles_[node];
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
