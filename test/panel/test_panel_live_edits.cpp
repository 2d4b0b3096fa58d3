// Editing while the data flows: a playing bag changes the graph many times a second (its frame and
// time), and no gesture in progress may be cancelled by the graphs shown meanwhile.
#include "panel_test_support.hpp"

namespace panel_test {
namespace {

/** A drag as a hand makes it: a press, moves with the event loop running between them, the
 *  release once at least one graph was shown during the drag (the moment that cancelled it).
 *  Returns the number of graphs shown between the press and the release. */
int liveDrag(PanelWidget& panel, QGraphicsView* view, QPointF from, QPointF to) {
  int shown = 0;
  const auto counting = QObject::connect(&panel, &PanelWidget::graphShown, [&] { ++shown; });
  mouse(view, QEvent::MouseButtonPress, from, Qt::LeftButton);
  for (int i = 1; i <= 10; ++i) {
    QTest::qWait(20);
    mouse(view, QEvent::MouseMove, from + (to - from) * (i / 10.0), Qt::LeftButton);
  }
  (void)QTest::qWaitFor([&] { return shown > 0; }, kWaitMs);  // (the caller asserts it)
  mouse(view, QEvent::MouseMove, to, Qt::LeftButton);
  mouse(view, QEvent::MouseButtonRelease, to, Qt::NoButton);
  QObject::disconnect(counting);
  return shown;
}

bool disconnectLink(const std::string& a, const std::string& ap, const std::string& b, const std::string& bp) {
  apex::Connect srv;
  srv.request.from_node = a, srv.request.from_port = ap, srv.request.to_node = b, srv.request.to_port = bp;
  return ros::service::call("/apex/disconnect", srv) && srv.response.success;
}

}  // namespace

TEST_F(PanelWidgetTest, TwentyLinkDragsAllConnectWhileABagPlaysAtItsFullRate) {
  emptyGraph();
  ASSERT_TRUE(addNode("apex_nodes/BagReader", "live_player",
                      "{file: '" + g_bag + "', topics: [/camera/image_raw], rate: 0.0, loop: true}"));
  ASSERT_TRUE(addNode("apex_nodes/Clock", "live_clock", ""));
  ASSERT_TRUE(addNode("apex_nodes/Counter", "live_count", ""));
  for (const char* n : {"live_player", "live_clock", "live_count"}) waitPlaced(n);
  const auto before = panel.model().graph().revision;
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.model().graph().revision > before + 5; }, kWaitMs))
      << "the player does not change the graph as it plays";

  int connected_by_drag = 0;
  for (int i = 0; i < 20; ++i) {
    const int shown = liveDrag(panel, view, portAt("live_clock", "count", true), portAt("live_count", "in", false));
    ASSERT_GT(shown, 0) << "drag " << i << ": no graph came during it";
    const bool made =
        QTest::qWaitFor([&] { return connected(runtimeGraph(), "live_clock", "count", "live_count", "in"); }, kWaitMs);
    ASSERT_TRUE(made) << "drag " << i << " of 20 made no link while the bag played (" << shown
                      << " graphs shown during it); message: " << panel.editor()->message().toStdString();
    ++connected_by_drag;
    ASSERT_TRUE(disconnectLink("live_clock", "count", "live_count", "in"));  // as a script would: the next drag makes it again
    ASSERT_TRUE(QTest::qWaitFor(
        [&] { return !connected(panel.model().graph(), "live_clock", "count", "live_count", "in") && panel.editsPending() == 0; },
        kWaitMs));
  }
  EXPECT_EQ(connected_by_drag, 20);
  emptyGraph();
}

}  // namespace panel_test
