// The editor as a person sees it: a tool bar (runtime namespace, pause, step,
// undo, redo, save, load), a searchable palette of node types and the graph
// view, the quick-add box at the cursor and the node types' help. It draws what
// it is given and says what the person asked for, as signals; it makes no calls
// itself (no ROS here).
#pragma once

#include <QPointer>
#include <QStringList>
#include <QWidget>

#include <apex/NodeTypeInfo.h>

#include <map>
#include <optional>
#include <vector>

#include "apex_rviz_plugin/graph_scene.hpp"

class QFileDialog;
class QGraphicsView;
class QLabel;
class QMenu;
class QLineEdit;
class QTabWidget;
class QToolButton;

namespace apex_rviz_plugin {

class HelpView;
class Minimap;
class Palette;
class PropertiesView;
class QuickAdd;

class GraphEditor : public QWidget {
  Q_OBJECT
 public:
  explicit GraphEditor(QWidget* parent = nullptr);
  /** Deaf to its scene first: the scene's items go last (selectionChanged while they go), after
   *  the model shown (its owner's) is gone. */
  ~GraphEditor() override;
  /** @brief The menu of a right-click on a number parameter: "Tune automatically with" an Optimizer of the
   *  graph or a new one. Filled for tests to read; shown by a right-click. */
  void fillParamMenu(QMenu& menu, const QString& node, const QString& param);
  /** @brief The menu of a right-click on a node. Filled for tests to read; shown by a right-click. */
  void fillNodeMenu(QMenu& menu, const QString& node);
  /** @brief The menu of a right-click on a link: "Insert node..." (openInsertAdd) and "Delete link"
   *  (it disappears at once, and comes back if the runtime refuses). Filled for tests to read;
   *  shown by a right-click. */
  void fillLinkMenu(QMenu& menu, const apex::Connection& link);
  /** @brief The menu of a right-click on a port: inspect (an output) or fire (a slot), and for an
   *  output "Show in rviz", disabled with the reason as its tooltip once the port's ROS message
   *  type is known to have no rviz display; for an image output "Label frames...". Filled for
   *  tests to read; shown by a right-click. */
  void fillPortMenu(QMenu& menu, const QString& node, const QString& port);
  /** @brief The runtime inspects node/port as `message_type` (empty: not known): remembered for
   *  every port of its type, which the runtime inspects alike, for "Show in rviz". */
  void showMessageType(const QString& node, const QString& port, const std::string& message_type);
  /** @brief The Presets button's menu: save all, and per saved preset restore or compare.
   *  Filled for tests to read; shown by the button. */
  void fillPresetMenu(QMenu& menu);
  /** @brief The Trace button's menu: start or stop the frame trace, save the last 10 s or all kept
   *  (a file dialog, then the runtime writes Chrome trace JSON). Filled for tests to read. */
  void fillTraceMenu(QMenu& menu);
  /** @brief Whether the runtime traces (RuntimeStatus::tracing): the Trace button says so. */
  void showTracing(bool on);
  /** @brief The presets saved (names), for the Presets menu. */
  void showPresets(const QStringList& names) { presets_ = names; }
  /** @brief What differs between a preset and the graph now, in a window of its own. */
  void showPresetDiff(const QString& name, const QString& text);
  /** @brief The names of the selected nodes. */
  QStringList selectedNodes() const;
  /** @brief Selects these nodes (only these) once the graph shows them: what a paste or a
   *  duplicate made. */
  void selectWhenShown(const QStringList& nodes);

  GraphScene* scene() const { return scene_; }
  /** @brief $ROS_HOME/apex/ (~/.ros/apex/): where graphs and presets go by default. */
  static QString defaultGraphFolder();
  QGraphicsView* view() const { return view_; }

  void showGraph(const GraphModel& model);
  void showTypes(const std::vector<apex::NodeTypeInfo>& types);
  void showMessage(const QString& text, bool error);
  void showConnection(bool up, const QString& text);
  void showHistory(const QString& undo_label, bool can_undo, bool can_redo);
  /** @brief The mark beside the runtime's name: the graph differs from its file (RuntimeStatus::unsaved). */
  void showUnsaved(bool unsaved);
  bool unsavedShown() const;
  void setNamespace(const QString& ns);
  QString message() const;
  /** @brief The smallest zoom (Fit, the wheel): a docked view shows a graph of hundreds of nodes whole. */
  static constexpr double kMinZoom = 0.01;  // Fit shows a graph of hundreds of nodes whole
  /** @brief Scales and scrolls the view to show the whole graph (at most 1:1, at least kMinZoom). */
  void fitGraph();
  /** @brief Scrolls the view (growing the canvas if needed) to show `area`'s top-left part: where
   *  a node was just put (freePlace may have moved it below the view). */
  void reveal(const QRectF& area);
  /** @brief Fits the view to the next graph shown (after connecting to a runtime), and again as
   *  boxes grow past the view (previews arriving) until the person clicks or scrolls in it. */
  void fitNextGraph() { fit_pending_ = true; }

