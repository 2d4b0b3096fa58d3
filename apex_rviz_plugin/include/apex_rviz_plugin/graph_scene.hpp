// The graph drawn: nodes as boxes (inputs left, outputs right, slots and
// triggers as diamonds, parameter ports as squares, parameter widgets inside),
// connections as curves. Dragging from an output shows which inputs would take
// it. Everything a person does comes out as a signal; no ROS, no service calls.
#pragma once

#include <QGraphicsObject>
#include <QGraphicsPathItem>
#include <QGraphicsScene>
#include <QImage>

#include <apex/RuntimeStatus.h>

#include <map>
#include <optional>

#include "apex_rviz_plugin/box_name.hpp"
#include "apex_rviz_plugin/box_view.hpp"
#include "apex_rviz_plugin/graph_model.hpp"
#include "apex_rviz_plugin/layout.hpp"

class QGraphicsProxyWidget;
class QGraphicsSimpleTextItem;
class QToolButton;

namespace apex_rviz_plugin {

class ParamEditor;
class NodeItem;
class TransportBar;

/** @brief One port: where connections end and drags start. */
class PortItem : public QGraphicsItem {
 public:
  enum class Mark { None, Accepts, Refuses };
  static constexpr double kRadius = 5;

  PortItem(const apex::PortInfo& port, NodeItem* parent);
  const apex::PortInfo& port() const { return port_; }
  NodeItem* node() const;
  bool isSource() const;  ///< output, trigger or parameter output
  void setMark(Mark m, const QString& why = {});

  QRectF boundingRect() const override;
  void paint(QPainter* p, const QStyleOptionGraphicsItem*, QWidget*) override;

 protected:
  void mousePressEvent(QGraphicsSceneMouseEvent* e) override;
  void mouseDoubleClickEvent(QGraphicsSceneMouseEvent* e) override;  ///< on an output: inspect it
  void hoverEnterEvent(QGraphicsSceneHoverEvent* e) override;  ///< the tooltip, with what it carried last

 private:
  apex::PortInfo port_;
  Mark mark_ = Mark::None;
};

/** @brief A node's box; moved by dragging its title. */
class NodeItem : public QGraphicsObject {
  Q_OBJECT
 public:
  /** Boxes are as wide as their names, port labels and parameter values need, within these. */
  static constexpr double kMinWidth = 230, kMaxWidth = 480;

  explicit NodeItem(const apex::NodeInfo& node);
  const apex::NodeInfo& info() const { return info_; }
  double width() const { return width_; }
  /** @brief Shows a newer description; rebuilds the ports and widgets only if they changed. */
  void update(const apex::NodeInfo& node);
  /** @brief An orange outline: on the critical path the panel shows. */
  void setCritical(bool on);
  bool critical() const { return critical_; }
  void showStatus(const apex::NodeStatus& status, double rate_hz);
  void showValue(const QString& port, const QString& text);
  /** @brief Draws previews of the outputs that carry images (thumbnails) or numbers
   *  (sparklines) in the box, which grows for them. */
  void setPreviews(bool on);
  bool previews() const { return previews_; }
  /** @brief The outputs a preview is drawn for. */
  std::vector<std::string> previewPorts() const;
  void showImage(const QString& port, const QImage& image);
  /** @brief What the output's last previewed message was (e.g. an image's real size). */
  void showAbout(const QString& port, const QString& text) { abouts_[port.toStdString()] = text; }
  /** @brief The last preview image of an output, and the last values of a numeric one. */
  QImage image(const std::string& port) const {
    auto it = images_.find(port);
    return it == images_.end() ? QImage() : it->second;
  }
  std::size_t samples(const std::string& port) const {
    auto it = series_.find(port);
    return it == series_.end() ? 0 : it->second.size();
  }
  /** @brief At the view's scale: full detail (port labels, widgets, timing) from
   *  GraphScene::kDetailScale, else the name alone, as large as the box holds it (BoxName). */
  void setZoom(double scale);
  bool detailed() const { return detail_; }
  /** @brief The graph holds a frame (GraphScene::holdsFrame): a node that keeps something from
   *  frame to frame (NodeInfo::keeps) says that the re-runs change it. */
  void setHeld(bool held);
  /** @brief What the box says of a held frame: "" unless the graph holds one and the node keeps something. */
  QString heldNote() const;
  /** @brief The name as drawn at the zoom set: on the title bar, or alone, zoomed out. */
  BoxName name() const;
  /** @brief Where the name is drawn zoomed out: the box above its previews. */
  QRectF nameArea() const;
  /** @brief How tall the name's letters are on screen, in pixels (the font's size at the zoom). */
  double namePixels() const;
  /** @brief What a port is and what it carried last: its tooltip. */
  QString portTip(const apex::PortInfo& port) const;
  PortItem* port(const std::string& name, bool source) const;
  const std::vector<PortItem*>& ports() const { return ports_; }
  /** @brief The editor of a parameter the box shows, nullptr for one it does not (BoxView). */
  ParamEditor* editor(const std::string& param) const;
  /** @brief The toggle between the compact and the expanded box, nullptr if it has none. */
  QToolButton* expandToggle() const { return toggle_; }
  /** @brief What the box shows from ~status, e.g. "0.12 ms (p95 0.50) · 10.0 Hz · 42 firings". */
  const QString& timing() const { return timing_; }
  const QString& waiting() const { return waiting_; }
  std::uint64_t firings() const { return firings_; }
  /** @brief Inspected scalar values shown in the box, e.g. "count = 42". */
  const QString& values() const { return values_; }
  /** @brief A player's transport bar, nullptr for other nodes. */
  TransportBar* transport() const { return transport_; }
  /** @brief An Optimizer's best fitness after each evaluation of its current run (plotted). */
  const std::vector<double>& fitnessHistory() const { return fitness_; }
  /** @brief An Optimizer's evaluations so far in its current run. */
  int evaluations() const { return evaluations_; }

