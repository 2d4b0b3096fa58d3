// What the panel inspects (the ports rviz shows, as "Show in rviz" asks) follows the graph: the
// runtime ends every inspection when nodes are grouped or ungrouped, and the ports go on being
// published, under their nodes' new paths.
#include "panel_test_support.hpp"

#include <topic_tools/shape_shifter.h>

namespace panel_test {
namespace {

/** Whether a message of any type comes on `topic` within the wait. */
bool messageComes(const std::string& topic) {
  ros::NodeHandle nh;
  ros::CallbackQueue queue;
  nh.setCallbackQueue(&queue);
  int got = 0;
  const ros::Subscriber sub = nh.subscribe<topic_tools::ShapeShifter>(
      topic, 1, boost::function<void(const topic_tools::ShapeShifter::ConstPtr&)>([&got](const auto&) { ++got; }));
  return QTest::qWaitFor(
      [&] {
        queue.callAvailable(ros::WallDuration(0.01));
        return got > 0;
      },
      kWaitMs);
}

}  // namespace

TEST_F(PanelWidgetTest, AnInspectedPortIsPublishedAgainUnderItsNewPathAfterAGroupAndAnUngroup) {
  emptyGraph();
  ASSERT_TRUE(addNode("apex_nodes/Clock", "shown_clock", "{rate: 20.0}"));
  ASSERT_TRUE(addNode("apex_nodes/Counter", "shown_count", ""));
  ASSERT_TRUE(link("shown_clock", "count", "shown_count", "in"));
  for (const char* n : {"shown_clock", "shown_count"}) waitPlaced(n);
  std::vector<std::pair<QString, QString>> renames;  // what GraphPanel's displays follow
  const auto following = QObject::connect(&panel, &PanelWidget::renameSent,
                                          [&](const QString& from, const QString& to) { renames.emplace_back(from, to); });
  panel.inspect("shown_clock", "count");
  ASSERT_TRUE(messageComes("/apex/inspect/shown_clock/count"));

  emit panel.editor()->groupIntoSubgraphRequested({"shown_clock", "shown_count"});
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.model().node("subgraph_1/shown_clock") && panel.editsPending() == 0; }, kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_TRUE(
      std::count(renames.begin(), renames.end(), std::make_pair(QString("shown_clock"), QString("subgraph_1/shown_clock"))))
      << "the displays were not told where the node went";
  EXPECT_TRUE(messageComes("/apex/inspect/subgraph_1/shown_clock/count")) << "not inspected under its path in the group";

  emit panel.editor()->ungroupRequested("subgraph_1");
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.model().node("shown_clock") && panel.editsPending() == 0; }, kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_TRUE(
      std::count(renames.begin(), renames.end(), std::make_pair(QString("subgraph_1/shown_clock"), QString("shown_clock"))));
  EXPECT_TRUE(messageComes("/apex/inspect/shown_clock/count")) << "not inspected again after the ungroup";
  QObject::disconnect(following);
  emptyGraph();
}

TEST_F(PanelWidgetTest, TheUnsavedMarkComesWithAnEditAndGoesWithASave) {
  emptyGraph();  // an empty graph: nothing to lose
  ASSERT_TRUE(QTest::qWaitFor([&] { return !panel.editor()->unsavedShown(); }, kWaitMs));
  ASSERT_TRUE(addNode("apex_nodes/Clock", "unsaved_clock", ""));
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editor()->unsavedShown(); }, kWaitMs)) << "no mark after an edit";
  const std::string file = std::filesystem::path(g_bag).parent_path() / "unsaved_mark.yaml";
  emit panel.editor()->saveRequested(QString::fromStdString(file));
  ASSERT_TRUE(QTest::qWaitFor([&] { return !panel.editor()->unsavedShown(); }, kWaitMs))
      << "the mark stayed after a save; message: " << panel.editor()->message().toStdString();
  std::filesystem::remove(file);
  emptyGraph();
}

}  // namespace panel_test