  // --- adding where the person works, and the types' help (graph_editor_adding.cpp) ---
  /** @brief Opens the quick-add box at scene point `at` (Tab or Space in the view, a double-click
   *  on empty canvas): every type; the one chosen is added there. */
  void openQuickAdd(QPointF at);
  /** @brief Opens the quick-add box for a link dragged from `node`/`port` (an output, trigger or
   *  parameter output if `source`) and let go at scene point `at`: the types with a port that fits
   *  (GraphModel::linkable); the one chosen is added there with the link, as one edit. */
  void openLinkAdd(const QString& node, const QString& port, bool source, QPointF at);
  /** @brief Opens the quick-add box midway between the boxes `link` joins, offering the types a
   *  new node put into it may be of (GraphModel::insertable); the one chosen is added there, with
   *  the link's source into it and it into the link's target in the link's place, as one edit. */
  void openInsertAdd(const apex::Connection& link);
  /** @brief The quick-add box; nullptr before it was first opened. */
  QuickAdd* quickAdd() const { return quick_add_; }
  /** @brief Shows a type's documentation (a palette entry's, F1 in the quick-add box). */
  void showTypeHelp(const QString& type);
  /** @brief Shows the documentation of a node's type (its menu's Help, F1 on the canvas). */
  void showNodeHelp(const QString& node);
  /** @brief The help window; nullptr before help was first asked for. */
  HelpView* help() const { return help_; }
  /** @brief Checks or unchecks the Previews button, as a click does: previewsToggled if it changes. */
  void setPreviewsChecked(bool on);
  /** @brief The Whole window button: checked while the editor has the whole window. */
  QToolButton* wholeWindowButton() const { return whole_; }
  /** @brief The selected node's parameters, beside the canvas (a tab beside the palette's). */
  PropertiesView* properties() const { return properties_; }

 protected:
  /** The wheel zooms around the cursor; Delete, Ctrl+C, Ctrl+V, Ctrl+D on the selection; Tab or
   *  Space opens quick add at the cursor, F1 the selected node's help. */
  bool eventFilter(QObject* watched, QEvent* event) override;

 signals:
  void namespaceChanged(const QString& ns);
  void addRequested(const QString& type, QPointF pos);
  /** A new node of `type` at `pos` with `link`, whose end at the new node has its port but no
   *  node name (the name is the panel's to choose): one edit. */
  void addLinkedRequested(const QString& type, QPointF pos, const apex::Connection& link);
  /** A new node of `type` centred at `pos` put into `link`: fed through its port `in`, feeding
   *  through `out` (the name is the panel's to choose): one edit. */
  void insertNewRequested(const QString& type, QPointF pos, const apex::Connection& link, const QString& in, const QString& out);
  void removeRequested(const QString& node);
  void groupIntoSubgraphRequested(const QStringList& nodes);
  void ungroupRequested(const QString& subgraph);
  void duplicateRequested(const QStringList& nodes);
  void copyRequested(const QStringList& nodes);
  /** Paste what the clipboard holds, its top-left node at `at` (scene). */
  void pasteRequested(QPointF at);
  void renameRequested(const QString& node, const QString& new_name);
  /** Parameters back to their defaults: `param`, or all of the node's if empty. */
  void resetRequested(const QString& node, const QString& param);
  /** A parameter pinned to (or unpinned from) its node's compact box. */
  void pinRequested(const QString& node, const QString& param, bool pinned);
  void enabledRequested(const QString& node, bool enabled);
  void groupRequested(const QString& node, const QString& group);
  void fireSlotRequested(const QString& node, const QString& slot);
  void inspectRequested(const QString& node, const QString& port);
  /** Label the frames of image output node/port (a LabelView). */
  void labelRequested(const QString& node, const QString& port);
  /** Start Tracker `node` on a box the person draws on the frame it last saw (TrackerStartView). */
  void trackerStartRequested(const QString& node);
  /** Tune node/param with an Optimizer; an empty `optimizer`: a new one. */
  void optimiseRequested(const QString& node, const QString& param, const QString& optimizer);
  void applyBestRequested(const QString& optimizer);
  /** Apply the values of the point of the optimizer's Pareto front from evaluation `evaluation`. */
  void applyFrontPointRequested(const QString& optimizer, int evaluation);
  void controlRequested(const QString& command);
  void undoRequested();
  void redoRequested();
  void saveRequested(const QString& path);
  void loadRequested(const QString& path);
  /** The frame trace (FrameTrace.srv): "start", "stop", or "save" the last `seconds` (0: all) to `path`. */
  void traceRequested(const QString& command, const QString& path, double seconds);
  /** A node's menu: its latency and firing-time histograms in a window (HistogramView). */
  void profileRequested(const QString& node);
  /** New: the person confirmed that every node goes. */
  void newRequested();
  void typesRequested();
  /** Lay the nodes shown out in layers, left to right. */
  void tidyRequested();
  /** Thread groups that make the graph a pipeline filling the cores, from the nodes' times. */
  void balanceRequested();
  /** Save the parameters of `nodes` (all if empty) as preset `name`. */
  void presetSaveRequested(const QString& name, const QStringList& nodes);
  void presetRestoreRequested(const QString& name);
  void presetCompareRequested(const QString& name);
  /** Previews on the nodes (thumbnails of images, sparklines of numbers) on or off. */
  void previewsToggled(bool on);
  /** The editor over the whole window (the Whole window button, Ctrl+M), or back where it was:
   *  for who holds it (GraphPanel, in rviz's window). */
  void wholeWindowToggled(bool on);