  QRectF boundingRect() const override;
  void paint(QPainter* p, const QStyleOptionGraphicsItem*, QWidget*) override;

 signals:
  /** `dragging`: a value of a slider drag going on (one undo step with the drag's last value). */
  void parameterEdited(const QString& node, const QString& param, const QString& yaml, bool dragging = false);
  void interactiveToggled(const QString& node, const QString& param, bool interactive);
  void moved(const QString& node, QPointF pos);
  void slotFired(const QString& node, const QString& slot);
  void paramMenuRequested(const QString& node, const QString& param, QPoint screen_pos);
  /** The box's toggle: every parameter, or the compact box (BoxView). */
  void expandToggled(const QString& node, bool expanded);

 protected:
  void mouseReleaseEvent(QGraphicsSceneMouseEvent* e) override;
  QVariant itemChange(GraphicsItemChange change, const QVariant& value) override;

 private:
  void build();
  void updateToolTip();
  /** The editors of the parameters shown (BoxView), a player's transport bar and the toggle
   *  between compact and expanded, in one widget, not yet placed. */
  QWidget* buildParams();
  /** What the ui metadata says of the box, with a player's frame slider and transport bar. */
  BoxView boxView() const;
  /** What the parameters' part of the box shows: rebuilt when it changes. */
  std::string paramsKey() const;
  QString shortName() const;
  QString title() const;
  /** The line under the title: the type and thread group, or what subgraph it is. */
  QString kindLine() const;
  /** The width the title, the type line and the port labels need (the editors add theirs). */
  double textWidth() const;
  /** The box's width for its text and `params` (its editors; those shown if null), within limits. */
  double wantedWidth(const QWidget* params = nullptr) const;
  bool isOptimizer() const;
  /** An Optimizer's progress: evaluations of the budget, best fitness, and its curve. */
  void paintProgress(QPainter* p, const QRectF& area) const;
  void paintPreviews(QPainter* p) const;

