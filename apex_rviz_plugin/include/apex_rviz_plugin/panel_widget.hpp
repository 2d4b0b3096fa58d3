// The panel without rviz: the editor, the model and the link to a runtime,
// joined. What a person asks for in the editor becomes an edit of the model,
// made through the link; the history records it once the runtime accepts it.
// The controller is split by concern, each part owning its state and its reset:
// PanelHistory (undo, redo), Placement (where boxes go, Tidy, Balance),
// Inspections (ports inspected, Optimizers' progress), Previews, PresetFiles,
// LabelWindows, TrackerStarter. PanelWidget joins them: the runtime's types and
// graph, the edits, the files and the one place that forgets a runtime.
// GraphPanel puts this in rviz; tests drive it directly.
#pragma once

#include <functional>
#include <map>

#include <QPointer>
#include <QWidget>

#include "apex_rviz_plugin/graph_editor.hpp"
#include "apex_rviz_plugin/graph_model.hpp"
#include "apex_rviz_plugin/inspections.hpp"
#include "apex_rviz_plugin/label_windows.hpp"
#include "apex_rviz_plugin/panel_context.hpp"
#include "apex_rviz_plugin/panel_history.hpp"
#include "apex_rviz_plugin/placement.hpp"
#include "apex_rviz_plugin/preset_files.hpp"
#include "apex_rviz_plugin/previews.hpp"
#include "apex_rviz_plugin/runtime_link.hpp"
#include "apex_rviz_plugin/tracker_starter.hpp"

namespace apex_rviz_plugin {

class HistogramView;
class LabelView;
class RecoveryBar;
class TrackerStartView;

class PanelWidget : public QWidget {
  Q_OBJECT
 public:
  explicit PanelWidget(QWidget* parent = nullptr);

  void setNamespace(const QString& ns);
  QString ns() const { return QString::fromStdString(link_.ns()); }
  GraphEditor* editor() const { return editor_; }
  const GraphModel& model() const { return model_; }
  const RuntimeLink& link() const { return link_; }
  int nodeTypeCount() const { return type_count_; }
  /** @brief Edits sent whose answer has not come back yet. */
  int editsPending() const { return history_.pending(); }
  /** @brief Previews on the nodes on or off (the editor's Previews button). */
  void setPreviews(bool on) { editor_->setPreviewsChecked(on); }  // its toggle does the rest
  bool previews() const { return previews_.on(); }
  /** @brief Where presets are saved, one YAML file per name: $ROS_HOME/apex/presets. */
  static QString presetFolder() { return PresetFiles::folder(); }
  QSize sizeHint() const override { return QSize(1000, 650); }  ///< room for a few nodes side by side
  /** @brief Inspects node/port as a double-click on it does (an rviz display of it, if it has one). */
  void inspect(const QString& node, const QString& port) { inspections_.inspect(node, port); }
  /** @brief Opens the labelling window of image output node/port, as its menu's "Label frames..."
   *  does (label_windows.cpp): its frames come as the runtime inspects the port; its player, if a
   *  BagReader feeds it, is paused and stepped from the window. */
  void labelFrames(const QString& node, const QString& port) { labels_.open(node, port); }
  /** @brief The labelling window of node/port, or nullptr before it was opened. */
  LabelView* labelView(const QString& node, const QString& port) const { return labels_.view(node, port); }
  /** @brief Starts Tracker `tracker` on a box drawn on its frame, as its menu's "Start on a box
   *  drawn on the frame..." does (tracker_starter.cpp): the frame held by the output feeding its
   *  image input (the one it last saw) opens a TrackerStartView; the box dragged on it sets its
   *  x, y, width and height as one edit (the same box again fires its restart slot). Nothing
   *  linked to its image input, no frame within a few seconds, or one that cannot be shown: the
   *  message line says so and no window opens. */
  void startTrackerOnDrawnBox(const QString& tracker) { tracker_.start(tracker); }
  /** @brief The window to draw a Tracker's box on, open or waiting for its frame; nullptr if none. */
  TrackerStartView* trackerStartView() const { return tracker_.view(); }

 signals:
  void namespaceChanged(const QString& ns);
  /** The runtime publishes node/port on `topic` as `message_type`, which rviz has a display for
   *  (rviz_displays.hpp): rviz may show it. */
  void displayRequested(const QString& node, const QString& port, const QString& topic, const QString& message_type);
  /** A rename of node `from` (its new path `to`) is sent to the runtime: who follows node names
   *  (GraphPanel's displays) follows it once a graph shows it. Also for the nodes a group or
   *  an ungroup moves. */
  void renameSent(const QString& from, const QString& to);
  /** The graph shown changed (after a ~graph message): for tests and status. */
  void graphShown(quint64 revision);
  /** Timing from ~status is shown. */
  void statusShown();

