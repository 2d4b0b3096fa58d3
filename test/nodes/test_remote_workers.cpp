// The Optimizer's remote workers: candidates sent to the Optimizer of the same name in another
// runtime, which evaluates each in copies of its evaluated part. Here two graphs in one process
// stand for two runtimes, joined by a transport that hands a request to the Optimizer served
// under a runtime's name (the ROS one is checked by optuna.test).
#include <gmock/gmock.h>

#include <cctype>
#include <map>
#include <mutex>

#include "apex_nodes/remote_workers.hpp"
#include "tuning_loop.hpp"

using namespace apex_test;
using namespace apex_test::tuning;
using apex_nodes::tuning::CandidateValues;
using apex_nodes::tuning::RemoteWorkers;
using ::testing::HasSubstr;

namespace {

/** Requests to a runtime's name go to the Optimizer "opt" of the graph given that name. */
class InProcess : public RemoteWorkers {
 public:
  void name(const std::string& runtime, Graph& g) {
    std::lock_guard<std::mutex> lock(mutex_);
    names_[runtime] = g.nodeObject("opt");
  }
  void evaluate(const std::string& runtime, const std::string& optimizer, CandidateValues values, bool with_cost,
                Done done) override {
    Serve serve;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (auto n = names_.find(runtime); n != names_.end() && served_.count(n->second)) serve = served_.at(n->second);
    }
    if (!serve || optimizer != "opt") return done({"no runtime " + runtime + " serves '" + optimizer + "'", 0, 0});
    serve(std::move(values), with_cost, std::move(done));
  }
  /** Whether the Optimizer named `runtime` serves (it starts to in its setup, on its group's thread). */
  bool serves(const std::string& runtime) {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto n = names_.find(runtime);
    return n != names_.end() && served_.count(n->second) > 0;
  }
  std::shared_ptr<void> serve(const apex::Node& node, Serve serve) override {
    std::lock_guard<std::mutex> lock(mutex_);
    served_[&node] = std::move(serve);
    return std::shared_ptr<void>(new int(0), [this, n = &node](int* p) {
      delete p;
      std::lock_guard<std::mutex> lock(mutex_);
      served_.erase(n);
    });
  }

 private:
  std::mutex mutex_;
  std::map<std::string, const apex::Node*> names_;
  std::map<const apex::Node*, Serve> served_;
};

class RemoteWorkersTest : public ::testing::Test {
 protected:
  void SetUp() override {
    registry();  // the node libraries loaded first: the ROS one sets its transport as it loads
    before_ = apex_nodes::tuning::setRemoteWorkers(transport_);
  }
  void TearDown() override { apex_nodes::tuning::setRemoteWorkers(before_); }
  /** `loop` serves as the runtime `runtime`, running (once its Optimizer serves: as a runtime is
   *  up once its services are). */
  void serveAs(const std::string& runtime, Loop& loop) {
    transport_->name(runtime, loop.g);
    loop.g.start();
    EXPECT_TRUE(waitUntil([&] { return transport_->serves(runtime); })) << runtime << " never served";
  }
  std::shared_ptr<InProcess> transport_ = std::make_shared<InProcess>();
  std::shared_ptr<RemoteWorkers> before_;
};

/** The Optimizer's error, "" if none. */
std::string errorOf(Graph& g) {
  for (const auto& s : g.nodeStats())
    if (s.name == "opt") return s.error;
  return "";
}

/** The number just before `what` in `state` ("...; 17 evaluated by /b": 17), -1 if none. */
int countBefore(const std::string& state, const std::string& what) {
  const auto at = state.find(what);
  if (at == std::string::npos || at == 0) return -1;
  auto from = at;
  while (from > 0 && std::isdigit(static_cast<unsigned char>(state[from - 1]))) --from;
  return from == at ? -1 : std::stoi(state.substr(from, at - from));
}

