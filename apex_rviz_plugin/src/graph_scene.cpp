#include "apex_rviz_plugin/graph_scene.hpp"
#include "apex_rviz_plugin/transport_bar.hpp"

#include <QApplication>
#include <QGraphicsProxyWidget>

#include <QGraphicsSceneContextMenuEvent>
#include <QGraphicsSceneMouseEvent>
#include <QGraphicsSimpleTextItem>
#include <QGraphicsView>
#include <QLabel>
#include <QPainterPath>
#include <QPen>

#include "apex_rviz_plugin/critical_path.hpp"
#include "apex_rviz_plugin/param_editor.hpp"

#include <algorithm>
#include <set>

namespace apex_rviz_plugin {
namespace {

QPainterPath curve(QPointF a, QPointF b) {
  const double dx = std::max(40.0, std::abs(b.x() - a.x()) / 2);
  QPainterPath path(a);
  path.cubicTo(a + QPointF(dx, 0), b - QPointF(dx, 0), b);
  return path;
}

/** Whether `pos` is on the link's curve, within a few pixels: its shape is the area the curve
 *  encloses, which is not the link. */
bool onCurve(const ConnectionItem* c, QPointF pos) { return c->shape().contains(pos); }

}  // namespace

// ------------------------------------------------------------ ConnectionItem

ConnectionItem::ConnectionItem(const apex::Connection& c, PortItem* from, PortItem* to) : c_(c), from_(from), to_(to) {
  restyle();
  setToolTip(QString::fromStdString(c.from_node + "/" + c.from_port + " -> " + c.to_node + "/" + c.to_port +
                                    "\n(right-click: delete it)"));
  reroute();
}

void ConnectionItem::reroute() {
  setPath(curve(from_->scenePos(), to_->scenePos()));
  if (rate_) rate_->setPos(path().pointAtPercent(0.5) - QPointF(rate_->boundingRect().width() / 2, 16));
}

void ConnectionItem::showRate(double per_s, double latency_p95_ms) {
  if (c_.kind != "data") return;
  if (per_s < 0) {
    delete rate_;
    rate_ = nullptr;
    return;
  }
  if (!rate_) {
    rate_ = new QGraphicsSimpleTextItem(this);
    rate_->setBrush(QColor(170, 200, 225));
    QFont f;
    f.setPointSizeF(7.5);
    rate_->setFont(f);
  }
  QString text = QString("%1/s").arg(per_s, 0, 'f', per_s < 10 ? 1 : 0);
  if (latency_p95_ms >= 0)  // from the frame's stamp to this output, 95 in 100 frames within
    text += QString::fromUtf8(" \u00b7 p95 %1 ms").arg(latency_p95_ms, 0, 'f', latency_p95_ms < 10 ? 1 : 0);
  rate_->setText(text);
  reroute();
}

QString ConnectionItem::rateText() const { return rate_ ? rate_->text() : QString(); }

void ConnectionItem::setCritical(bool on) {
  if (on == critical_) return;
  critical_ = on;
  restyle();
}

void ConnectionItem::restyle() {
  QPen pen(critical_                ? QColor(255, 140, 0)
           : c_.kind == "event"     ? QColor(230, 160, 40)
           : c_.kind == "parameter" ? QColor(150, 110, 200)
                                    : QColor(140, 190, 230),
           critical_           ? 4.5
           : c_.kind == "data" ? 2.5
                               : 1.8);
  if (c_.kind == "event") pen.setStyle(Qt::DashLine);
  setPen(pen);
  setZValue(critical_ ? 0.5 : 0);
}

QPainterPath ConnectionItem::shape() const {
  QPainterPathStroker near;  // the drawn line is 2 wide: at a small zoom a click would rarely land on it
  near.setWidth(8);
  return near.createStroke(path());
}

QRectF ConnectionItem::boundingRect() const { return shape().boundingRect(); }

// ---------------------------------------------------------------- GraphScene

GraphScene::GraphScene(QObject* parent) : QGraphicsScene(parent) { setBackgroundBrush(QColor(30, 32, 36)); }

NodeItem* GraphScene::node(const std::string& name) const {
  auto it = nodes_.find(name);
  return it == nodes_.end() ? nullptr : it->second;
}

bool GraphScene::holdsFrame(const apex::GraphState& graph) {
  if (graph.paused) return true;
  for (const auto& n : graph.nodes) {
    if (!TransportBar::isPlayer(n)) continue;
    for (const auto& p : n.parameters)
      if (p.name == "playing" && p.value == "false") return true;
  }
  return false;
}

void GraphScene::show(const GraphModel& model) {
  model_ = &model;
  // A link being dragged goes on through any number of graphs shown (a playing bag changes the
  // graph ten times a second): its port is found again by name below, since a box may be rebuilt.
  std::optional<PortKey> dragging;
  if (drag_from_) dragging = PortKey{drag_from_->node()->info().name, drag_from_->port().name, drag_from_->isSource()};
  drag_from_ = nullptr;
  for (auto* c : connections_) delete c;  // first: they point at ports that may be rebuilt
  connections_.clear();
  auto shown = [this](const std::string& name) {  // a node of the level shown
    const auto slash = name.rfind('/');
    return (slash == std::string::npos ? std::string() : name.substr(0, slash)) == level_;
  };
  bool level_exists = level_.empty();
  for (const auto& n : model.graph().nodes) level_exists = level_exists || (n.name == level_ && !n.subgraph.empty());
  if (!level_exists) {  // the subgraph shown is gone (removed, or a Load)
    resumeDrag(std::nullopt);
    return setLevel("");
  }
  const bool held = holdsFrame(model.graph());
  std::set<std::string> seen;
  for (const auto& n : model.graph().nodes) {
    if (!shown(n.name)) continue;
    seen.insert(n.name);
    NodeItem* item = node(n.name);
    if (!item) {
      item = new NodeItem(n);
      addItem(item);
      nodes_[n.name] = item;
      connect(item, &NodeItem::parameterEdited, this, &GraphScene::parameterEdited);
      connect(item, &NodeItem::interactiveToggled, this, &GraphScene::interactiveToggled);
      connect(item, &NodeItem::moved, this, &GraphScene::dropped);
      connect(item, &NodeItem::slotFired, this, &GraphScene::slotFired);
      connect(item, &NodeItem::paramMenuRequested, this, &GraphScene::paramMenuRequested);
      connect(item, &NodeItem::expandToggled, this, &GraphScene::expandToggled);
      connect(item, &QGraphicsObject::xChanged, this, &GraphScene::reroute);
      connect(item, &QGraphicsObject::yChanged, this, &GraphScene::reroute);
    } else {
      item->update(n);
    }
    item->setZoom(zoom_);
    item->setHeld(held);
    const auto [x, y] = model.position(n.name);
    if (mouseGrabberItem() != item) item->setPos(x, y);
  }
  for (auto it = nodes_.begin(); it != nodes_.end();) {
    if (seen.count(it->first)) {
      ++it;
      continue;
    }
    delete it->second;
    it = nodes_.erase(it);
  }
  for (const auto& c : model.graph().connections) {
    if (c.kind == "export") continue;  // a subgraph's port to the inner one: seen as the subgraph's own
    NodeItem* from = node(c.from_node);
    NodeItem* to = node(c.to_node);
    PortItem* a = from ? from->port(c.from_port, true) : nullptr;
    PortItem* b = to ? to->port(c.to_port, false) : nullptr;
    if (!a || !b) continue;  // a placeholder's ports are unknown here
    connections_.push_back(new ConnectionItem(c, a, b));
    addItem(connections_.back());
  }
  markLinks();
  resumeDrag(dragging);
}

void GraphScene::resumeDrag(const std::optional<PortKey>& from) {
  NodeItem* item = from ? node(from->node) : nullptr;
  drag_from_ = item ? item->port(from->port, from->source) : nullptr;
  if (drag_from_) return markPorts();  // boxes rebuilt or new: their ports marked again
  endDrag();  // the port it started from is gone: no link to make
}

std::map<std::string, Box> GraphScene::boxes() const {
  std::map<std::string, Box> out;
  for (const auto& [name, item] : nodes_) {
    const QRectF r = item->sceneBoundingRect();
    out[name] = Box{item->x(), item->y(), r.width(), r.height()};
  }
  return out;
}

std::vector<std::pair<std::string, std::string>> GraphScene::edges() const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const ConnectionItem* c : connections_) out.emplace_back(c->connection().from_node, c->connection().to_node);
  return out;
}

