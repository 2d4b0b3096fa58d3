// Panel tests, continued: Balance (issue #37) moves nodes into the thread groups the runtime
// proposes, as one undo step, and says what to expect.
#include <apex/SetThreadGroup.h>

#include <set>

#include "panel_test_support.hpp"

namespace panel_test {
namespace {

bool setGroup(const std::string& node, const std::string& group) {
  apex::SetThreadGroup srv;
  srv.request.node = node, srv.request.group = group;
  return ros::service::call("/apex/set_thread_group", srv) && srv.response.success;
}

/** The nodes' groups as the runtime has them, in the order asked. */
std::vector<std::string> groupsOf(const std::vector<std::string>& nodes) {
  const auto g = runtimeGraph();
  std::vector<std::string> out;
  for (const auto& n : nodes) out.push_back(find(g, n) ? find(g, n)->thread_group : "(gone)");
  return out;
}

TEST_F(PanelWidgetTest, BalanceMovesNodesIntoTheProposedGroupsAsOneUndoStep) {
  emptyGraph();
  const std::vector<std::string> nodes{"bal_clock", "bal_first", "bal_second"};
  ASSERT_TRUE(addNode("apex_nodes/Clock", nodes[0], "{rate: 200}"));
  ASSERT_TRUE(addNode("apex_nodes/Relay", nodes[1], ""));
  ASSERT_TRUE(addNode("apex_nodes/Relay", nodes[2], ""));
  ASSERT_TRUE(link(nodes[0], "count", nodes[1], "in"));
  ASSERT_TRUE(link(nodes[1], "out", nodes[2], "in"));
  const std::vector<std::string> before{"a", "b", "c"};  // three groups for a chain of microseconds: more than it needs
  for (std::size_t i = 0; i < nodes.size(); ++i) ASSERT_TRUE(setGroup(nodes[i], before[i]));
  ASSERT_TRUE(QTest::qWaitFor(
      [&] {
        for (std::size_t i = 0; i < nodes.size(); ++i)
          if (!panel.model().node(nodes[i]) || panel.model().node(nodes[i])->thread_group != before[i]) return false;
        return panel.editsPending() == 0;
      },
      kWaitMs));

  auto* balance = panel.editor()->findChild<QToolButton*>("balance");
  ASSERT_TRUE(balance);
  QTest::mouseClick(balance, Qt::LeftButton);  // the answer comes later: the click returns at once
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editsPending() == 0 && undo->toolTip().contains("Balance"); }, kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_TRUE(panel.editor()->message().contains("expect")) << panel.editor()->message().toStdString();
  const auto after = groupsOf(nodes);
  EXPECT_NE(after, before);
  EXPECT_LT(std::set<std::string>(after.begin(), after.end()).size(), 3u) << "one group per stage, fewer stages than nodes";

  QTest::mouseClick(undo, Qt::LeftButton);  // one step back: every node in its group again
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editsPending() == 0 && groupsOf(nodes) == before; }, kWaitMs))
      << panel.editor()->message().toStdString();
}

}  // namespace
}  // namespace panel_test