 private:
  QWidget* buildToolBar();
  QWidget* buildLevelBar();
  /** The palette of node types (palette.hpp): what it asks to add goes at newNodePosition(). */
  QWidget* buildPalette();
  /** The column beside the canvas: the palette, and the selected node's properties, as tabs;
   *  picking one node shows its properties. */
  QWidget* buildSideTabs();
  /** The properties of the node selected alone, as the graph shows it now. */
  void showProperties();
  void showNodeMenu(const QString& node, QPoint at);
  void showPortMenu(const QString& node, const QString& port, QPoint at);
  /** Whether an output carries images (its type, or the ROS type an inspection answered): it can
   *  be labelled. */
  bool carriesImages(const apex::PortInfo& port) const;
  /** "Show in rviz" for an output of `port_type`: see fillPortMenu. */
  void addShowInRviz(QMenu& menu, const QString& node, const QString& port, const std::string& port_type);
  void showParamMenu(const QString& node, const QString& param, QPoint at);
  void showLinkMenu(const apex::Connection& link, QPoint at);
  void removeSelected();
  void showCanvasMenu(QPointF scene_pos, QPoint at);
  void askNewName(const QString& node);
  /** Asks a preset's name, then saves the parameters of `nodes` (all if empty) under it. */
  void askPresetName(const QStringList& nodes);
  QPointF newNodePosition();
  /** Where the cursor is on the canvas (else where the mouse was last over it, else the middle of the view). */
  QPointF cursorPosition() const;
  QuickAdd* ensureQuickAdd();
  HelpView* ensureHelp();
  /** A type chosen in the quick-add box: added where it was opened, with its link if a link opened it. */
  void addChosen(const QString& type, const QString& port);
  /** What a node of the graph is, for its help: its type as listed, else (a subgraph, a type not
   *  listed) its ports and parameters as the node has them. */
  apex::NodeTypeInfo typeOf(const apex::NodeInfo& node) const;
  const apex::NodeTypeInfo* listedType(const std::string& id) const;
  void placeMinimap();
  /** The view's scene rectangle: the boxes with a view's size around them, what is seen, and `also`. */
  void growCanvas(const QRectF& also = QRectF());
  /** Shows the next node whose name or type contains the find field's text (in its subgraph),
   *  selected and centred; says which of how many. */
  void findNext();

  GraphScene* scene_;
  QGraphicsView* view_;
  Minimap* minimap_ = nullptr;
  const GraphModel* model_ = nullptr;
  QLineEdit* namespace_;
  QLineEdit* find_ = nullptr;  ///< finds nodes on the canvas by name or type
  int found_ = -1;  ///< the match shown last
  Palette* palette_ = nullptr;
  QTabWidget* side_ = nullptr;  ///< the palette and the properties
  PropertiesView* properties_ = nullptr;
  std::vector<apex::NodeTypeInfo> types_;  ///< as the runtime listed them, in the palette's order
  QuickAdd* quick_add_ = nullptr;
  QPointF quick_at_;  ///< where the quick-add box adds (scene)
  std::optional<apex::Connection> quick_link_;  ///< the dragged link it completes; its end at the new node without a name
  std::optional<apex::Connection> quick_insert_;  ///< the link it puts a node into
  std::vector<NewInsert> quick_inserts_;  ///< the types offered for quick_insert_, with their ports
  HelpView* help_ = nullptr;
  QPoint last_mouse_{-1, -1};  ///< where the mouse was last over the view (viewport pixels)
  QLabel* message_;
  QLabel* connection_;
  QLabel* unsaved_;  ///< "● unsaved" while the graph differs from its file
  QToolButton *pause_, *undo_, *redo_, *whole_, *trace_, *previews_ = nullptr;
  bool tracing_ = false;
  int added_ = 0;
  QStringList select_when_shown_;
  QStringList presets_;
  std::map<std::string, std::string> message_types_;  ///< port type -> ROS message type, as inspections answered
  bool fit_pending_ = true;
  bool keep_fitted_ = false;  ///< fitted on its own (a new runtime's graph) and not moved by the person since
  QRectF fitted_;  ///< the boxes' bounds at the last fit
  QString last_path_ = defaultGraphFolder();  // where a runtime saves and loads by default (~file_roots)
  QPointer<QFileDialog> file_dialog_;  // Save's or Load's, while open: one at a time
};

}  // namespace apex_rviz_plugin