void GraphScene::dropped(const QString& name, QPointF pos) {
  NodeItem* item = node(name.toStdString());
  const QRectF box = item ? item->sceneBoundingRect() : QRectF();
  for (const ConnectionItem* c : connections_) {  // onto a connection: put in it, if it can be
    if (!item || c->connection().from_node == name.toStdString() || c->connection().to_node == name.toStdString()) continue;
    bool crosses = false;
    for (int i = 1; i < 40 && !crosses; ++i) crosses = box.contains(c->path().pointAtPercent(i / 40.0));
    if (crosses && model_ && model_->insert(name.toStdString(), c->connection(), pos.x(), pos.y()))
      return emit insertRequested(name, c->connection(), pos);
  }
  emit nodeMoved(name, pos);
}

void GraphScene::setLevel(const std::string& path) {
  if (path == level_) return;
  level_ = path;
  endDrag();
  for (auto* c : connections_) delete c;
  connections_.clear();
  for (auto& [name, item] : nodes_) delete item;
  nodes_.clear();
  const std::string shown = level_;  // (`path` may be a name of a box just deleted)
  if (model_) show(*model_);  // first: who follows the level (the editor's Fit) sees its boxes
  if (level_ == shown) emit levelChanged(QString::fromStdString(level_));  // (else show went up: said there)
}

