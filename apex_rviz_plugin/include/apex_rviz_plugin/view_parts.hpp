// Small parts around the graph view: the minimap in a corner, the breadcrumb over
// it that says (and changes) which subgraph the view shows, and the scrolling of
// the view while a box is dragged to its edge.
#pragma once

#include <QTimer>
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
  /** @brief Shown only when there are boxes, the view does not show them all and has room for
   *  it; then in the first corner of the view (bottom-right, bottom-left, top-right, top-left)
   *  where it covers no box, and hidden if it would cover one in each: it never hides a node. */
  void place();

 protected:
  void paintEvent(QPaintEvent*) override;
  void mousePressEvent(QMouseEvent* e) override;

 private:
  GraphScene* scene_;
  QGraphicsView* main_;
  QTransform map_;  // scene -> minimap
};

/** @brief Scrolls the view while a box is dragged within a few pixels of its edge, faster the
 *  closer, and the box goes along (as in Blender's node editor and Groot2). */
class EdgeScroller : public QObject {
 public:
  explicit EdgeScroller(QGraphicsView* view);

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  /** Pixels to scroll by at the cursor (0, 0 away from the edges). */
  QPoint speed() const;
  void step();

  QGraphicsView* view_;
  QTimer timer_;
  QPoint at_;  // the cursor while dragging, viewport pixels
  Qt::MouseButtons held_;
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