  apex::NodeInfo info_;
  std::vector<PortItem*> ports_;
  std::map<std::string, ParamEditor*> editors_;
  TransportBar* transport_ = nullptr;  // in params_, for players
  QToolButton* toggle_ = nullptr;  // in params_: compact or expanded
  std::string params_key_;  // paramsKey() when built
  QGraphicsProxyWidget* params_ = nullptr;
  QString timing_, values_;
  QString waiting_;  // what a stalled node waits for (the runtime says)
  bool critical_ = false;  // on the critical path the panel shows: an orange outline
  std::uint64_t firings_ = 0;
  std::map<QString, QString> scalar_values_;
  std::vector<double> fitness_;  // Optimizer: best fitness per evaluation of the current run
  int evaluations_ = 0;
  bool previews_ = false;
  bool detail_ = true;
  bool held_ = false;
  double zoom_ = 1;
  double preview_top_ = 0;  // where the previews start in the box
  std::map<std::string, QImage> images_;  // previews: the last thumbnail per output
  std::map<std::string, QString> abouts_;  // previews: what the last message was per output
  std::map<std::string, std::vector<double>> series_;  // previews: the last values per output
  double rate_hz_ = 0;
  double width_ = kMinWidth, height_ = 60;
  bool dragged_ = false;
};

/** @brief A connection as a curve from its output to its input. */
class ConnectionItem : public QGraphicsPathItem {
 public:
  ConnectionItem(const apex::Connection& c, PortItem* from, PortItem* to);
  const apex::Connection& connection() const { return c_; }
  void reroute();
  /** A band 8 units wide along the curve: a click that near it is on it (hit tests, menus). */
  QPainterPath shape() const override;
  QRectF boundingRect() const override;
  /** @brief Writes the messages per second its output sends beside the curve's middle, and the
   *  95th percentile of that output's latency from its frames' stamps when it has one (a data
   *  link; a negative rate: none known yet, nothing written; a negative latency: none shown). */
  void showRate(double per_s, double latency_p95_ms = -1);
  /** @brief The rate written on it ("12/s", "12/s · p95 8.5 ms"), empty if none. */
  QString rateText() const;
  /** @brief Drawn thick and orange: on the critical path the panel shows. */
  void setCritical(bool on);
  bool critical() const { return critical_; }

 private:
  void restyle();

  apex::Connection c_;
  PortItem* from_;
  PortItem* to_;
  QGraphicsSimpleTextItem* rate_ = nullptr;  // a child: moves and goes with the link
  bool critical_ = false;
};

class GraphScene : public QGraphicsScene {
  Q_OBJECT
 public:
  explicit GraphScene(QObject* parent = nullptr);
  /** @brief Draws the model's graph, keeping the items (and widgets being used) of unchanged nodes. */
  void show(const GraphModel& model);
  void showStatus(const apex::RuntimeStatus& status);
  /** @brief Colours the critical path to `node` (critical_path.hpp), followed live as statuses
   *  come; "" takes it off. Returns the path as the message says it. */
  std::string showCriticalPath(const std::string& node);
  const std::string& criticalTarget() const { return critical_to_; }
  void showValue(const QString& node, const QString& port, const QString& text);
  void showImage(const QString& node, const QString& port, const QImage& image);
  void showAbout(const QString& node, const QString& port, const QString& text);
  NodeItem* node(const std::string& name) const;
  /** @brief Whether the graph holds a frame that edits re-run: it is paused, or a player is. */
  static bool holdsFrame(const apex::GraphState& graph);
  /** @brief The view's scale: below kDetailScale nodes show their names large, without
   *  port labels and widgets (as map viewers drop detail when zoomed out). */
  void setZoom(double scale);
  /** The title bar's name (9.5 pt, 12.7 px) is 10 px on screen from this scale on. */
  static constexpr double kDetailScale = 0.8;
  /** @brief The nodes shown, by name. */
  const std::map<std::string, NodeItem*>& nodes() const { return nodes_; }
  /** @brief The subgraph shown ("" the top level): its nodes and the connections between them. */
  const std::string& level() const { return level_; }
  /** @brief Shows another level (a subgraph's path, or "" for the top). */
  void setLevel(const std::string& path);
  const std::vector<ConnectionItem*>& connections() const { return connections_; }
  /** @brief The boxes of the nodes shown (position and size), by name. */
  std::map<std::string, Box> boxes() const;
  /** @brief The connections shown, as (from node, to node). */
  std::vector<std::pair<std::string, std::string>> edges() const;

  /** @brief Starts dragging a connection from a port (called by the port): from an output,
   *  trigger or parameter output to an input, slot or parameter input, or the other way round. */
  void beginConnect(PortItem* from);
  /** @brief Whether nothing is at `pos`: no box, port or widget, no link within a few pixels. */
  bool emptyAt(QPointF pos) const;
  /** @brief Takes link `c` off the canvas at once and asks for its removal (disconnectRequested);
   *  the next graph shown draws it again if the runtime refused. */
  void removeLink(const apex::Connection& c);