void GraphScene::mouseDoubleClickEvent(QGraphicsSceneMouseEvent* e) {
  if (emptyAt(e->scenePos())) {  // on empty canvas: a node to add there
    emit canvasDoubleClicked(e->scenePos(), e->screenPos());
    return e->accept();
  }
  for (QGraphicsItem* i : items(e->scenePos())) {  // topmost first
    if (dynamic_cast<PortItem*>(i) || dynamic_cast<QGraphicsProxyWidget*>(i)) break;  // theirs
    auto* n = dynamic_cast<NodeItem*>(i);
    if (!n) continue;
    if (n->info().subgraph.empty()) break;
    setLevel(n->info().name);
    return e->accept();
  }
  QGraphicsScene::mouseDoubleClickEvent(e);
}

void GraphScene::showStatus(const apex::RuntimeStatus& status) {
  const double now = status.stamp.toSec();
  forgetGone(status);
  for (const auto& s : status.nodes) {
    NodeItem* item = node(s.name);
    if (!item) continue;
    double rate = 0;  // from the firings since the last status
    auto it = last_status_.find(s.name);
    if (it != last_status_.end() && now > it->second.second && s.firings >= it->second.first)
      rate = (s.firings - it->second.first) / (now - it->second.second);
    last_status_[s.name] = {s.firings, now};
    item->showStatus(s, rate);
  }
  for (const auto& s : status.nodes) {  // each output's messages per second: the rate on its links
    statuses_[s.name] = s;
    for (std::size_t i = 0; i < s.outputs.size() && i < s.sent.size(); ++i) {
      const std::string key = s.name + "/" + s.outputs[i];
      auto it = last_sent_.find(key);
      if (it != last_sent_.end() && now > it->second.second && s.sent[i] >= it->second.first)
        link_rates_[key] = (s.sent[i] - it->second.first) / (now - it->second.second);
      last_sent_[key] = {s.sent[i], now};
    }
  }
  markLinks();
}

void GraphScene::forgetGone(const apex::RuntimeStatus& status) {
  std::set<std::string> there;
  for (const auto& s : status.nodes) there.insert(s.name);
  const auto gone = [&](const std::string& key) {  // "node" or "node/output"
    for (std::string node = key;; node = node.substr(0, node.rfind('/'))) {  // (a node's path has '/' too)
      if (there.count(node)) return false;
      if (node.find('/') == std::string::npos) return true;
    }
  };
  for (auto* m : {&last_status_, &last_sent_})
    for (auto it = m->begin(); it != m->end();) it = gone(it->first) ? m->erase(it) : std::next(it);
  for (auto it = link_rates_.begin(); it != link_rates_.end();) it = gone(it->first) ? link_rates_.erase(it) : std::next(it);
  for (auto it = statuses_.begin(); it != statuses_.end();) it = there.count(it->first) ? std::next(it) : statuses_.erase(it);
}

std::string GraphScene::showCriticalPath(const std::string& node) {
  critical_to_ = node;
  markLinks();
  if (node.empty() || !model_) return "";
  return describeCriticalPath(criticalPath(model_->graph(), statuses_, node), statuses_, node);
}

