#include "apex_rviz_plugin/view_parts.hpp"

#include <QGraphicsView>
#include <QHBoxLayout>
#include <QLabel>
#include <QMouseEvent>
#include <QPainter>
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
}

void Minimap::place() {
  const QRect port = main_->viewport()->geometry();
  move(port.right() - width() - 8, port.bottom() - height() - 8);
  const QRectF seen = main_->mapToScene(main_->viewport()->rect()).boundingRect();
  const bool all_seen = seen.contains(scene_->itemsBoundingRect());
  setVisible(!all_seen && port.width() > 500 && port.height() > 300);  // needed, and room for it
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
