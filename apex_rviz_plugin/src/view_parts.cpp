#include "apex_rviz_plugin/view_parts.hpp"

#include <QApplication>
#include <QGraphicsView>
#include <QHBoxLayout>
#include <QLabel>
#include <QMouseEvent>
#include <QPainter>
#include <QScrollBar>
#include <QToolButton>

#include <algorithm>

#include "apex_rviz_plugin/graph_scene.hpp"

namespace apex_rviz_plugin {

// ------------------------------------------------------------------ Minimap

Minimap::Minimap(GraphScene* scene, QGraphicsView* main) : QWidget(main), scene_(scene), main_(main) {
  setObjectName("minimap");
  setFixedSize(180, 120);
  setToolTip("the whole graph: click to go there");
  connect(scene, &QGraphicsScene::changed, this, QOverload<>::of(&QWidget::update));  // repaints coalesce
  connect(scene, &QGraphicsScene::changed, this, &Minimap::place);  // a box moved under it
}

void Minimap::place() {
  // Node editors' users (Blender, Groot2) frame the graph with Fit and pan; an overview that
  // covers a box takes clicks and sight from it. So only where it covers none, or not at all.
  const QRect port = main_->viewport()->geometry();
  const QRectF seen = main_->mapToScene(main_->viewport()->rect()).boundingRect();
  const auto boxes = scene_->boxes();
  bool all_seen = true;
  for (const auto& [name, b] : boxes) all_seen = all_seen && seen.contains(QRectF(b.x, b.y, b.width, b.height));
  if (boxes.empty() || all_seen || port.width() <= 500 || port.height() <= 300) return hide();
  const int m = 8, left = port.left() + m, right = port.right() - width() - m;
  const int top = port.top() + m, bottom = port.bottom() - height() - m;
  for (const QPoint corner : {QPoint(right, bottom), QPoint(left, bottom), QPoint(right, top), QPoint(left, top)}) {
    const QRect there(main_->viewport()->mapFrom(main_, corner), size());  // viewport pixels
    const QRectF covered = main_->mapToScene(there).boundingRect();
    bool free = true;
    for (const auto& [name, b] : boxes) free = free && !covered.intersects(QRectF(b.x, b.y, b.width, b.height));
    if (!free) continue;
    move(corner);
    return show();
  }
  hide();
}

void Minimap::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.fillRect(rect(), QColor(20, 22, 26, 220));
  p.setPen(QColor(110, 110, 110));
  p.drawRect(rect().adjusted(0, 0, -1, -1));
  const QRectF seen = main_->mapToScene(main_->viewport()->rect()).boundingRect();
  QRectF all = seen;
  const auto boxes = scene_->boxes();
  for (const auto& [name, b] : boxes) all |= QRectF(b.x, b.y, b.width, b.height);
  const double s = std::min((width() - 8) / all.width(), (height() - 8) / all.height());
  map_ = QTransform().translate(-all.left(), -all.top()) * QTransform().scale(s, s) * QTransform().translate(4, 4);
  p.setPen(Qt::NoPen);
  p.setBrush(QColor(120, 140, 170));
  for (const auto& [name, b] : boxes) p.drawRect(map_.mapRect(QRectF(b.x, b.y, b.width, b.height)));
  p.setPen(QPen(QColor(255, 220, 80), 1));
  p.setBrush(Qt::NoBrush);
  p.drawRect(map_.mapRect(seen));
}

void Minimap::mousePressEvent(QMouseEvent* e) { main_->centerOn(map_.inverted().map(QPointF(e->pos()))); }

// ------------------------------------------------------------------ EdgeScroller

namespace {
constexpr int kEdge = 24;  // pixels from the view's edge where a dragged box scrolls it
constexpr int kFastest = 20;  // pixels a tick at the very edge
}  // namespace

EdgeScroller::EdgeScroller(QGraphicsView* view) : QObject(view), view_(view) {
  timer_.setInterval(30);
  connect(&timer_, &QTimer::timeout, this, &EdgeScroller::step);
  view->viewport()->installEventFilter(this);
}

