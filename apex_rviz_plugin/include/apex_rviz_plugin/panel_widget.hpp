// The panel without rviz: the editor, the model and the link to a runtime,
// joined. What a person asks for in the editor becomes an edit of the model,
// made through the link; the history records it once the runtime accepts it.
// GraphPanel puts this in rviz; tests drive it directly.
#pragma once

#include <deque>
#include <functional>
#include <map>
#include <set>

#include <QPointer>
#include <QTimer>
#include <QWidget>

#include "apex_rviz_plugin/graph_editor.hpp"
#include "apex_rviz_plugin/graph_model.hpp"
#include "apex_rviz_plugin/runtime_link.hpp"

namespace apex_rviz_plugin {

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
  int editsPending() const { return pending_; }
  /** @brief Previews on the nodes on or off (the editor's Previews button). */
  void setPreviews(bool on);
  bool previews() const { return previews_; }
  /** @brief Where presets are saved, one YAML file per name: $ROS_HOME/apex/presets. */
  static QString presetFolder();
  QSize sizeHint() const override { return QSize(1000, 650); }  ///< room for a few nodes side by side
  /** @brief Inspects node/port as a double-click on it does (an rviz display of it, if it has one). */
  void inspect(const QString& node, const QString& port) { onInspect(node, port); }
  /** @brief Opens the labelling window of image output node/port, as its menu's "Label frames..."
   *  does (panel_labels.cpp): its frames come as the runtime inspects the port; its player, if a
   *  BagReader feeds it, is paused and stepped from the window. */
  void labelFrames(const QString& node, const QString& port);
  /** @brief The labelling window of node/port, or nullptr before it was opened. */
  LabelView* labelView(const QString& node, const QString& port) const;
  /** @brief Starts Tracker `tracker` on a box drawn on its frame, as its menu's "Start on a box
   *  drawn on the frame..." does (panel_tracker.cpp): the frame held by the output feeding its
   *  image input (the one it last saw) opens a TrackerStartView; the box dragged on it sets its
   *  x, y, width and height as one edit (the same box again fires its restart slot). Nothing
   *  linked to its image input, no frame within a few seconds, or one that cannot be shown: the
   *  message line says so and no window opens. */
  void startTrackerOnDrawnBox(const QString& tracker);
  /** @brief The window to draw a Tracker's box on, open or waiting for its frame; nullptr if none. */
  TrackerStartView* trackerStartView() const;

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
  void perform(const std::optional<Edit>& edit);
  /** An undo (`undo`) or redo step's calls, named `label` (the edit's own): the message says
   *  "undid: <label>" or "redid: <label>"; what the graph is after them is what a redo applies to. */
  void replay(std::vector<Call> calls, bool undo, const std::string& label);
  // --- redo after edits made elsewhere (panel_history.cpp) ---
  /** An undo or redo step answered; `after`, the runtime's graph right after it. */
  void stepDone(bool undo, const std::string& label, bool ok, const std::string& message, const apex::GraphState& after);
  /** Someone else (a script, another panel) edited the graph since the last undo or redo: what
   *  could be redone no longer applies and is dropped. */
  void dropRedoIfEditedElsewhere();
  /** Undo (true) or redo: at once, or, while an edit is unanswered (not in the history yet: the
   *  runtime's new graph can show before its answer), after the answers, in the order asked. */
  void historyStep(bool undo);
  /** Adds what a paste or duplicate made, and selects it once shown. */
  void pasted(const Pasted& p);
  void forgetHistory();
  /** Previews: every node shown gets its preview area; the outputs of nodes in view are
   *  previewed (inspect with preview, subscribed), those out of view are not (unsubscribed:
   *  the runtime then publishes nothing for them). Runs on a timer while previews are on. */
  void updatePreviews();
  /** Presets are files in $ROS_HOME/apex/presets, one per name: the editor's menu lists them. */
  void listPresets();
  void savePreset(const QString& name, const QStringList& nodes);
  /** The preset's text, or "" with the reason shown. */
  std::string readPreset(const QString& name);
  /** Tidy: the nodes shown in layers, where their top-left corner was; one edit. */
  void tidy();
  /** Balance: the runtime proposes thread groups from the nodes' times (~balance), applied as one
   *  edit; the status line says what to expect (and which links would need a Relay). */
  void balance();
  /** Gives nodes shown without a position one (a graph written by hand, a node added by a
   *  script): laid out in layers beside the others, never on top of one. Not an edit of the
   *  person's: not in the history. */
  void placeUnplaced();
  /** Sends positions for nodes (set_ui), outside the history. */
  void place(const std::map<std::string, std::pair<double, double>>& positions);
  /** For a Load or New: starts a fresh history now; the answer's handler, which reports it and,
   *  if refused, brings the old history back. */
  std::function<void(bool, const std::string&)> replacingGraph(const QString& what);
  /** The runtime ended every inspection (a load, a group, an ungroup): the ports inspected (the
   *  displays' and the Optimizers' progress) inspected again, the previews asked for anew. */
  void inspectAgain();
  /** Boxes below a box that grew onto them move down (a box is sized to its content). */
  void pushDownUnderGrown();
  void rememberSizes();
  /** Lays a loaded graph out if its boxes lie on each other (placeUnplaced with untangle_). */
  void untangleLoaded();
  /** Places nodes shown without a position, else pushes boxes that grew apart. */
  void arrangeShown();
  /** The places the set_ui calls among `calls` send nodes to, taken until the graph shows them there. */
  void reservePlaces(const std::vector<Call>& calls);
  void onGraph(const apex::GraphState& graph);
  /** The runtime is gone or another one came: its graph, history, watches and previews forgotten. */
  void forgetRuntime();
  /** A runtime to show (connected, or started anew): its types, its graph, a copy its last run left. */
  void meetRuntime();
  /** Reads the runtime's graph; a read that fails (a runtime just started may not answer yet) is
   *  tried again every 250 ms, `tries` times, while it is connected and no graph is shown. */
  void readGraph(int tries);
  void onInspect(const QString& node, const QString& port);
  /** The nodes `calls` move (a rename, a group, an ungroup), about to be sent, as renameSent; the
   *  ports inspected follow them. */
  void announceMoves(const std::vector<Call>& calls);
  void refreshTypes();
  /** The size of a new node of `type`'s box, measured on one made for it. */
  Box typeBox(const std::string& type) const;
  /** Inspects each Optimizer's progress (evaluations, best fitness) once, for its box to draw. */
  void watchOptimizers();
  void report(bool ok, const std::string& message, const QString& what);
  /** What the panel does on each signal of the editor and its scene: the handlers below. */
  void connectEditor();

