// Two small widgets around the graph view: the minimap in its corner, and the
// breadcrumb over it that says (and changes) which subgraph the view shows.
#pragma once

#include <QTransform>
#include <QWidget>

class QGraphicsView;
class QHBoxLayout;

namespace apex_rviz_plugin {

class GraphScene;

/** @brief The whole graph small in a corner of the view: the boxes as blocks, the part the
 *  view shows framed; a click there centres the view on it. Draws rectangles, not the scene. */
class Minimap : public QWidget {
 public:
  Minimap(GraphScene* scene, QGraphicsView* main);
  /** @brief In the view's bottom-right corner; shown only when the view does not show every
   *  box and has room for it. */
  void place();

 protected:
  void paintEvent(QPaintEvent*) override;
  void mousePressEvent(QMouseEvent* e) override;

 private:
  GraphScene* scene_;
  QGraphicsView* main_;
  QTransform map_;  // scene -> minimap
};

/** @brief Where the view is among nested subgraphs: "graph › camera_detector › inner", each
 *  part a button that opens that level, and Up. Hidden at the top level. */
class LevelBar : public QWidget {
 public:
  explicit LevelBar(GraphScene* scene, QWidget* parent = nullptr);
  /** @brief Shows the path of the level shown ("a/b"; "" hides the bar). */
  void showPath(const QString& path);

 private:
  GraphScene* scene_;
  QHBoxLayout* crumbs_;
};

}  // namespace apex_rviz_plugin