void GraphScene::markLinks() {
  std::vector<apex::Connection> path;
  if (!critical_to_.empty() && model_) path = criticalPath(model_->graph(), statuses_, critical_to_);
  const auto same = [](const apex::Connection& a, const apex::Connection& b) {
    return a.from_node == b.from_node && a.from_port == b.from_port && a.to_node == b.to_node && a.to_port == b.to_port;
  };
  std::set<std::string> on_path;
  for (const auto& c : path) on_path.insert(c.from_node), on_path.insert(c.to_node);
  for (auto* item : connections_) {
    const auto& c = item->connection();
    const auto rate = link_rates_.find(c.from_node + "/" + c.from_port);
    item->showRate(rate == link_rates_.end() ? -1 : rate->second, outputLatencyP95(c.from_node, c.from_port));
    item->setCritical(std::any_of(path.begin(), path.end(), [&](const apex::Connection& p) { return same(p, c); }));
  }
  for (auto& [name, item] : nodes_) item->setCritical(on_path.count(name) > 0);
}

double GraphScene::outputLatencyP95(const std::string& node, const std::string& output) const {
  const auto s = statuses_.find(node);
  if (s == statuses_.end()) return -1;
  const auto& st = s->second;
  for (std::size_t i = 0; i < st.outputs.size() && i < st.output_latency_p95_ms.size(); ++i)
    if (st.outputs[i] == output) return st.output_latency_p95_ms[i];
  return -1;
}

void GraphScene::showValue(const QString& node_name, const QString& port, const QString& text) {
  if (NodeItem* item = node(node_name.toStdString())) item->showValue(port, text);
}

void GraphScene::setZoom(double scale) {
  zoom_ = scale;
  for (auto& [name, item] : nodes_) item->setZoom(scale);
}

void GraphScene::showImage(const QString& node_name, const QString& port, const QImage& image) {
  if (NodeItem* item = node(node_name.toStdString())) item->showImage(port, image);
}

void GraphScene::showAbout(const QString& node_name, const QString& port, const QString& text) {
  if (NodeItem* item = node(node_name.toStdString())) item->showAbout(port, text);
}

void GraphScene::reroute() {
  for (auto* c : connections_) c->reroute();
}

PortItem* GraphScene::portAt(QPointF pos) const {
  for (QGraphicsItem* i : items(pos))
    if (auto* p = dynamic_cast<PortItem*>(i)) return p;
  return nullptr;
}

bool GraphScene::emptyAt(QPointF pos) const {
  for (QGraphicsItem* i : items(pos)) {
    if (i == drag_line_) continue;
    const auto* c = dynamic_cast<const ConnectionItem*>(i);
    if (!c || onCurve(c, pos)) return false;
  }
  return true;
}

void GraphScene::removeLink(const apex::Connection& c) {
  const auto same = [&c](const ConnectionItem* i) {
    const apex::Connection& o = i->connection();
    return o.from_node == c.from_node && o.from_port == c.from_port && o.to_node == c.to_node && o.to_port == c.to_port;
  };
  const auto it = std::find_if(connections_.begin(), connections_.end(), same);
  if (it != connections_.end()) delete *it, connections_.erase(it);  // gone from the canvas now, not at the next graph
  emit disconnectRequested(c);
}

std::pair<QString, QString> GraphScene::paramAt(QPointF pos) const {
  for (QGraphicsItem* i : items(pos)) {  // topmost first: the box's widgets, if any
    auto* proxy = dynamic_cast<QGraphicsProxyWidget*>(i);
    auto* node = proxy ? dynamic_cast<NodeItem*>(proxy->parentItem()) : nullptr;
    if (!node || !proxy->widget()) continue;
    QWidget* under = proxy->widget()->childAt(proxy->mapFromScene(pos).toPoint());
    auto* editor = qobject_cast<ParamEditor*>(under);
    if (!editor && qobject_cast<QLabel*>(under)) editor = qobject_cast<ParamEditor*>(under->parentWidget());
    if (!editor) return {};
    return {QString::fromStdString(node->info().name), QString::fromStdString(editor->param().name)};
  }
  return {};
}

void GraphScene::beginConnect(PortItem* from) {
  endDrag();
  drag_from_ = from;
  drag_line_ = addPath(QPainterPath(), QPen(QColor(255, 255, 255), 2, Qt::DotLine));
  drag_line_->setZValue(5);
  markPorts();
}