TEST_F(RemoteWorkersTest, ARemoteWorkerTakesTheCourseOfAWorkerHereAndEachCandidateIsEvaluatedOnce) {
  Loop two(5), here(5), there(5);
  const auto expected = studyOfRun("differential_evolution", 2, two);
  serveAs("/b", there);
  ASSERT_TRUE(here.g.setParameter("opt", "remote_workers", "[/b]"));
  const auto rows = studyOfRun("differential_evolution", 1, here);
  ASSERT_EQ(rows.size(), 40u);
  EXPECT_EQ(rows, expected) << "one worker here and one there take the course of two workers here";
  for (const auto& row : rows) EXPECT_TRUE(scoredItsOwnValue(row)) << row;
  const std::string state = paramText(here.g, "opt", "state"), served = paramText(there.g, "opt", "state");
  const int remote = countBefore(state, " evaluated by /b");
  EXPECT_GT(remote, 0) << state;
  EXPECT_EQ(countBefore(served, " candidates for other runtimes"), remote) << served;
  EXPECT_LT(remote, 40) << "and some here";
  EXPECT_EQ(here.seen()->size(), 0u) << "both graphs rest: copies evaluate, here and there";
  EXPECT_EQ(there.seen()->size(), 0u);
}

TEST_F(RemoteWorkersTest, ARuntimeThatIsNotThereStopsTheRunSayingWhichAndTheGraphPlaysOn) {
  Loop here(5);
  ASSERT_TRUE(here.g.setParameter("opt", "remote_workers", "[/nowhere]"));
  here.g.start();
  ASSERT_TRUE(here.g.fireSlot("opt", "start"));
  ASSERT_TRUE(waitState(here.g, "stopped")) << paramText(here.g, "opt", "state");
  EXPECT_THAT(errorOf(here.g), HasSubstr("remote worker /nowhere: no runtime /nowhere"));
  ASSERT_TRUE(here.g.waitIdle(kWait));
  const std::size_t seen = here.seen()->size();
  ASSERT_TRUE(here.g.fireSlot("seq", "restart"));
  EXPECT_TRUE(here.seen()->waitFor(seen + 5));
}

TEST_F(RemoteWorkersTest, AnOptimizerRunningASearchOfItsOwnRefusesAndTheAskingRunStops) {
  Loop here(5), there(20);
  serveAs("/b", there);
  ASSERT_TRUE(there.g.setParameter("opt", "budget", "100000"));
  ASSERT_TRUE(there.g.fireSlot("opt", "start"));
  ASSERT_TRUE(waitState(there.g, "running"));
  ASSERT_TRUE(here.g.setParameter("opt", "remote_workers", "[/b]"));
  here.g.start();
  ASSERT_TRUE(here.g.fireSlot("opt", "start"));
  ASSERT_TRUE(waitState(here.g, "stopped")) << paramText(here.g, "opt", "state");
  EXPECT_THAT(errorOf(here.g), HasSubstr("remote worker /b: the optimizer 'opt' there runs a search of its own"));
  EXPECT_TRUE(waitState(there.g, "running")) << "its own run goes on";
}

TEST_F(RemoteWorkersTest, RemovingTheServingOptimizerAnswersWhatWasAskedAndNothingWaitsForever) {
  Loop here(5), there(200);
  serveAs("/b", there);
  ASSERT_TRUE(here.g.setParameter("opt", "remote_workers", "[/b, /b]"));
  ASSERT_TRUE(here.g.setParameter("opt", "budget", "100000"));
  here.g.start();
  ASSERT_TRUE(here.g.fireSlot("opt", "start"));
  ASSERT_TRUE(waitUntil([&] { return errorOf(there.g).empty() && paramText(there.g, "opt", "state").rfind("served", 0) == 0; }));
  ASSERT_TRUE(there.g.removeNode("opt"));
  ASSERT_TRUE(waitState(here.g, "stopped")) << paramText(here.g, "opt", "state");
  EXPECT_THAT(errorOf(here.g), HasSubstr("remote worker /b: "));
}

}  // namespace