QPoint EdgeScroller::speed() const {
  const QRect r = view_->viewport()->rect();
  auto along = [](int from_low, int from_high) {  // distances to the two edges of one axis
    if (from_low < kEdge) return -std::max(2, kFastest * (kEdge - from_low) / kEdge);
    if (from_high < kEdge) return std::max(2, kFastest * (kEdge - from_high) / kEdge);
    return 0;
  };
  return QPoint(along(at_.x() - r.left(), r.right() - at_.x()), along(at_.y() - r.top(), r.bottom() - at_.y()));
}

bool EdgeScroller::eventFilter(QObject*, QEvent* event) {
  if (event->type() == QEvent::MouseButtonRelease) timer_.stop();
  if (event->type() != QEvent::MouseMove) return false;
  auto* move = static_cast<QMouseEvent*>(event);
  QGraphicsItem* grabbed = view_->scene() ? view_->scene()->mouseGrabberItem() : nullptr;
  if (!(move->buttons() & Qt::LeftButton) || !dynamic_cast<NodeItem*>(grabbed)) return timer_.stop(), false;
  at_ = move->pos();
  held_ = move->buttons();
  if (speed().isNull()) timer_.stop();
  else if (!timer_.isActive()) timer_.start();
  return false;
}

void EdgeScroller::step() {
  const QPoint by = speed();
  if (by.isNull() || !dynamic_cast<NodeItem*>(view_->scene()->mouseGrabberItem())) return timer_.stop();  // let go
  view_->horizontalScrollBar()->setValue(view_->horizontalScrollBar()->value() + by.x());
  view_->verticalScrollBar()->setValue(view_->verticalScrollBar()->value() + by.y());
  // The cursor stays where it is over a canvas that moved: the box follows it there.
  QMouseEvent again(QEvent::MouseMove, at_, view_->viewport()->mapToGlobal(at_), Qt::NoButton, held_, Qt::NoModifier);
  QApplication::sendEvent(view_->viewport(), &again);
}

// ------------------------------------------------------------------ LevelBar

LevelBar::LevelBar(GraphScene* scene, QWidget* parent) : QWidget(parent), scene_(scene), crumbs_(new QHBoxLayout) {
  auto* row = new QHBoxLayout(this);
  row->setContentsMargins(0, 0, 0, 0);
  auto* up = new QToolButton;
  up->setObjectName("up");
  up->setText("Up");
  up->setToolTip("back to the graph around this subgraph");
  connect(up, &QToolButton::clicked, this, [this] {
    const std::string& at = scene_->level();
    const auto slash = at.rfind('/');
    scene_->setLevel(slash == std::string::npos ? "" : at.substr(0, slash));
  });
  crumbs_->setSpacing(0);
  auto* hint = new QLabel("   (double-click a subgraph to open it)");
  hint->setObjectName("level_hint");
  row->addWidget(up);
  row->addLayout(crumbs_);
  row->addWidget(hint, 1);
  setVisible(false);
}

void LevelBar::showPath(const QString& path) {
  while (QLayoutItem* item = crumbs_->takeAt(0)) {
    delete item->widget();
    delete item;
  }
  setVisible(!path.isEmpty());
  const QStringList parts = path.isEmpty() ? QStringList() : path.split('/');
  for (int i = -1; i < parts.size(); ++i) {  // -1: the graph itself
    const QString to = i < 0 ? QString() : QStringList(parts.mid(0, i + 1)).join('/');
    if (i >= 0) crumbs_->addWidget(new QLabel(" › "));  // the bar may be shown: its new parts are, at once
    auto* crumb = new QToolButton;
    crumb->setObjectName("crumb:" + to);
    crumb->setText(i < 0 ? "graph" : parts[i]);
    crumb->setAutoRaise(true);
    const bool here = i == parts.size() - 1;
    crumb->setEnabled(!here);  // where the view is: shown, nothing to go to
    crumb->setToolTip(here ? "shown now" : "open " + (to.isEmpty() ? QString("the whole graph") : to));
    QFont f = crumb->font();
    f.setBold(here);
    crumb->setFont(f);
    connect(crumb, &QToolButton::clicked, this, [this, to] { scene_->setLevel(to.toStdString()); });
    crumbs_->addWidget(crumb);
  }
  for (int i = 0; i < crumbs_->count(); ++i) crumbs_->itemAt(i)->widget()->show();
}

}  // namespace apex_rviz_plugin