void GraphScene::markPorts() {
  PortItem* from = drag_from_;
  const std::string node = from->node()->info().name, port = from->port().name;
  for (const auto& [name, item] : nodes_) {
    for (PortItem* p : item->ports()) {
      if (p->isSource() == from->isSource()) continue;  // the ports at the link's other end
      const std::string& other = p->port().name;
      const std::string why = !model_            ? ""
                              : from->isSource() ? model_->whyNotReplacing(node, port, name, other)
                                                 : model_->whyNotReplacing(name, other, node, port);
      p->setMark(why.empty() ? PortItem::Mark::Accepts : PortItem::Mark::Refuses, QString::fromStdString(why));
    }
  }
}

void GraphScene::mouseMoveEvent(QGraphicsSceneMouseEvent* e) {
  if (!drag_from_) return QGraphicsScene::mouseMoveEvent(e);
  const QPointF at = drag_from_->scenePos();  // the curve always runs from the output to the input
  drag_line_->setPath(drag_from_->isSource() ? curve(at, e->scenePos()) : curve(e->scenePos(), at));
}

void GraphScene::mouseReleaseEvent(QGraphicsSceneMouseEvent* e) {
  if (!drag_from_) return QGraphicsScene::mouseReleaseEvent(e);
  PortItem* target = portAt(e->scenePos());
  QGraphicsScene::mouseReleaseEvent(e);  // the port that started the drag lets go of the mouse
  finishConnect(target, e);
}

void GraphScene::finishConnect(PortItem* target, QGraphicsSceneMouseEvent* e) {
  PortItem* from = drag_from_;
  const QString node = QString::fromStdString(from->node()->info().name), port = QString::fromStdString(from->port().name);
  const bool source = from->isSource();
  const bool moved =
      (e->screenPos() - e->buttonDownScreenPos(Qt::LeftButton)).manhattanLength() >= QApplication::startDragDistance();
  endDrag();
  if (!target && moved && emptyAt(e->scenePos())) return emit linkDropped(node, port, source, e->scenePos(), e->screenPos());
  if (!target || target->isSource() == source) return;
  PortItem* out = source ? from : target;
  PortItem* in = source ? target : from;
  apex::Connection c;
  c.from_node = out->node()->info().name, c.from_port = out->port().name;
  c.to_node = in->node()->info().name, c.to_port = in->port().name;
  const std::string why = model_ ? model_->whyNotReplacing(c.from_node, c.from_port, c.to_node, c.to_port) : "";
  if (!why.empty()) emit refused(QString::fromStdString("cannot connect: " + why));
  else emit connectRequested(c);
}

void GraphScene::endDrag() {
  drag_from_ = nullptr;
  if (!drag_line_) return;  // no drag
  delete drag_line_;
  drag_line_ = nullptr;
  for (const auto& [name, item] : nodes_)
    for (PortItem* p : item->ports()) p->setMark(PortItem::Mark::None);
}

void GraphScene::contextMenuEvent(QGraphicsSceneContextMenuEvent* e) {
  // A parameter's name: its menu, here. Passed to the box's widgets it would need the box to have
  // the keyboard focus (QGraphicsProxyWidget drops it otherwise, as accepted: nothing showed).
  const auto [node_name, param] = paramAt(e->scenePos());
  if (!param.isEmpty()) {
    emit paramMenuRequested(node_name, param, e->screenPos());
    return e->accept();
  }
  QGraphicsScene::contextMenuEvent(e);  // proxied widgets first
  if (e->isAccepted()) return;
  for (QGraphicsItem* i : items(e->scenePos())) {
    if (auto* p = dynamic_cast<PortItem*>(i)) {
      emit portMenuRequested(QString::fromStdString(p->node()->info().name), QString::fromStdString(p->port().name),
                             e->screenPos());
      return e->accept();
    }
    if (auto* c = dynamic_cast<ConnectionItem*>(i); c && onCurve(c, e->scenePos())) {
      emit linkMenuRequested(c->connection(), e->screenPos());
      return e->accept();
    }
    if (auto* n = dynamic_cast<NodeItem*>(i)) {
      emit nodeMenuRequested(QString::fromStdString(n->info().name), e->screenPos());
      return e->accept();
    }
  }
  emit canvasMenuRequested(e->scenePos(), e->screenPos());
  e->accept();
}

}  // namespace apex_rviz_plugin
