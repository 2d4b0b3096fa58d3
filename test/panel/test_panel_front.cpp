// Panel tests, continued: a two-objective Optimizer's Pareto front, drawn in its box and applied
// from its menu while a bag plays.
#include <QImage>
#include <QPainter>

#include "apex_rviz_plugin/optimizer_plot.hpp"
#include "panel_test_support.hpp"

namespace panel_test {
namespace {

/** The front's points in a picture: blobs of the front's colour. */
std::size_t frontPointsIn(const QImage& picture) {
  std::vector<std::vector<bool>> seen(picture.height(), std::vector<bool>(picture.width(), false));
  std::size_t blobs = 0;
  const auto front = [&](int x, int y) { return picture.pixelColor(x, y) == kFrontColor; };
  for (int y = 0; y < picture.height(); ++y)
    for (int x = 0; x < picture.width(); ++x) {
      if (seen[y][x] || !front(x, y)) continue;
      ++blobs;  // flood the blob: a point's disc (the line between points is drawn darker)
      std::vector<std::pair<int, int>> todo{{x, y}};
      while (!todo.empty()) {
        const auto [i, j] = todo.back();
        todo.pop_back();
        if (i < 0 || j < 0 || i >= picture.width() || j >= picture.height() || seen[j][i] || !front(i, j)) continue;
        seen[j][i] = true;
        todo.insert(todo.end(), {{i + 1, j}, {i - 1, j}, {i, j + 1}, {i, j - 1}});
      }
    }
  return blobs;
}

/** The front's points the box draws. */
std::size_t frontPointsDrawn(NodeItem& box) {
  const QRectF r = box.boundingRect();
  QImage picture(r.size().toSize(), QImage::Format_ARGB32);
  picture.fill(Qt::black);
  {
    QPainter p(&picture);
    p.translate(-r.topLeft());
    box.paint(&p, nullptr, nullptr);
  }
  return frontPointsIn(picture);
}

TEST(OptimizerPlot, EachPointOfTheFrontIsOneBlobHoweverNearTheOthers) {
  QImage picture(240, 90, QImage::Format_ARGB32);
  for (double dx = 0; dx <= 1.0; dx += 0.05)
    for (double dy = 0; dy <= 0.1; dy += 0.01) {
      // a point of the front near the cheapest (touching it or not), and the fittest far off
      const std::vector<FrontPoint> front{{1, 0.0, 1.0, ""}, {2, dy, 1.0 + dx, ""}, {3, 1.0, 10.0, ""}};
      picture.fill(Qt::black);
      {
        QPainter p(&picture);
        p.setRenderHint(QPainter::Antialiasing);  // as the box draws
        paintOptimizerRun(&p, QRectF(0, 0, 240, 90), 3, 3, {0.0, 0.5, 1.0}, front);
      }
      const std::size_t blobs = frontPointsIn(picture);
      EXPECT_LE(blobs, front.size()) << "dx " << dx << " dy " << dy;
      EXPECT_GE(blobs, 2u) << "dx " << dx << " dy " << dy;
    }
}

TEST_F(PanelWidgetTest, ATwoObjectiveRunsFrontIsDrawnInItsBoxAndAPointOfItsMenuAppliesInOneUndoStep) {
  emptyGraph();
  // fitness: the bag's stamps scaled by factor; cost: what the scale takes per frame
  ASSERT_TRUE(addNode("apex_nodes/BagReader", "front_player", "{file: '" + g_bag + "', topics: [/camera/image_raw], rate: 0.0}"));
  ASSERT_TRUE(addNode("apex_nodes/Scale", "front_scale", "{factor: 1.0}"));
  ASSERT_TRUE(addNode("apex_nodes/SequenceMean", "front_mean", ""));
  ASSERT_TRUE(addNode("apex_nodes/Optimizer", "front_opt",
                      "{dimensions: [factor 0 2], budget: 6, algorithm: random, objectives: fitness_and_cost}"));
  ASSERT_TRUE(setInteractive("front_scale", "factor"));
  ASSERT_TRUE(link("front_player", "stamp", "front_scale", "in") && link("front_scale", "out", "front_mean", "value"));
  ASSERT_TRUE(link("front_mean", "mean", "front_opt", "fitness") && link("front_opt", "factor", "front_scale", "factor"));
  ASSERT_TRUE(link("front_opt", "evaluate", "front_player", "restart") && link("front_opt", "evaluate", "front_mean", "reset"));
  ASSERT_TRUE(fireSlot("front_opt", "start"));
  ASSERT_TRUE(
      QTest::qWaitFor([&] { return param(runtimeGraph(), "front_opt", "state").find("finished") != std::string::npos; }, kWaitMs))
      << param(runtimeGraph(), "front_opt", "state");
  EXPECT_NE(param(runtimeGraph(), "front_opt", "state").find("; a front of "), std::string::npos);
  const std::string front = param(runtimeGraph(), "front_opt", "front");  // the run's last: it finished
  ASSERT_TRUE(QTest::qWaitFor(
      [&] {  // the panel shows that front, not one from before the run's last evaluation
        const auto* shown = panel.model().parameter("front_opt", "front");
        return shown && shown->value == front;
      },
      kWaitMs))
      << "the panel's graph never showed the final front";
  ASSERT_FALSE(panel.model().front("front_opt").empty()) << front;
  // the box draws the front beside the best fitness's curve: a point per point of the front
  panel.editor()->scene()->setZoom(1);  // zoomed in, as to read the box
  NodeItem* box = panel.editor()->scene()->node("front_opt");
  ASSERT_TRUE(box);
  const std::size_t points = panel.model().front("front_opt").size(), drawn = frontPointsDrawn(*box);
  EXPECT_LE(drawn, points);  // points near each other may touch; the cheapest and the fittest are corners apart
  EXPECT_GE(drawn, std::min<std::size_t>(points, 2));
  const FrontPoint first = panel.model().front("front_opt").front();  // the cheapest
  EXPECT_GT(first.ms_per_frame, 0.0);
  const double value = YAML::Load(first.values)["factor"].as<double>();

  // Right-click on the Optimizer while a bag plays; Apply a point of the front > its cheapest
  startPlaying("front_live");
  waitPlaced("front_opt");
  ASSERT_GT(chooseInNodeMenu(panel, view, "front_opt", "fitness ", "Apply a point of the front", 1), 0) << "no point in the menu";
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(runtimeGraph(), "front_scale", "factor") == value; }, kWaitMs))
      << panel.editor()->message().toStdString() << "; factor " << param(runtimeGraph(), "front_scale", "factor");
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  ASSERT_TRUE(undo);
  ASSERT_TRUE(QTest::qWaitFor(
      [&] { return undo->toolTip().contains(QString("Apply evaluation %1 of front_opt's front").arg(first.evaluation)); },
      kWaitMs))
      << undo->toolTip().toStdString();
  QTest::mouseClick(undo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(runtimeGraph(), "front_scale", "factor") == 1.0; }, kWaitMs));
}

}  // namespace
}  // namespace panel_test
