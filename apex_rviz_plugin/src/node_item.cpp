#include <algorithm>
#include <cmath>

#include <QGraphicsProxyWidget>
#include <QGraphicsSceneMouseEvent>
#include <QFontInfo>
#include <QFontMetricsF>
#include <QPainter>
#include <QToolButton>
#include <QVBoxLayout>
#include <QWidget>

#include "apex_rviz_plugin/box_view.hpp"
#include "apex_rviz_plugin/graph_scene.hpp"
#include "apex_rviz_plugin/optimizer_plot.hpp"
#include "apex_rviz_plugin/param_editor.hpp"
#include "apex_rviz_plugin/transport_bar.hpp"
#include "apex/core/description.hpp"

namespace apex_rviz_plugin {
namespace {

constexpr double kTitle = 38, kRow = 18, kPad = 6, kPlot = 56, kThumb = 110, kSpark = 30;

bool imageType(const std::string& t) { return t == "apex_nodes/Image"; }
bool numberType(const std::string& t) { return t == "int" || t == "double" || t == "bool"; }

bool sourceKind(const std::string& k) { return k == "output" || k == "trigger" || k == "param_out"; }
bool eventKind(const std::string& k) { return k == "slot" || k == "trigger"; }
bool paramKind(const std::string& k) { return k == "param_in" || k == "param_out"; }

/** Same ports and parameters (by name and kind): the widgets can stay. */
bool sameShape(const apex::NodeInfo& a, const apex::NodeInfo& b) {
  if (a.ports.size() != b.ports.size() || a.parameters.size() != b.parameters.size() || a.type != b.type) return false;
  for (std::size_t i = 0; i < a.ports.size(); ++i)
    if (a.ports[i].name != b.ports[i].name || a.ports[i].kind != b.ports[i].kind) return false;
  for (std::size_t i = 0; i < a.parameters.size(); ++i)
    if (a.parameters[i].name != b.parameters[i].name || a.parameters[i].kind != b.parameters[i].kind ||
        a.parameters[i].min != b.parameters[i].min || a.parameters[i].max != b.parameters[i].max)
      return false;  // e.g. a player's frame range after another bag
  return true;
}

QColor groupColor(const std::string& group) {
  if (group.empty() || group == apex::kDefaultGroup) return QColor(70, 90, 120);
  return QColor::fromHsv(static_cast<int>(std::hash<std::string>()(group) % 360), 110, 150);
}

}  // namespace

// ------------------------------------------------------------------ PortItem

PortItem::PortItem(const apex::PortInfo& port, NodeItem* parent) : QGraphicsItem(parent), port_(port) {
  setToolTip(parent->portTip(port));
  setAcceptedMouseButtons(Qt::LeftButton);
  setAcceptHoverEvents(true);
}

void PortItem::hoverEnterEvent(QGraphicsSceneHoverEvent* e) {
  if (mark_ == Mark::None) setToolTip(node()->portTip(port_));  // a drag's mark says why instead
  QGraphicsItem::hoverEnterEvent(e);
}

NodeItem* PortItem::node() const { return static_cast<NodeItem*>(parentItem()); }
bool PortItem::isSource() const { return sourceKind(port_.kind); }

void PortItem::setMark(Mark m, const QString& why) {
  mark_ = m;
  setToolTip(why.isEmpty() ? node()->portTip(port_) : why);
  update();
}

QRectF PortItem::boundingRect() const {
  const double w = node()->width() / 2;
  return isSource() ? QRectF(-w, -kRow / 2, w + kRadius + 1, kRow) : QRectF(-kRadius - 1, -kRow / 2, w, kRow);
}

void PortItem::paint(QPainter* p, const QStyleOptionGraphicsItem*, QWidget*) {
  p->setRenderHint(QPainter::Antialiasing);
  QColor fill = eventKind(port_.kind)   ? QColor(230, 160, 40)
                : paramKind(port_.kind) ? QColor(150, 110, 200)
                                        : QColor(80, 160, 220);
  if (mark_ == Mark::Accepts) fill = QColor(60, 200, 60);
  if (mark_ == Mark::Refuses) fill = QColor(210, 50, 50);
  p->setBrush(fill);
  p->setPen(QPen(Qt::black, 1));
  const double r = kRadius;
  if (eventKind(port_.kind)) {  // slots and triggers: diamonds
    p->drawPolygon(QPolygonF({QPointF(0, -r - 1), QPointF(r + 1, 0), QPointF(0, r + 1), QPointF(-r - 1, 0)}));
  } else if (paramKind(port_.kind)) {  // parameter ports: squares
    p->drawRect(QRectF(-r + 1, -r + 1, 2 * r - 2, 2 * r - 2));
  } else {
    p->drawEllipse(QPointF(0, 0), r, r);
  }
  if (!node()->detailed()) return;  // zoomed out: the dot alone
  p->setPen(Qt::white);
  QFont f = p->font();
  f.setPointSizeF(8);
  f.setItalic(port_.optional);
  p->setFont(f);
  const QString label = QString::fromStdString(port_.name);
  const double half = node()->width() / 2;
  if (isSource()) p->drawText(QRectF(-half, -kRow / 2, half - 10, kRow), Qt::AlignRight | Qt::AlignVCenter, label);
  else p->drawText(QRectF(10, -kRow / 2, half - 12, kRow), Qt::AlignLeft | Qt::AlignVCenter, label);
}

void PortItem::mousePressEvent(QGraphicsSceneMouseEvent* e) {  // a link from here: from an output or to an input
  if (auto* s = qobject_cast<GraphScene*>(scene())) s->beginConnect(this);
  e->accept();
}

void PortItem::mouseDoubleClickEvent(QGraphicsSceneMouseEvent* e) {
  if (port_.kind != "output" && port_.kind != "param_out") return e->ignore();
  if (auto* s = qobject_cast<GraphScene*>(scene()))
    emit s->inspectRequested(QString::fromStdString(node()->info().name), QString::fromStdString(port_.name));
  e->accept();
}

// ------------------------------------------------------------------ NodeItem

NodeItem::NodeItem(const apex::NodeInfo& node) : info_(node) {
  setFlags(ItemIsMovable | ItemIsSelectable | ItemSendsGeometryChanges);
  setZValue(1);
  build();
}

void NodeItem::update(const apex::NodeInfo& node) {
  const bool rebuild = !sameShape(info_, node);
  info_ = node;
  if (rebuild) return build();
  for (const auto& p : info_.parameters)
    if (auto* e = editor(p.name)) e->showApplied(p);
  const bool typing = params_ && params_->widget()->focusWidget();  // not rebuilt under the keyboard
  if (!typing && paramsKey() != params_key_) return build();  // expanded, collapsed, pinned, or a value set
  if (!typing && wantedWidth() != width_) return build();  // a longer path, group or type: wider
  if (transport_) transport_->show(info_);
  updateToolTip();
  QGraphicsObject::update();
}

void NodeItem::build() {
  prepareGeometryChange();
  for (auto* p : ports_) delete p;
  ports_.clear();
  if (params_) delete params_;  // deletes its widget and the editors in it
  params_ = nullptr;
  editors_.clear();
  transport_ = nullptr;
  toggle_ = nullptr;
  params_key_ = paramsKey();
  QWidget* box = info_.parameters.empty() ? nullptr : buildParams();
  width_ = wantedWidth(box);
  double left = kTitle + kRow / 2, right = left;
  for (const auto& p : info_.ports) {
    auto* item = new PortItem(p, this);
    const bool src = item->isSource();
    item->setPos(src ? width_ : 0, src ? right : left);
    (src ? right : left) += kRow;
    ports_.push_back(item);
  }
  height_ = std::max(left, right) - kRow / 2 + kPad;
  if (box) {
    box->setFixedWidth(static_cast<int>(width_ - 2 * kPad));
    box->adjustSize();
    params_ = new QGraphicsProxyWidget(this);
    params_->setWidget(box);
    params_->setPos(kPad, height_);
    params_->setVisible(detail_);  // rebuilt while zoomed out: hidden, as before
    height_ += box->height() + kPad;
  }
  preview_top_ = height_;
  if (previews_)
    for (const auto& name : previewPorts()) height_ += imageType(port(name, true)->port().type) ? kThumb + 4 : kSpark;
  if (isOptimizer()) height_ += kPlot;  // its progress
  height_ += 2 * kRow;  // timing and error lines
  updateToolTip();
}

QWidget* NodeItem::buildParams() {
  auto* box = new QWidget;
  box->setObjectName(QString::fromStdString("params_" + info_.name));
  auto* column = new QVBoxLayout(box);
  column->setContentsMargins(4, 2, 4, 2);
  column->setSpacing(2);
  const QString node = QString::fromStdString(info_.name);
  if (TransportBar::isPlayer(info_)) {
    transport_ = new TransportBar(info_);
    column->addWidget(transport_);
    connect(transport_, &TransportBar::parameterEdited, this,
            [this, node](const QString& n, const QString& v) { emit parameterEdited(node, n, v); });
    connect(transport_, &TransportBar::slotFired, this, [this, node](const QString& slot) { emit slotFired(node, slot); });
  }
  const BoxView view = boxView();
  const std::vector<std::string> shown = view.shown(info_);
  for (const auto& p : info_.parameters) {
    if (std::find(shown.begin(), shown.end(), p.name) == shown.end()) continue;
    auto* e = editorFor(p, node, this);
    editors_[p.name] = e;
    column->addWidget(e);
  }
  BoxView compact = view;
  compact.expanded = false;
  const std::size_t hidden = view.hidden(info_);
  // a box of few parameters shows them all with no toggle; one that would leave none out has none
  if (hidden > 0 || (view.isExpanded(info_) && view.collapsible(info_) && compact.hidden(info_) > 0)) {
    toggle_ = new QToolButton;
    toggle_->setObjectName("expand");
    toggle_->setAutoRaise(true);
    toggle_->setText(hidden > 0 ? QString("▸ %1 more parameter%2").arg(hidden).arg(hidden == 1 ? "" : "s")
                                : QString("▴ fewer parameters"));
    toggle_->setToolTip(hidden > 0 ? "show every parameter"
                                   : "show only the pinned parameters and those set away from their defaults");
    column->addWidget(toggle_, 0, Qt::AlignLeft);
    connect(toggle_, &QToolButton::clicked, this, [this, node, expand = hidden > 0] { emit expandToggled(node, expand); });
  }
  QFont small = box->font();  // as the node's own text: rviz's default font is larger
  small.setPointSizeF(8);
  box->setFont(small);
  return box;
}

BoxView NodeItem::boxView() const {
  BoxView view = BoxView::of(info_.ui);
  if (TransportBar::isPlayer(info_)) view.always = {"frame"}, view.elsewhere = {"playing", "time"};
  return view;
}

std::string NodeItem::paramsKey() const {
  const BoxView view = boxView();
  std::string key = view.isExpanded(info_) ? "+" : "-";
  for (const auto& name : view.shown(info_)) key += name + ",";
  return key;
}

QString NodeItem::shortName() const {  // inside a subgraph: its own name
  return QString::fromStdString(info_.name.substr(info_.name.rfind('/') + 1));
}

QString NodeItem::title() const { return info_.enabled ? shortName() : shortName() + "  (disabled)"; }

QString NodeItem::kindLine() const {
  if (!info_.subgraph.empty())  // a subgraph has no group of its own: its nodes do
    return QString::fromStdString("subgraph  " + (info_.subgraph == "inline" ? std::string("(inline)") : info_.subgraph) +
                                  "  · double-click to open");
  return QString::fromStdString(apex_rviz_plugin::kindLine(info_.type, info_.thread_group));
}

double NodeItem::wantedWidth(const QWidget* params) const {
  if (!params && params_) params = params_->widget();
  const double wanted = std::max(textWidth(), params ? params->sizeHint().width() + 2 * kPad : 0.0);
  return std::clamp(std::ceil(wanted), kMinWidth, kMaxWidth);
}

double NodeItem::textWidth() const {
  QFont bold;
  bold.setBold(true);
  bold.setPointSizeF(9.5);
  QFont small;
  small.setPointSizeF(7.5);
  QFont label;
  label.setPointSizeF(8);
  const QFontMetricsF b(bold), s(small), l(label);
  double wide = std::max(b.horizontalAdvance(shortName() + "  (disabled)"), s.horizontalAdvance(kindLine()));  // either way
  std::vector<double> in, out;  // label widths per row, each side
  for (const auto& p : info_.ports)
    (sourceKind(p.kind) ? out : in).push_back(l.horizontalAdvance(QString::fromStdString(p.name)));
  for (std::size_t row = 0; row < std::max(in.size(), out.size()); ++row)
    wide = std::max(wide, (row < in.size() ? in[row] : 0) + (row < out.size() ? out[row] : 0) + 30);
  return wide + 2 * kPad;
}

void NodeItem::setCritical(bool on) {
  if (on == critical_) return;
  critical_ = on;
  QGraphicsObject::update();
}

void NodeItem::showStatus(const apex::NodeStatus& s, double rate_hz) {
  timing_ = QString("%1 ms (p95 %2) · %3 Hz · ").arg(s.mean_ms, 0, 'f', 2).arg(s.p95_ms, 0, 'f', 2).arg(rate_hz, 0, 'f', 1);
  // live frames: how old they are (since their stamp) when this node is done with them
  timing_ += s.latency_ms >= 0 ? QString("stamp +%1 ms").arg(s.latency_p50_ms, 0, 'f', 1) : QString("%1 firings").arg(s.firings);
  firings_ = s.firings;
  rate_hz_ = rate_hz;
  info_.state = s.state;
  info_.error = s.error;
  waiting_ = QString::fromStdString(s.waiting_for);
  updateToolTip();
  QGraphicsObject::update();
}

bool NodeItem::isOptimizer() const { return info_.type == kOptimizerType; }

std::vector<std::string> NodeItem::previewPorts() const {
  std::vector<std::string> out;
  for (const auto& p : info_.ports)
    if (p.kind == "output" && (imageType(p.type) || numberType(p.type))) out.push_back(p.name);
  return out;
}

void NodeItem::setPreviews(bool on) {
  if (on == previews_) return;
  previews_ = on;
  if (!on) images_.clear(), series_.clear(), abouts_.clear();
  build();
}

void NodeItem::setZoom(double scale) {
  const bool full = scale >= GraphScene::kDetailScale;
  if (full == detail_ && (full || scale == zoom_)) return;
  zoom_ = scale;
  detail_ = full;
  if (params_) params_->setVisible(full);
  QGraphicsObject::update();
  for (auto* p : ports_) p->update();
}

void NodeItem::setHeld(bool held) {
  if (held == held_) return;
  held_ = held;
  QGraphicsObject::update();
}

QString NodeItem::heldNote() const {
  return held_ && !info_.keeps.empty() ? QString("↻ re-runs of the held frame change it") : QString();
}

BoxName NodeItem::name() const {
  QFont bold;
  bold.setBold(true);
  if (detail_) {  // on the title bar
    bold.setPointSizeF(9.5);
    return BoxName{bold, title(), Qt::AlignLeft | Qt::AlignVCenter, true};
  }
  return BoxName::fit(title(), nameArea(), zoom_, bold);
}

QRectF NodeItem::nameArea() const { return QRectF(kPad, 2, width_ - 2 * kPad, (previews_ ? preview_top_ : height_) - 4); }

double NodeItem::namePixels() const {
  const BoxName n = name();
  return (n.font.pixelSize() > 0 ? n.font.pixelSize() : QFontInfo(n.font).pixelSize()) * zoom_;
}

void NodeItem::showImage(const QString& port, const QImage& image) {
  images_[port.toStdString()] = image;
  QGraphicsObject::update();
}

QString NodeItem::portTip(const apex::PortInfo& p) const {
  QString tip =
      QString::fromStdString(p.name + " (" + p.kind + (p.type.empty() ? "" : ", " + p.type) + (p.optional ? ", optional" : "") +
                             ")" + (p.description.empty() ? "" : "\n" + p.description));
  if (p.kind == "output") {
    auto image = images_.find(p.name);
    auto value = scalar_values_.find(QString::fromStdString(p.name));
    auto about = abouts_.find(p.name);
    if (image != images_.end() && !image->second.isNull())
      tip += QString("\nlast: %1 image (preview %2×%3)")
                 .arg(about == abouts_.end() ? QString("an") : about->second)
                 .arg(image->second.width())
                 .arg(image->second.height());
    else if (value != scalar_values_.end()) tip += "\nlast: " + value->second;
    else tip += "\nlast: not watched (turn on Previews, or double-click to inspect)";
    tip += QString("\nnode: %1 Hz").arg(rate_hz_, 0, 'f', 1);
    tip += "\n(drag to an input to connect; double-click to inspect)";
  }
  return tip;
}

void NodeItem::showValue(const QString& port, const QString& text) {
  if (isOptimizer() && (port == "best_fitness" || port == "evaluations")) {  // drawn as progress
    if (port == "evaluations") {
      const int n = text.toInt();
      if (n < evaluations_) fitness_.clear();  // a new run
      evaluations_ = n;
    } else {
      fitness_.push_back(text.toDouble());
    }
    return QGraphicsObject::update();
  }
  scalar_values_[port] = text;
  if (previews_) {  // a sparkline's next point
    auto& s = series_[port.toStdString()];
    s.push_back(text == "true" ? 1.0 : text == "false" ? 0.0 : text.toDouble());
    if (s.size() > 60) s.erase(s.begin());
  }
  values_.clear();
  for (const auto& [p, v] : scalar_values_) values_ += (values_.isEmpty() ? "" : "  ") + p + " = " + v;
  QGraphicsObject::update();
}

PortItem* NodeItem::port(const std::string& name, bool source) const {
  for (auto* p : ports_)
    if (p->port().name == name && p->isSource() == source) return p;
  return nullptr;
}

ParamEditor* NodeItem::editor(const std::string& param) const {
  auto it = editors_.find(param);
  return it == editors_.end() ? nullptr : it->second;
}

// The frame's pen is up to 3 wide (an error's), half of it outside the box: all of it inside the
// bounds, or a moved box leaves a trail of its old frame.
QRectF NodeItem::boundingRect() const { return QRectF(-2, -2, width_ + 4, height_ + 4); }

void NodeItem::paint(QPainter* p, const QStyleOptionGraphicsItem*, QWidget*) {
  p->setRenderHint(QPainter::Antialiasing);
  const bool error = info_.state == "error", off = !info_.enabled || info_.state == "placeholder";
  p->setPen(QPen(error          ? QColor(230, 40, 40)
                 : isSelected() ? QColor(255, 220, 80)
                 : critical_    ? QColor(255, 140, 0)
                                : QColor(20, 20, 20),
                 error || critical_ ? 3 : 1.5));
  p->setBrush(off ? QColor(70, 70, 70) : QColor(45, 48, 55));
  p->drawRoundedRect(QRectF(0, 0, width_, height_), 6, 6);
  p->setBrush(groupColor(info_.thread_group));
  p->setPen(Qt::NoPen);
  p->drawRoundedRect(QRectF(1, 1, width_ - 2, kTitle - 4), 5, 5);
  p->setPen(Qt::white);
  const BoxName name = this->name();
  p->setFont(name.font);
  QFont f = name.font;
  if (!detail_) {  // zoomed out: the name alone, as large as the box holds it, readable on screen
    p->drawText(nameArea(), name.flags, name.text);
    f = QFont();
    f.setBold(false);
    f.setPointSizeF(7.5);
    p->setFont(f);
    if (previews_) paintPreviews(p);
    return;
  }
  p->drawText(QRectF(kPad, 2, width_ - 2 * kPad, 18), name.flags, name.text);
  f.setBold(false);
  f.setPointSizeF(7.5);
  p->setFont(f);
  p->drawText(QRectF(kPad, 18, width_ - 2 * kPad, 14), Qt::AlignLeft | Qt::AlignVCenter, kindLine());
  const double bottom = height_ - 2 * kRow;
  if (previews_) paintPreviews(p);
  if (isOptimizer()) paintProgress(p, QRectF(kPad, bottom - kPlot, width_ - 2 * kPad, kPlot - 4));
  p->setPen(QColor(200, 200, 200));
  p->drawText(QRectF(kPad, bottom, width_ - 2 * kPad, kRow), Qt::AlignLeft | Qt::AlignVCenter,
              values_.isEmpty() ? timing_ : values_);
  if (error) {
    p->setPen(QColor(255, 90, 90));
    p->drawText(
        QRectF(kPad, bottom + kRow, width_ - 2 * kPad, kRow), Qt::AlignLeft | Qt::AlignVCenter,
        p->fontMetrics().elidedText(QString::fromStdString(info_.error), Qt::ElideRight, static_cast<int>(width_ - 2 * kPad)));
  } else if (!waiting_.isEmpty()) {  // stalled: what it waits for, from the runtime
    p->setPen(QColor(255, 190, 60));
    p->drawText(QRectF(kPad, bottom + kRow, width_ - 2 * kPad, kRow), Qt::AlignLeft | Qt::AlignVCenter,
                p->fontMetrics().elidedText(waiting_, Qt::ElideRight, static_cast<int>(width_ - 2 * kPad)));
  } else if (!heldNote().isEmpty()) {  // what it keeps: the held frame's re-runs add to it
    p->setPen(QColor(230, 170, 60));
    p->drawText(QRectF(kPad, bottom + kRow, width_ - 2 * kPad, kRow), Qt::AlignLeft | Qt::AlignVCenter,
                p->fontMetrics().elidedText(heldNote(), Qt::ElideRight, static_cast<int>(width_ - 2 * kPad)));
  } else if (!values_.isEmpty()) {
    p->drawText(QRectF(kPad, bottom + kRow, width_ - 2 * kPad, kRow), Qt::AlignLeft | Qt::AlignVCenter, timing_);
  }
}

void NodeItem::paintProgress(QPainter* p, const QRectF& area) const {
  int budget = 0;
  const apex::ParamInfo* front = nullptr;
  for (const auto& param : info_.parameters) {
    if (param.name == "budget") budget = QString::fromStdString(param.value).toInt();
    if (param.name == "front") front = &param;
  }
  paintOptimizerRun(p, area, evaluations_, budget, fitness_, frontIn(front));
}

void NodeItem::paintPreviews(QPainter* p) const {
  double y = preview_top_;
  const double w = width_ - 2 * kPad;
  for (const auto& name : previewPorts()) {
    const bool image = imageType(port(name, true)->port().type);
    const QRectF area(kPad, y, w, image ? kThumb : kSpark - 4);
    y += image ? kThumb + 4 : kSpark;
    p->setPen(QColor(90, 90, 90));
    p->setBrush(QColor(30, 32, 36));
    p->drawRect(area);
    p->setPen(QColor(170, 170, 170));
    if (image) {
      auto it = images_.find(name);
      if (it == images_.end() || it->second.isNull()) {
        p->drawText(area, Qt::AlignCenter, QString::fromStdString(name + ": waiting for a frame"));
        continue;
      }
      const QSizeF size = QSizeF(it->second.size()).scaled(area.size(), Qt::KeepAspectRatio);
      const QRectF at(area.center().x() - size.width() / 2, area.center().y() - size.height() / 2, size.width(), size.height());
      p->drawImage(at, it->second);
      continue;
    }
    auto it = series_.find(name);
    const std::vector<double> none;
    const std::vector<double>& v = it == series_.end() ? none : it->second;
    p->drawText(area.adjusted(3, 0, -3, 0), Qt::AlignLeft | Qt::AlignTop,
                QString::fromStdString(name) + (v.empty() ? ": waiting" : " = " + QString::number(v.back(), 'g', 5)));
    if (v.size() < 2) continue;
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    const double span = *hi - *lo > 0 ? *hi - *lo : 1;
    const QRectF plot = area.adjusted(2, 12, -2, -2);
    QPolygonF line;
    for (std::size_t i = 0; i < v.size(); ++i)
      line << QPointF(plot.left() + plot.width() * i / 59.0, plot.bottom() - plot.height() * (v[i] - *lo) / span);
    p->setPen(QPen(QColor(100, 180, 240), 1.2));
    p->drawPolyline(line);
  }
}

QVariant NodeItem::itemChange(GraphicsItemChange change, const QVariant& value) {
  if (change == ItemPositionHasChanged && scene() && scene()->mouseGrabberItem() == this) dragged_ = true;
  return QGraphicsObject::itemChange(change, value);
}

void NodeItem::mouseReleaseEvent(QGraphicsSceneMouseEvent* e) {
  QGraphicsObject::mouseReleaseEvent(e);
  if (dragged_) emit moved(QString::fromStdString(info_.name), pos());
  dragged_ = false;
}

/** Its error, else what it waits for; then what it keeps from frame to frame (a status must not
 *  drop that line: the type's list brings it once). */
void NodeItem::updateToolTip() {
  const std::string first = !info_.error.empty() ? info_.error : waiting_.toStdString();
  const std::string keeps = info_.keeps.empty() ? "" : "Keeps from frame to frame: " + info_.keeps;
  setToolTip(QString::fromStdString(first + (first.empty() || keeps.empty() ? "" : "\n") + keeps));
}

}  // namespace apex_rviz_plugin
