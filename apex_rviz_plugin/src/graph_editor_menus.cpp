// GraphEditor's menus and dialogs: a node's, a port's (with "Show in rviz"), a parameter's, the
// canvas's and the presets' menus; asking a name for a preset or a node.
#include "apex_rviz_plugin/graph_editor.hpp"
#include "apex_rviz_plugin/file_dialog.hpp"
#include "apex_rviz_plugin/rviz_displays.hpp"

#include <QDir>
#include <QFileInfo>
#include <QInputDialog>
#include <QMenu>
#include <QMessageBox>

namespace apex_rviz_plugin {

void GraphEditor::showNodeMenu(const QString& node, QPoint at) {
  QMenu menu;
  fillNodeMenu(menu, node);
  if (!menu.isEmpty()) menu.exec(at);
}

void GraphEditor::fillNodeMenu(QMenu& menu, const QString& node) {
  const NodeItem* item = scene_->node(node.toStdString());
  if (!item || !model_) return;
  const apex::NodeInfo& info = item->info();
  QStringList selected = selectedNodes();  // the node and the others selected with it
  if (!selected.contains(node)) selected = QStringList{node};
  menu.addAction(info.enabled ? "Disable" : "Enable", this,
                 [this, node, on = !info.enabled] { emit enabledRequested(node, on); });
  menu.addAction("Rename...", this, [this, node] { askNewName(node); });
  menu.addAction("Copy", this, [this, selected] { emit copyRequested(selected); });
  menu.addAction("Save parameters as preset...", this, [this, selected] { askPresetName(selected); });
  menu.addAction("Duplicate", this, [this, selected] { emit duplicateRequested(selected); });
  menu.addAction("Remove", this, [this, node] { emit removeRequested(node); });
  QAction* reset = menu.addAction("Reset parameters to defaults", this, [this, node] { emit resetRequested(node, QString()); });
  reset->setEnabled(model_->resetToDefault(info.name).has_value());
  menu.addAction(selected.size() > 1 ? QString("Group %1 nodes into a subgraph").arg(selected.size()) : "Group into a subgraph",
                 this, [this, selected] { emit groupIntoSubgraphRequested(selected); });
  if (!info.subgraph.empty()) {
    menu.addAction("Open subgraph", this, [this, node] { scene_->setLevel(node.toStdString()); });
    menu.addAction("Ungroup", this, [this, node] { emit ungroupRequested(node); });
  }
  QMenu* groups = menu.addMenu("Thread group");
  for (const auto& g : model_->graph().thread_groups) {
    QAction* a = groups->addAction(QString::fromStdString(g), this,
                                   [this, node, g] { emit groupRequested(node, QString::fromStdString(g)); });
    a->setCheckable(true);
    a->setChecked(g == info.thread_group);
  }
  groups->addAction("New group...", this, [this, node] {
    const QString g = QInputDialog::getText(this, "Thread group", "Name of the new thread group:");
    if (!g.isEmpty()) emit groupRequested(node, g);
  });
  if (info.type == kOptimizerType) {
    menu.addSeparator();
    menu.addAction("Start optimising", this, [this, node] { emit fireSlotRequested(node, "start"); });
    menu.addAction("Stop", this, [this, node] { emit fireSlotRequested(node, "stop"); });
    QAction* apply = menu.addAction("Apply best values", this, [this, node] { emit applyBestRequested(node); });
    apply->setEnabled(model_->applyBest(info.name).has_value());
    const auto front = model_->front(info.name);
    if (!front.empty()) {  // a two-objective run: each point of its front, cheapest first
      QMenu* points = menu.addMenu("Apply a point of the front");
      for (const auto& p : front) {
        const QString text = QString("fitness %1 · %2 ms/frame  %3 (evaluation %4)")
                                 .arg(p.fitness, 0, 'g', 4)
                                 .arg(p.ms_per_frame, 0, 'f', 2)
                                 .arg(QString::fromStdString(p.values))
                                 .arg(p.evaluation);
        points->addAction(text, this, [this, node, k = p.evaluation] { emit applyFrontPointRequested(node, k); });
      }
    }
    menu.addSeparator();
  }
  if (info.type == kTrackerType) {
    QAction* start =
        menu.addAction("Start on a box drawn on the frame...", this, [this, node] { emit trackerStartRequested(node); });
    start->setObjectName("tracker_start");
    start->setToolTip(
        "shows the frame it last saw: drag a box around the object and it starts on it "
        "(its x, y, width and height, one undo step)");
    menu.setToolTipsVisible(true);
  }
  QMenu* slot_menu = menu.addMenu("Fire slot");
  QMenu* inspect = menu.addMenu("Inspect");
  QMenu* label = nullptr;  // "Label frames" of each image output, if it has any
  for (const auto& p : info.ports) {
    const QString port = QString::fromStdString(p.name);
    if (p.kind == "slot") slot_menu->addAction(port, this, [this, node, port] { emit fireSlotRequested(node, port); });
    if (p.kind == "output" || p.kind == "param_out")
      inspect->addAction(port, this, [this, node, port] { emit inspectRequested(node, port); });
    if (p.kind == "output" && carriesImages(p)) {
      if (!label) label = menu.addMenu("Label frames");
      label->addAction(port, this, [this, node, port] { emit labelRequested(node, port); });
    }
  }
  menu.addSeparator();
  const bool shown = scene_->criticalTarget() == node.toStdString();
  QAction* critical = menu.addAction(shown ? "Hide the critical path" : "Critical path to here", this, [this, node, shown] {
    const std::string path = scene_->showCriticalPath(shown ? "" : node.toStdString());
    showMessage(shown ? "critical path hidden" : QString::fromStdString("critical path to " + node.toStdString() + ": " + path),
                false);
  });
  critical->setObjectName("critical_path");
  QAction* histogram = menu.addAction("Latency histogram...", this, [this, node] { emit profileRequested(node); });
  histogram->setObjectName("latency_histogram");
  histogram->setToolTip("its latency from the frame's stamp and its firing time over the last 5-10 s, updated every second");
  critical->setToolTip("colours the chain of links whose frames come last to this node (by live latency, else by firing time)");
  menu.addAction("Help (F1)", this, [this, node] { showNodeHelp(node); });  // what its type does, its ports and parameters
}

void GraphEditor::showPortMenu(const QString& node, const QString& port, QPoint at) {
  QMenu menu;
  fillPortMenu(menu, node, port);
  if (!menu.isEmpty()) menu.exec(at);
}

void GraphEditor::fillPortMenu(QMenu& menu, const QString& node, const QString& port) {
  const NodeItem* item = scene_->node(node.toStdString());
  const PortItem* p = item ? item->port(port.toStdString(), true) : nullptr;
  if (p) {
    menu.addAction("Inspect " + port, this, [this, node, port] { emit inspectRequested(node, port); });
    addShowInRviz(menu, node, port, p->port().type);
    if (p->port().kind == "output" && carriesImages(p->port())) {
      QAction* label = menu.addAction("Label frames...", this, [this, node, port] { emit labelRequested(node, port); });
      label->setObjectName("label_frames");
      label->setToolTip("draw boxes on its frames and save them as ground truth for RegionScore");
    }
  } else if (item && item->port(port.toStdString(), false) && item->port(port.toStdString(), false)->port().kind == "slot") {
    menu.addAction("Fire " + port, this, [this, node, port] { emit fireSlotRequested(node, port); });
  }
}

void GraphEditor::addShowInRviz(QMenu& menu, const QString& node, const QString& port, const std::string& port_type) {
  // An inspection's answer makes the display (Inspections::inspect), as a double-click's does.
  QAction* show = menu.addAction("Show in rviz", this, [this, node, port] { emit inspectRequested(node, port); });
  show->setObjectName("show_in_rviz");
  menu.setToolTipsVisible(true);
  const auto known = message_types_.find(port_type);
  if (known == message_types_.end())
    return show->setToolTip("shown if rviz has a display for its messages (their type is known once it is inspected)");
  const auto display = rvizDisplayFor(known->second);
  show->setEnabled(display.has_value());
  show->setToolTip(QString::fromStdString(display ? "as " + display->rviz_class + " (" + known->second + ")"
                                                  : "not in rviz: " + noRvizDisplayReason(known->second)));
}

bool GraphEditor::carriesImages(const apex::PortInfo& port) const {
  const auto known = message_types_.find(port.type);  // a port of any type, once inspected
  return port.type == "apex_nodes/Image" || (known != message_types_.end() && known->second == "sensor_msgs/Image");
}

void GraphEditor::showMessageType(const QString& node, const QString& port, const std::string& message_type) {
  const NodeItem* item = scene_->node(node.toStdString());
  const PortItem* p = item ? item->port(port.toStdString(), true) : nullptr;
  // A port of any type is inspected as its first message's type: not the same for every such port.
  if (p && !message_type.empty() && !p->port().type.empty() && p->port().type != "any")
    message_types_[p->port().type] = message_type;
}

void GraphEditor::fillParamMenu(QMenu& menu, const QString& node, const QString& param) {
  const apex::ParamInfo* p = model_ ? model_->parameter(node.toStdString(), param.toStdString()) : nullptr;
  if (!p) return;
  QAction* reset = menu.addAction("Reset to default (" + QString::fromStdString(p->default_value) + ")", this,
                                  [this, node, param] { emit resetRequested(node, param); });
  reset->setEnabled(p->value != p->default_value);
  const apex::NodeInfo* n = model_->node(node.toStdString());
  const bool pinned = n && BoxView::of(n->ui).isPinned(param.toStdString());
  QAction* pin = menu.addAction(pinned ? "Unpin from the compact box" : "Pin to the compact box", this,
                                [this, node, param, pinned] { emit pinRequested(node, param, !pinned); });
  pin->setObjectName("pin");
  if (!tunedAs(*p)) return;  // a number, an interval, a choice or a flag can be tuned
  QMenu* with = menu.addMenu("Tune automatically with");
  with->setObjectName("optimise_with");
  with->setToolTipsVisible(true);
  const QString how = "; link a score to its fitness input (larger is better), then fire its start slot";
  if (model_)
    for (const auto& opt : model_->optimizers()) {
      const QString o = QString::fromStdString(opt);
      QAction* a =
          with->addAction(o + " (tune this too)", this, [this, node, param, o] { emit optimiseRequested(node, param, o); });
      a->setToolTip(o + " also sets " + param + " in its search (Differential Evolution)" + how);
    }
  QAction* fresh = with->addAction("a new Optimizer (Differential Evolution)", this,
                                   [this, node, param] { emit optimiseRequested(node, param, QString()); });
  fresh->setToolTip("an Optimizer below " + node + " that tries values of " + param + " in its range" + how);
}

void GraphEditor::showParamMenu(const QString& node, const QString& param, QPoint at) {
  QMenu menu;
  fillParamMenu(menu, node, param);
  menu.exec(at);
}

void GraphEditor::showLinkMenu(const apex::Connection& link, QPoint at) {
  QMenu menu;
  fillLinkMenu(menu, link);
  menu.exec(at);
}

void GraphEditor::fillLinkMenu(QMenu& menu, const apex::Connection& link) {
  QAction* insert = menu.addAction("Insert node...", this, [this, link] { openInsertAdd(link); });
  insert->setObjectName("insert_node");
  // A right-click used to disconnect at once: now it asks, as Blender and Groot2 do.
  QAction* remove = menu.addAction("Delete link", this, [this, link] { scene_->removeLink(link); });
  remove->setObjectName("delete_link");
}

void GraphEditor::showCanvasMenu(QPointF scene_pos, QPoint at) {
  QMenu menu;
  menu.addAction("Add node... (Tab)", this, [this, scene_pos] { openQuickAdd(scene_pos); });
  menu.addAction("Paste", this, [this, scene_pos] { emit pasteRequested(scene_pos); });
  menu.exec(at);
}

void GraphEditor::fillPresetMenu(QMenu& menu) {
  menu.addAction("Save all parameters as...", this, [this] { askPresetName({}); });
  if (!presets_.isEmpty()) menu.addSeparator();
  for (const QString& name : presets_) {
    QMenu* one = menu.addMenu(name);
    one->addAction("Restore", this, [this, name] { emit presetRestoreRequested(name); });
    one->addAction("Compare with now", this, [this, name] { emit presetCompareRequested(name); });
  }
}

void GraphEditor::askPresetName(const QStringList& nodes) {
  auto* ask = new QInputDialog(this);
  ask->setObjectName("preset_dialog");
  ask->setAttribute(Qt::WA_DeleteOnClose);
  ask->setWindowTitle("Save preset");
  ask->setLabelText(nodes.isEmpty() ? "Name for the parameters of the whole graph:"
                                    : QString("Name for the parameters of %1:").arg(nodes.join(", ")));
  connect(ask, &QInputDialog::textValueSelected, this, [this, nodes](const QString& name) {
    if (!name.trimmed().isEmpty()) emit presetSaveRequested(name.trimmed(), nodes);
  });
  ask->open();
}

void GraphEditor::fillTraceMenu(QMenu& menu) {
  if (tracing_) menu.addAction("Stop tracing", this, [this] { emit traceRequested("stop", "", 0); });
  else menu.addAction("Start tracing", this, [this] { emit traceRequested("start", "", 0); });
  auto save = [this](double seconds) {
    const QString folder = QFileInfo(last_path_).dir().path();
    const FileDialogSpec spec{"trace_dialog",           "Save trace", folder + "/trace.json", FileDialogSpec::Mode::Save,
                              "Chrome traces (*.json)", "json"};
    openFileDialog(file_dialog_, this, spec,
                   [this, seconds](const QString& path) { emit traceRequested("save", path, seconds); });
  };
  menu.addAction("Save the last 10 s...", this, [save] { save(10); })->setObjectName("trace_save_10");
  menu.addAction("Save all kept...", this, [save] { save(0); })->setObjectName("trace_save_all");
}

void GraphEditor::showTracing(bool on) {
  if (on == tracing_) return;
  tracing_ = on;
  trace_->setText(on ? "Trace ●" : "Trace");
  trace_->setStyleSheet(on ? "color: #c03030;" : "");
}

void GraphEditor::setPreviewsChecked(bool on) { previews_->setChecked(on); }

void GraphEditor::showPresetDiff(const QString& name, const QString& text) {
  auto* box = new QMessageBox(QMessageBox::Information, "Preset " + name, text, QMessageBox::Close, this);
  box->setObjectName("preset_diff");
  box->setAttribute(Qt::WA_DeleteOnClose);
  box->setModal(false);
  box->show();
}

void GraphEditor::askNewName(const QString& node) {
  auto* ask = new QInputDialog(this);
  ask->setObjectName("rename_dialog");
  ask->setAttribute(Qt::WA_DeleteOnClose);
  ask->setWindowTitle("Rename " + node);
  ask->setLabelText("New name (its connections are kept):");
  ask->setTextValue(node.mid(node.lastIndexOf('/') + 1));
  connect(ask, &QInputDialog::textValueSelected, this, [this, node](const QString& name) {
    if (!name.isEmpty()) emit renameRequested(node, name);
  });
  ask->open();  // not modal to the event loop: rviz goes on drawing
}

}  // namespace apex_rviz_plugin