  // --- the editor's requests that become edits of the model, made through perform() (panel_edits.cpp) ---
  /** A new node of `type` in the subgraph shown, on a free place near `at`. */
  void onAddRequested(const QString& type, QPointF at);
  /** A new node of `type` near `at` with `link` (its end at the new node named here), one edit:
   *  a node that feeds the link is placed to the left of `at`, one fed by it to the right. */
  void onAddLinkedRequested(const QString& type, QPointF at, const apex::Connection& link);
  /** A new node of `type` centred near `at`, put into `link` through its ports `in` and `out`: one edit. */
  void onInsertNewRequested(const QString& type, QPointF at, const apex::Connection& link, const QString& in, const QString& out);
  /** A path for a new node of `type` in the subgraph shown, and a free place for its box with its
   *  top-left corner near `at` (its top-right one if `left_of`); reserved until the graph shows it. */
  std::pair<std::string, Box> placeNew(const std::string& type, QPointF at, bool left_of = false);
  /** The boxes a new one must not lie on: those shown, and those sent a place not shown there yet. */
  std::vector<Box> takenPlaces() const;
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

  // --- the editor's other requests: the namespace, history, the runtime's controls, files, presets, views ---
  /** The namespace typed in the editor: another runtime, if it differs. */
  void onNamespaceEdited(const QString& ns);
  void onUndoRequested();
  void onRedoRequested();
  void onControlRequested(const QString& command);
  void onFireSlotRequested(const QString& node, const QString& slot);
  void onSaveRequested(const QString& path);
  /** Loads a graph file: a fresh history; laid out once shown if its boxes lie on each other. */
  void onLoadRequested(const QString& path);
  void onNewRequested();
  void onPreviewsToggled(bool on);
  /** The preset's values set where they differ, as one edit. */
  void onPresetRestoreRequested(const QString& name);
  /** What differs between the preset and the graph, in the editor's window for it. */
  void onPresetCompareRequested(const QString& name);
  /** Another subgraph shown: its nodes without a position get one once shown. */
  void onLevelChanged();
  /** A node's HistogramView, opened (or raised: one per node), fed by ~node_profile each second. */
  void showProfile(const QString& node);
  // --- labelling frames (panel_labels.cpp) ---
  /** The player (a node with a transport bar) whose frames reach `node` through data links, the
   *  node itself if it is one; "" if none does. */
  QString playerFeeding(const std::string& node) const;
  /** Inspects the window's port and sends its images to it; a refusal is said in the window. */
  void watchFrames(LabelView* view);
  /** The open labelling windows' ports inspected again (the runtime ended every inspection). */
  void watchLabelledAgain();
  void onFrameReceived(const QString& node, const QString& port, const QImage& image, quint64 stamp, const QString& encoding);
  // --- starting a Tracker on a box drawn on its frame (panel_tracker.cpp) ---
  /** The frame for the window waiting for one (its source's): it opens on it. */
  void onTrackerFrame(const QString& node, const QString& port, const QImage& image, quint64 stamp, const QString& encoding);
  /** The frames of node/port no longer wanted for a Tracker (a labelling window on them keeps them). */
  void stopTrackerFrames(const QString& node, const QString& port);
  /** The Tracker's x, y, width and height set to `box` (image pixels) as one edit. */
  void startTrackerOn(const QString& tracker, const QRect& box);
  // --- the unsaved graph a previous run of the runtime left (panel_recovery.cpp) ---
  /** Asks the runtime just connected: the bar offers its copy, if it has one. */
  void askRecovery();
  void onRecoveryRestore();
  void onRecoveryDiscard();