 signals:
  void connectRequested(const apex::Connection& c);
  void disconnectRequested(const apex::Connection& c);
  void refused(const QString& why);
  /** `dragging`: a value of a slider drag going on (one undo step with the drag's last value). */
  void parameterEdited(const QString& node, const QString& param, const QString& yaml, bool dragging = false);
  void interactiveToggled(const QString& node, const QString& param, bool interactive);
  void nodeMoved(const QString& node, QPointF pos);
  /** A node with no connections dropped onto connection `c`: to be put in it. */
  void insertRequested(const QString& node, const apex::Connection& c, QPointF pos);
  void nodeMenuRequested(const QString& node, QPoint screen_pos);
  /** A right-click on empty canvas, at a scene and a screen position. */
  void canvasMenuRequested(QPointF scene_pos, QPoint screen_pos);
  /** A double-click on empty canvas, at a scene and a screen position. */
  void canvasDoubleClicked(QPointF scene_pos, QPoint screen_pos);
  /** A link dragged from node/port (an output, trigger or parameter output if `source`) and let
   *  go on empty canvas, at a scene and a screen position: a new node for its other end. */
  void linkDropped(const QString& node, const QString& port, bool source, QPointF scene_pos, QPoint screen_pos);
  void portMenuRequested(const QString& node, const QString& port, QPoint screen_pos);
  /** A right-click on a link, at a screen position. */
  void linkMenuRequested(const apex::Connection& c, QPoint screen_pos);
  void inspectRequested(const QString& node, const QString& port);
  void slotFired(const QString& node, const QString& slot);
  void paramMenuRequested(const QString& node, const QString& param, QPoint screen_pos);
  void expandToggled(const QString& node, bool expanded);
  void levelChanged(const QString& path);

 protected:
  void mouseMoveEvent(QGraphicsSceneMouseEvent* e) override;
  void mouseReleaseEvent(QGraphicsSceneMouseEvent* e) override;
  void contextMenuEvent(QGraphicsSceneContextMenuEvent* e) override;
  void mouseDoubleClickEvent(QGraphicsSceneMouseEvent* e) override;  ///< on a subgraph: opens it

 private:
  void reroute();
  /** A node dragged and let go: onto a connection it fits in, an insert; else a move. */
  void dropped(const QString& node, QPointF pos);
  PortItem* portAt(QPointF pos) const;
  /** The node and parameter whose name (its label, or its editor's empty space) is at `pos`;
   *  empty if none (elsewhere, or on a field or slider that has its own handling). */
  std::pair<QString, QString> paramAt(QPointF pos) const;
  /** The dragged link let go at `e` on port `target` (nullptr: none): connected if the rules allow. */
  void finishConnect(PortItem* target, QGraphicsSceneMouseEvent* e);
  void endDrag();
  /** A port by name: what a link being dragged started from, across graphs shown. */
  struct PortKey {
    std::string node, port;
    bool source = false;
  };
  /** After a graph is shown: the drag goes on from `from`'s port as now shown, or ends if it is gone. */
  void resumeDrag(const std::optional<PortKey>& from);
  /** Marks each port as accepting or refusing the link being dragged from drag_from_. */
  void markPorts();

  const GraphModel* model_ = nullptr;
  std::string level_;
  std::map<std::string, NodeItem*> nodes_;
  double zoom_ = 1;
  std::vector<ConnectionItem*> connections_;
  std::map<std::string, std::pair<std::uint64_t, double>> last_status_;  ///< firings at a stamp
  std::map<std::string, std::pair<std::uint64_t, double>> last_sent_;  ///< "node/output": messages at a stamp
  std::map<std::string, double> link_rates_;  ///< "node/output": messages per second, from the last two statuses
  std::map<std::string, apex::NodeStatus> statuses_;  ///< the newest of each node
  std::string critical_to_;  ///< the node whose critical path is coloured ("" none)
  /** Rates and the critical path onto the links (rebuilt with every graph shown). */
  void markLinks();
  /** Drops what it kept of nodes no longer in the runtime's status (removed, renamed). */
  void forgetGone(const apex::RuntimeStatus& status);
  /** The p95 latency (ms) of an output in its node's newest status; -1 if none. */
  double outputLatencyP95(const std::string& node, const std::string& output) const;
  PortItem* drag_from_ = nullptr;
  QGraphicsPathItem* drag_line_ = nullptr;
};

}  // namespace apex_rviz_plugin
