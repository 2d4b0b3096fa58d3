// The panel offers the graph a killed runtime left unsaved (issue #35): a bar at the top, not
// modal, with Restore and Discard, each calling the runtime's ~recovery. Against a stand-in
// runtime that reports a recovery copy (test_ros_recovery.cpp tests the real one's).
#include <QDateTime>
#include <QLocale>
#include <QPushButton>

#include <apex/Recovery.h>

#include "apex_rviz_plugin/recovery_bar.hpp"
#include "panel_test_support.hpp"

namespace panel_test {
namespace {

/** A runtime in `ns` whose previous run left a copy of 3 nodes: ~graph (empty), list_node_types
 *  and ~recovery, which records the actions asked for. */
class RecoveringRuntime {
 public:
  static inline const ros::Time kWritten{1767322800, 0};  // 2026-01-02 03:00 UTC

  explicit RecoveringRuntime(const std::string& ns) : nh_(ns) {
    nh_.setCallbackQueue(&queue_);
    graph_ = nh_.advertise<apex::GraphState>("graph", 1, true);
    apex::GraphState g;
    g.revision = 1;
    graph_.publish(g);
    types_ = nh_.advertiseService<apex::ListNodeTypes::Request, apex::ListNodeTypes::Response>(
        "list_node_types", [](auto&, auto& res) { return res.success = true; });
    recovery_ = nh_.advertiseService<apex::Recovery::Request, apex::Recovery::Response>(
        "recovery", [this](apex::Recovery::Request& req, apex::Recovery::Response& res) {
          std::lock_guard<std::mutex> lock(mutex_);
          actions_.push_back(req.action);
          if (req.action == "restore" || req.action == "discard") offered_ = false;
          res.success = true, res.offered = offered_;
          res.path = "/home/u/.ros/apex/recovery/x.previous.yaml", res.written = kWritten, res.nodes = 3;
          return true;
        });
    spinner_.start();
  }
  std::vector<std::string> actions() {
    std::lock_guard<std::mutex> lock(mutex_);
    return actions_;
  }

 private:
  std::mutex mutex_;
  std::vector<std::string> actions_;
  bool offered_ = true;
  ros::NodeHandle nh_;
  ros::CallbackQueue queue_;
  ros::AsyncSpinner spinner_{1, &queue_};
  ros::Publisher graph_;
  ros::ServiceServer types_, recovery_;  // last: their callbacks use the members above
};

QString shortTime(const ros::Time& t) {
  return QLocale().toString(QDateTime::fromMSecsSinceEpoch(qint64(t.sec) * 1000), QLocale::ShortFormat);
}

TEST(PanelWidgetRecovery, OffersTheCopyAtTheTopWithoutAskingAndRestoreCallsTheRuntime) {
  RecoveringRuntime runtime("/recovering");
  PanelWidget panel;
  panel.resize(1000, 650);
  panel.show();
  auto* bar = panel.findChild<RecoveryBar*>("recovery");
  ASSERT_TRUE(bar);
  EXPECT_FALSE(bar->isVisible()) << "a bar before any runtime said it has a copy";
  panel.setNamespace("/recovering");
  ASSERT_TRUE(QTest::qWaitFor([&] { return bar->isVisible(); }, kWaitMs)) << "the offered copy is not shown";
  EXPECT_EQ(bar->text(), "Unsaved graph from " + shortTime(RecoveringRuntime::kWritten) + " (3 nodes) found");
  EXPECT_EQ(runtime.actions(), std::vector<std::string>{"keep"}) << "the panel did more than ask";
  EXPECT_EQ(QApplication::activeModalWidget(), nullptr) << "the offer blocks the panel";
  EXPECT_LT(bar->mapTo(&panel, QPoint(0, 0)).y(), panel.editor()->mapTo(&panel, QPoint(0, 0)).y()) << "not at the top";

  auto* restore = bar->findChild<QPushButton*>("recovery_restore");
  ASSERT_TRUE(restore);
  QTest::mouseClick(restore, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return runtime.actions().size() == 2 && !bar->isVisible(); }, kWaitMs))
      << "Restore did not call ~recovery, or the bar stayed";
  EXPECT_EQ(runtime.actions().back(), "restore");
  EXPECT_TRUE(panel.editor()->message().contains("restored")) << panel.editor()->message().toStdString();
}

TEST(PanelWidgetRecovery, DiscardCallsTheRuntimeAndARuntimeThatComesBackIsAskedAgain) {
  auto runtime = std::make_unique<RecoveringRuntime>("/recovering_b");
  PanelWidget panel;
  panel.show();
  panel.setNamespace("/recovering_b");
  auto* bar = panel.findChild<RecoveryBar*>("recovery");
  ASSERT_TRUE(bar);
  ASSERT_TRUE(QTest::qWaitFor([&] { return bar->isVisible(); }, kWaitMs)) << "the offered copy is not shown";
  runtime.reset();  // the runtime dies: its offer goes with it
  ASSERT_TRUE(QTest::qWaitFor([&] { return !panel.link().connected(); }, kWaitMs));
  EXPECT_FALSE(bar->isVisible()) << "the bar offers the copy of a runtime that is gone";
  runtime = std::make_unique<RecoveringRuntime>("/recovering_b");  // and starts again, with a copy
  ASSERT_TRUE(QTest::qWaitFor([&] { return bar->isVisible(); }, kWaitMs)) << "a runtime back with a copy: not offered";

  auto* discard = bar->findChild<QPushButton*>("recovery_discard");
  ASSERT_TRUE(discard);
  QTest::mouseClick(discard, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return runtime->actions().size() == 2 && !bar->isVisible(); }, kWaitMs))
      << "Discard did not call ~recovery, or the bar stayed";
  EXPECT_EQ(runtime->actions().back(), "discard");
}

}  // namespace
}  // namespace panel_test