  GraphEditor* editor_;
  GraphModel model_;
  EditHistory history_;
  RuntimeLink link_;
  int type_count_ = 0;
  int pending_ = 0;
  std::deque<bool> waiting_steps_;  // undo (true) or redo asked for while an edit was unanswered
  int history_epoch_ = 0;  // counts fresh histories: an edit answered after one began is not recorded
  std::map<std::string, apex::NodeTypeInfo> types_;  // by id, as the runtime listed them
  std::set<std::string> watched_;  // Optimizers whose progress is inspected
  std::set<std::pair<std::string, std::string>> inspected_;  // (node, port) asked for by the person
  std::map<std::string, Box> sizes_;  // the boxes when the graph was shown last
  std::uint64_t untangle_from_ = 0;  // a loaded graph's revision: lay it out when it is shown
  int placements_sent_ = 0;  // counts place() calls
  std::map<std::string, Box> placing_;  // where nodes were sent, until the graph shows them there
  bool previews_ = false;
  QTimer* preview_timer_ = nullptr;
  std::set<std::string> previewing_;  // "node/port" whose preview is asked for or watched
  RecoveryBar* recovery_ = nullptr;  // above the editor, hidden unless a copy is offered
  std::map<std::string, QPointer<LabelView>> label_views_;  // "node/port": labelling windows, hidden when closed
  QPointer<TrackerStartView> tracker_start_;  // the window to draw a Tracker's box on; it deletes itself when closed
  bool untangle_ = true;  // next graph shown: boxes on top of each other are laid out (a Load, a new level)
  int replaying_ = 0;  // undo and redo steps sent, not answered yet
  /** The graph a redo applies to: its revision and shape (panel_history.cpp) right after the last
   *  undo or redo; unset while unknown. */
  std::optional<std::pair<std::uint64_t, std::string>> redo_base_;
};

}  // namespace apex_rviz_plugin