 private:
  /** Sends an edit; the history records it once the runtime accepts it. Nothing: the message line
   *  says the node or parameter is gone. */
  void perform(const std::optional<Edit>& edit);
  /** Undo (true) or redo: at once, or after the answers of the edits on their way (PanelHistory). */
  void historyStep(bool undo);
  /** Adds what a paste or duplicate made, and selects it once shown. */
  void pasted(const Pasted& p);
  /** For a Load or New: starts a fresh history now; the answer's handler, which reports it and,
   *  if refused, brings the old history back. */
  std::function<void(bool, const std::string&)> replacingGraph(const QString& what);
  /** The runtime ended every inspection (a load, a group, an ungroup): the ports inspected (the
   *  displays' and the Optimizers' progress) inspected again, the previews asked for anew. */
  void inspectAgain();
  void onGraph(const apex::GraphState& graph);
  void onStatus(const apex::RuntimeStatus& status);
  /** The runtime is gone or another one came: the one place that forgets it. The model and each
   *  part reset once: the history, the places, the watches, the previews. */
  void forgetRuntime();
  /** A runtime to show (connected, or started anew): its types, its graph, a copy its last run left. */
  void meetRuntime();
  /** Reads the runtime's graph; a read that fails (a runtime just started may not answer yet) is
   *  tried again every 250 ms, `tries` times, while it is connected and no graph is shown. */
  void readGraph(int tries);
  /** The nodes `calls` move (a rename, a group, an ungroup), about to be sent, as renameSent; the
   *  ports inspected follow them. */
  void announceMoves(const std::vector<Call>& calls);
  void refreshTypes();
  /** The size of a new node of `type`'s box, measured on one made for it. */
  Box typeBox(const std::string& type) const;
  void report(bool ok, const std::string& message, const QString& what) { ctx_.report(ok, message, what); }
  /** What the panel does on each signal of the runtime link and of its parts. */
  void connectLink();
  void connectParts();
  /** What the panel does on each signal of the editor and its scene: the handlers below and the parts'. */
  void connectEditor();
  void connectEdits();

  // --- the editor's requests that become edits of the model, made through perform() (panel_edits.cpp) ---
  /** A new node of `type` in the subgraph shown, on a free place near `at`. */
  void onAddRequested(const QString& type, QPointF at);
  /** A new node of `type` near `at` with `link` (its end at the new node named here), one edit:
   *  a node that feeds the link is placed to the left of `at`, one fed by it to the right. */
  void onAddLinkedRequested(const QString& type, QPointF at, const apex::Connection& link);
  /** A new node of `type` centred near `at`, put into `link` through its ports `in` and `out`: one edit. */
  void onInsertNewRequested(const QString& type, QPointF at, const apex::Connection& link, const QString& in, const QString& out);
  void onRemoveRequested(const QString& node);
  void onGroupIntoSubgraphRequested(const QStringList& nodes);
  void onUngroupRequested(const QString& subgraph);
  void onDuplicateRequested(const QStringList& nodes);
  /** The nodes as graph file text on the clipboard (not an edit). */
  void onCopyRequested(const QStringList& nodes);
  /** The clipboard's nodes with their top-left corner at `at`, or on a free place near it. */
  void onPasteRequested(QPointF at);
  void onRenameRequested(const QString& node, const QString& new_name);
  void onResetRequested(const QString& node, const QString& param);
  void onEnabledRequested(const QString& node, bool enabled);
  void onThreadGroupRequested(const QString& node, const QString& group);
  void onConnectRequested(const apex::Connection& c);
  void onDisconnectRequested(const apex::Connection& c);
  void onParameterEdited(const QString& node, const QString& param, const QString& yaml, bool dragging);
  void onInteractiveToggled(const QString& node, const QString& param, bool interactive);
  void onNodeMoved(const QString& node, QPointF at);
  void onExpandToggled(const QString& node, bool expanded);
  void onPinRequested(const QString& node, const QString& param, bool pinned);
  void onInsertRequested(const QString& node, const apex::Connection& c, QPointF at);
  /** Tunes node/param with `optimizer`, or a new one below the node (its names from types_). */
  void onOptimiseRequested(const QString& node, const QString& param, const QString& optimizer);
  void onApplyBestRequested(const QString& optimizer);
  void onApplyFrontPointRequested(const QString& optimizer, int evaluation);
  /** Where the boxes are shown, placed or not yet saved: positions for a copy. */
  std::map<std::string, std::pair<double, double>> shownPositions() const;

  // --- the editor's other requests: the namespace, the runtime's controls, files, views ---
  /** The namespace typed in the editor: another runtime, if it differs. */
  void onNamespaceEdited(const QString& ns);
  void onControlRequested(const QString& command);
  void onFireSlotRequested(const QString& node, const QString& slot);
  void onTraceRequested(const QString& command, const QString& path, double seconds);
  void onSaveRequested(const QString& path);
  /** Loads a graph file: a fresh history; laid out once shown if its boxes lie on each other. */
  void onLoadRequested(const QString& path);
  void onNewRequested();
  void onPreviewsToggled(bool on);
  /** A node's HistogramView, opened (or raised: one per node), fed by ~node_profile each second. */
  void showProfile(const QString& node);
  // --- the unsaved graph a previous run of the runtime left (panel_recovery.cpp) ---
  /** Asks the runtime just connected: the bar offers its copy, if it has one. */
  void askRecovery();
  void onRecoveryRestore();
  void onRecoveryDiscard();

  // Who owns what: the editor is a child widget; the model changes only here (onGraph, forgetRuntime);
  // each part below owns its own state and its reset, and reads the model through ctx_.
  GraphEditor* editor_;
  GraphModel model_;
  RuntimeLink link_;
  PanelContext ctx_;
  PanelHistory history_;
  Placement placement_;
  Inspections inspections_;
  Previews previews_;
  PresetFiles presets_;
  LabelWindows labels_;
  TrackerStarter tracker_;
  RecoveryBar* recovery_ = nullptr;  // above the editor, hidden unless a copy is offered
  int type_count_ = 0;
  std::map<std::string, apex::NodeTypeInfo> types_;  // by id, as the runtime listed them
  std::map<QString, QPointer<HistogramView>> profiles_;  // by node: its profile window, deleted with the panel
};

}  // namespace apex_rviz_plugin
