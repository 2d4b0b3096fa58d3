// Unsaved edits outlive a runtime that dies (issue #35): the runtime keeps a recovery copy of
// its graph in $ROS_HOME/apex/recovery, offers a killed run's copy through ~recovery when it
// starts again, and restores it on request; a clean stop and a save leave no copy. Each test
// runs runtimes of its own, in a $ROS_HOME of its own.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <apex/AddNode.h>
#include <apex/Connect.h>
#include <apex/GetGraph.h>
#include <apex/Recovery.h>
#include <apex/SaveGraph.h>
#include <apex/SetParameter.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "apex_test/runtime_process.hpp"
#include "apex_test/test_bags.hpp"

namespace {

using apex_test::callWhenUp;
using apex_test::RuntimeProcess;
using apex_test::waitUntil;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/** A runtime in a $ROS_HOME of its own, started; the path of its recovery copy. */
class RecoveryTest : public ::testing::Test {
 protected:
  void start(const std::string& name) {
    char tmpl[] = "/tmp/apex_recovery_XXXXXX";
    ASSERT_NE(mkdtemp(tmpl), nullptr);
    home_ = tmpl;
    name_ = name;
    runtime_ = std::make_unique<RuntimeProcess>(name, home_);
    restart();
  }
  void restart() {
    runtime_->start();
    apex::Recovery srv;
    ASSERT_TRUE(callWhenUp(service("recovery"), srv)) << service("recovery") << " never answered";
  }
  void TearDown() override {
    runtime_.reset();
    std::error_code ec;
    if (!home_.empty()) fs::remove_all(home_, ec);
  }

  std::string service(const std::string& name) const { return runtime_->ns() + "/" + name; }
  /** This run's recovery copy. */
  std::string copy() const { return home_ + "/apex/recovery/" + name_ + ".yaml"; }

  template <class Srv>
  typename Srv::Response call(const std::string& name, const typename Srv::Request& req = {}) {
    Srv srv;
    srv.request = req;
    EXPECT_TRUE(callWhenUp(service(name), srv)) << service(name) << " never answered";
    return srv.response;
  }
  apex::Recovery::Response recovery(const std::string& action) {
    apex::Recovery::Request req;
    req.action = action;
    return call<apex::Recovery>("recovery", req);
  }
  std::string graphText() { return call<apex::GetGraph>("get_graph").yaml; }
  bool has(const std::string& node) {
    for (const auto& n : call<apex::GetGraph>("get_graph").graph.nodes)
      if (n.name == node) return true;
    return false;
  }
  /** Two nodes and a link: an unsaved graph. */
  void edit() {
    apex::AddNode::Request add;
    add.type = "apex_nodes/Clock", add.name = "ticks", add.parameters = "{rate: 5}";
    ASSERT_TRUE(call<apex::AddNode>("add_node", add).success);
    add.type = "apex_nodes/Counter", add.name = "count", add.parameters = "";
    ASSERT_TRUE(call<apex::AddNode>("add_node", add).success);
    apex::Connect::Request link;
    link.from_node = "ticks", link.from_port = "count", link.to_node = "count", link.to_port = "in";
    ASSERT_TRUE(call<apex::Connect>("connect", link).success);
  }
  /** The copy holds the graph as the runtime has it now (written after the burst of edits). */
  bool copyIsCurrent() {
    const std::string now = graphText();
    return waitUntil([&] { return fs::exists(copy()) && readText(copy()) == now; }, 20);
  }

  std::string home_, name_;
  std::unique_ptr<RuntimeProcess> runtime_;
};

TEST_F(RecoveryTest, AKilledRuntimesGraphIsOfferedWhenItStartsAgainAndRestoredOnRequest) {
  ASSERT_NO_FATAL_FAILURE(start("recovery_kill"));
  EXPECT_FALSE(recovery("keep").offered) << "a fresh $ROS_HOME has nothing to offer";
  edit();
  ASSERT_TRUE(copyIsCurrent()) << "no recovery copy of the unsaved graph in " << copy();
  const std::string before = graphText();

  ASSERT_EQ(runtime_->stop(SIGKILL), 128 + SIGKILL);  // a crash: no chance to clean up
  ASSERT_NO_FATAL_FAILURE(restart());
  const auto offer = recovery("keep");
  ASSERT_TRUE(offer.success) << offer.message;
  ASSERT_TRUE(offer.offered) << "the killed run's graph is not offered";
  EXPECT_EQ(offer.nodes, 2u);
  EXPECT_THAT(offer.path, HasSubstr(home_ + "/apex/recovery/"));
  EXPECT_GT(offer.written.toSec(), 0);
  EXPECT_LE(offer.written.toSec(), ros::WallTime::now().toSec());
  EXPECT_FALSE(has("ticks")) << "the runtime loaded the copy by itself";
  EXPECT_TRUE(recovery("keep").offered) << "keep: offered still";

  const auto bad = recovery("bogus");
  EXPECT_FALSE(bad.success);
  EXPECT_THAT(bad.message, HasSubstr("unknown action 'bogus' (actions: keep, restore, discard)"));

  const auto restored = recovery("restore");
  ASSERT_TRUE(restored.success) << restored.message;
  EXPECT_FALSE(restored.offered);
  EXPECT_EQ(graphText(), before) << "the restored graph is not the killed run's";
  // now this run's unsaved graph: kept as its copy, and offered to no one
  EXPECT_TRUE(copyIsCurrent()) << "the restored graph has no recovery copy of its own";
  EXPECT_FALSE(recovery("keep").offered);
  const auto again = recovery("restore");
  EXPECT_FALSE(again.success);
  EXPECT_THAT(again.message, HasSubstr("no unsaved graph of a previous run is offered"));
}

TEST_F(RecoveryTest, ACleanStopLeavesNoCopyAndTheNextRunOffersNothing) {
  ASSERT_NO_FATAL_FAILURE(start("recovery_sigint"));
  edit();
  ASSERT_TRUE(copyIsCurrent()) << "no recovery copy of the unsaved graph in " << copy();
  ASSERT_EQ(runtime_->stop(SIGINT), 0);
  EXPECT_FALSE(fs::exists(copy())) << "a clean stop left " << copy();
  ASSERT_NO_FATAL_FAILURE(restart());
  EXPECT_FALSE(recovery("keep").offered);
}

TEST_F(RecoveryTest, SaveGraphRemovesTheCopyAndTheNextEditWritesItAgain) {
  ASSERT_NO_FATAL_FAILURE(start("recovery_save"));
  edit();
  ASSERT_TRUE(copyIsCurrent()) << "no recovery copy of the unsaved graph in " << copy();
  apex::SaveGraph::Request save;
  save.path = "saved.yaml";  // in the first writable root: $ROS_HOME/apex
  const auto saved = call<apex::SaveGraph>("save_graph", save);
  ASSERT_TRUE(saved.success) << saved.message;
  EXPECT_FALSE(fs::exists(copy())) << "the saved graph still has a recovery copy";
  apex::SetParameter::Request set;
  set.node = "ticks", set.parameter = "rate", set.value = "7";
  ASSERT_TRUE(call<apex::SetParameter>("set_parameter", set).success);
  EXPECT_TRUE(copyIsCurrent()) << "an edit after the save has no recovery copy";
}

TEST_F(RecoveryTest, EditsWhileABagPlaysSurviveAKillAndPlayingAloneIsNoEdit) {
  // A playing bag changes the graph (its frame, its time) many times a second: once, the copy's
  // quiet second never came, edits were written only every 5 s and lost to a kill, and a graph
  // as saved was offered back as "unsaved" for its player's position.
  ASSERT_NO_FATAL_FAILURE(start("recovery_playing"));
  const std::string bag = home_ + "/apex/playing.bag";  // $ROS_HOME/apex: a root of the runtime's
  fs::copy_file(apex_test::writeBag(50), bag);
  apex::AddNode::Request add;
  add.type = "apex_nodes/BagReader", add.name = "bag", add.parameters = "{file: '" + bag + "', loop: true, rate: 4}";
  const auto added = call<apex::AddNode>("add_node", add);
  ASSERT_TRUE(added.success) << added.message;
  apex::SaveGraph::Request save;
  save.path = "playing.yaml";
  const auto saved = call<apex::SaveGraph>("save_graph", save);
  ASSERT_TRUE(saved.success) << saved.message;

  auto revision = [&] { return call<apex::GetGraph>("get_graph").graph.revision; };
  const auto since = std::chrono::steady_clock::now();
  const auto at_save = revision();
  ASSERT_TRUE(waitUntil(
      [&] { return std::chrono::steady_clock::now() - since > std::chrono::seconds(6) && revision() > at_save + 20; }, 60))
      << "the bag does not play";  // (longer than a copy ever waited)
  EXPECT_FALSE(fs::exists(copy())) << "a copy of the graph as saved: the player's frame counted as an edit";

  apex::SetParameter::Request set;
  set.node = "bag", set.parameter = "rate", set.value = "3";
  ASSERT_TRUE(call<apex::SetParameter>("set_parameter", set).success);
  ASSERT_TRUE(waitUntil([&] { return fs::exists(copy()) && readText(copy()).find("rate: 3") != std::string::npos; }, 20))
      << "the edit made while the bag plays is not in " << copy();
  ASSERT_EQ(runtime_->stop(SIGKILL), 128 + SIGKILL);
  ASSERT_NO_FATAL_FAILURE(restart());
  ASSERT_TRUE(recovery("keep").offered);
  const auto restored = recovery("restore");
  ASSERT_TRUE(restored.success) << restored.message;
  EXPECT_THAT(graphText(), HasSubstr("rate: 3")) << "the restored graph lost the edit";
}

TEST_F(RecoveryTest, DiscardDeletesAKilledRunsCopy) {
  ASSERT_NO_FATAL_FAILURE(start("recovery_discard"));
  edit();
  ASSERT_TRUE(copyIsCurrent()) << "no recovery copy of the unsaved graph in " << copy();
  ASSERT_EQ(runtime_->stop(SIGKILL), 128 + SIGKILL);
  ASSERT_NO_FATAL_FAILURE(restart());
  const auto offer = recovery("keep");
  ASSERT_TRUE(offer.offered);
  const auto discarded = recovery("discard");
  ASSERT_TRUE(discarded.success) << discarded.message;
  EXPECT_FALSE(discarded.offered);
  EXPECT_FALSE(fs::exists(offer.path)) << "discard left " << offer.path;
  EXPECT_FALSE(has("ticks"));
  ASSERT_EQ(runtime_->stop(SIGINT), 0);
  ASSERT_NO_FATAL_FAILURE(restart());
  EXPECT_FALSE(recovery("keep").offered) << "a discarded copy came back";
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_ros_recovery");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
