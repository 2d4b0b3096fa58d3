// Flow nodes (#34): Buffer, Accumulate, Demux, Latch, Statistics, Compare, Switch, Stamp; and
// withHeader, which Stamp uses, against headerOf for every stamped type.
#include <gmock/gmock.h>
#include <ros/time.h>

#include "apex_nodes/flow.hpp"
#include "apex_nodes/stamp.hpp"
#include "apex_test/node_harness.hpp"

using namespace apex_test;
using apex_nodes::MessageList;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

namespace {

constexpr int kNothing = -999;

/** The ints of a list message; Nothing (the message or an element) as kNothing. */
std::vector<int> ints(const Message& list) {
  if (list.isNothing()) return {kNothing};
  std::vector<int> out;
  for (const auto& m : *list.as<MessageList>()) out.push_back(m.isNothing() ? kNothing : *m.as<int>());
  return out;
}

int intOf(const Message& m) { return m.isNothing() ? kNothing : *m.as<int>(); }

/** A second sink, on another output of the harness's node. */
Collector* tap(NodeHarness& h, const std::string& output) {
  add(h.graph(), "test/Collector", "tap_" + output);
  link(h.graph(), "node", output, "tap_" + output, "in");
  return object<Collector>(h.graph(), "tap_" + output);
}

Message last(Collector* sink) { return sink->size() ? sink->messages().back() : Message(); }

/** A test/Counter whose `reset` slot counts the events of the node's trigger. */
Counter* events(NodeHarness& h, const std::string& trigger) {
  add(h.graph(), "test/Counter", "on_" + trigger);
  link(h.graph(), "node", trigger, "on_" + trigger, "reset");
  return object<Counter>(h.graph(), "on_" + trigger);
}

void fire(NodeHarness& h, const std::string& slot) {
  ASSERT_TRUE(h.graph().fireSlot("node", slot));
  ASSERT_TRUE(h.graph().waitIdle(kWait));
}

/** The end of a sequence on the first input, as a player sends it after its last frame. */
void endSequence(NodeHarness& h) {
  object<MessageFeeder>(h.graph(), "in0")->feed(Message::endOfSequence());
  ASSERT_TRUE(h.graph().waitIdle(kWait));
}

std::shared_ptr<const apex_nodes::Cloud> cloudAt(double t) {
  auto c = std::make_shared<apex_nodes::Cloud>();
  c->header.stamp = ros::Time(t);
  c->header.frame_id = "lidar";
  c->header.seq = 7;
  c->points = std::make_shared<pcl::PCLPointCloud2>();
  return c;
}

TEST(FlowNodes, BufferSendsTheLastNMessagesOldestFirst) {
  NodeHarness h("apex_nodes/Buffer", {"in"}, "window");
  h.set("size", "3");
  EXPECT_THAT(ints(h.run({Message::make(1)})), ElementsAre(1));  // shorter at first
  EXPECT_THAT(ints(h.run({Message::make(2)})), ElementsAre(1, 2));
  EXPECT_THAT(ints(h.run({Message::make(3)})), ElementsAre(1, 2, 3));
  EXPECT_THAT(ints(h.run({Message::make(4)})), ElementsAre(2, 3, 4));
  const auto payload = std::make_shared<const std::string>("same object");
  EXPECT_EQ(h.run(payload).as<MessageList>()->back().raw(), payload.get());
  fire(h, "reset");
  EXPECT_THAT(ints(h.run({Message::make(5)})), ElementsAre(5));
  endSequence(h);  // a new pass starts with an empty window
  EXPECT_THAT(ints(h.run({Message::make(6)})), ElementsAre(6));
}

TEST(FlowNodes, BufferWithFullOnlySendsNothingUntilTheWindowIsFull) {
  NodeHarness h("apex_nodes/Buffer", {"in"}, "window");
  h.set("size", "2");
  h.set("full_only", "true");
  EXPECT_THAT(ints(h.run({Message::make(1)})), ElementsAre(kNothing));
  EXPECT_THAT(ints(h.run({Message::make(2)})), ElementsAre(1, 2));
}

TEST(FlowNodes, AccumulateSendsEveryCountMessagesAsOneList) {
  NodeHarness h("apex_nodes/Accumulate", {"in"}, "values");
  h.set("count", "3");
  EXPECT_TRUE(h.run({Message::make(1)}).isNothing());
  EXPECT_TRUE(h.run({Message()}).isNothing());  // Nothing is not collected
  EXPECT_TRUE(h.run({Message::make(2)}).isNothing());
  EXPECT_THAT(ints(h.run({Message::make(3)})), ElementsAre(1, 2, 3));
  EXPECT_TRUE(h.run({Message::make(4)}).isNothing());  // a new list starts
}

TEST(FlowNodes, AccumulateSendsAtFlushAndAtTheEndOfASequence) {
  NodeHarness h("apex_nodes/Accumulate", {"in"}, "values");  // count 0: only at events
  auto* sink = object<Collector>(h.graph(), "sink");
  for (int v : {1, 2}) EXPECT_TRUE(h.run({Message::make(v)}).isNothing());
  fire(h, "flush");
  EXPECT_THAT(ints(last(sink)), ElementsAre(1, 2));
  fire(h, "flush");
  EXPECT_THAT(ints(last(sink)), ElementsAre());  // asked for: an empty list
  for (int v : {3, 4}) h.run({Message::make(v)});
  const auto before = sink->size();
  fire(h, "reset");  // dropped, nothing sent
  EXPECT_EQ(sink->size(), before);
  for (int v : {5, 6}) h.run({Message::make(v)});
  EXPECT_THAT(ints(h.run({Message::endOfSequence()})), ElementsAre(5, 6));  // in the token's place
}

TEST(FlowNodes, DemuxSendsOnTheChosenOutputAndNothingOnTheOthers) {
  NodeHarness h("apex_nodes/Demux", {"in"}, "out_2", {{"outputs", "3"}});
  auto* first = tap(h, "out_0");
  h.set("choice", "2");
  EXPECT_EQ(intOf(h.run({Message::make(7)})), 7);
  EXPECT_TRUE(last(first).isNothing());
  h.set("choice", "0");
  EXPECT_TRUE(h.run({Message::make(8)}).isNothing());
  EXPECT_EQ(intOf(last(first)), 8);
  h.set("choice", "5");
  EXPECT_TRUE(h.run({Message::make(9)}).isNothing());
  EXPECT_TRUE(last(first).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("choice 5 but only 3 outputs"));
}

TEST(FlowNodes, LatchHoldsTheLastMessageThroughNothingUntilReset) {
  NodeHarness h("apex_nodes/Latch", {"in"}, "out");
  EXPECT_TRUE(h.run({Message()}).isNothing());  // nothing held yet
  EXPECT_EQ(intOf(h.run({Message::make(1)})), 1);
  EXPECT_EQ(intOf(h.run({Message()})), 1);
  EXPECT_EQ(intOf(h.run({Message()})), 1);
  EXPECT_EQ(intOf(h.run({Message::make(2)})), 2);
  EXPECT_EQ(intOf(h.run({Message()})), 2);
  fire(h, "reset");
  EXPECT_TRUE(h.run({Message()}).isNothing());
  EXPECT_EQ(intOf(h.run({Message::make(3)})), 3);
  endSequence(h);
  EXPECT_TRUE(h.run({Message()}).isNothing());  // a new pass does not get the last one's message
}

TEST(FlowNodes, StatisticsOverAWindowOfIntsAndDoubles) {
  NodeHarness h("apex_nodes/Statistics", {"value"}, "mean");
  auto *std_dev = tap(h, "std"), *low = tap(h, "min"), *high = tap(h, "max"), *count = tap(h, "count");
  h.set("window", "3");
  EXPECT_DOUBLE_EQ(*h.run({Message::make(4)}).as<double>(), 4.0);
  EXPECT_DOUBLE_EQ(*last(std_dev).as<double>(), 0.0);
  h.run({Message::make(1.0)});
  h.run({Message::make(2)});
  EXPECT_DOUBLE_EQ(*h.run({Message::make(12.0)}).as<double>(), 5.0);  // 1, 2, 12: the 4 left the window
  EXPECT_DOUBLE_EQ(*last(std_dev).as<double>(), std::sqrt((16.0 + 9.0 + 49.0) / 3.0));  // population std
  EXPECT_DOUBLE_EQ(*last(low).as<double>(), 1.0);
  EXPECT_DOUBLE_EQ(*last(high).as<double>(), 12.0);
  EXPECT_EQ(intOf(last(count)), 3);
  EXPECT_TRUE(h.run({Message::make(std::string("7"))}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("input 'value' carries string, not a number (int or double)"));
  fire(h, "reset");
  EXPECT_DOUBLE_EQ(*h.run({Message::make(-3)}).as<double>(), -3.0);
  EXPECT_EQ(intOf(last(count)), 1);
}

TEST(FlowNodes, CompareAnswersAndFiresWhenTheAnswerChanges) {
  NodeHarness h("apex_nodes/Compare", {"value"}, "result");
  auto *rose = events(h, "rose"), *fell = events(h, "fell");
  h.set("operator", "less");
  h.set("threshold", "0.5");
  EXPECT_TRUE(*h.run({Message::make(0.2)}).as<bool>());  // false before the first value: rose
  EXPECT_EQ(rose->resets.load(), 1);
  EXPECT_TRUE(*h.run({Message::make(0)}).as<bool>());  // an int too; still true: no event
  EXPECT_EQ(rose->resets.load(), 1);
  EXPECT_FALSE(*h.run({Message::make(0.9)}).as<bool>());
  EXPECT_EQ(fell->resets.load(), 1);
  EXPECT_FALSE(*h.run({Message::make(0.5)}).as<bool>());
  EXPECT_TRUE(*h.run({Message::make(-1)}).as<bool>());
  EXPECT_EQ(rose->resets.load(), 2);
  EXPECT_EQ(fell->resets.load(), 1);
  h.set("operator", "equal");
  h.set("tolerance", "0.01");
  EXPECT_TRUE(*h.run({Message::make(0.505)}).as<bool>());
  EXPECT_TRUE(h.run({Message::make(true)}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("input 'value' carries bool, not a number (int or double)"));
}

TEST(FlowNodes, SwitchPassesWhileItsConditionIsTrue) {
  NodeHarness h("apex_nodes/Switch", {"in", "condition"}, "out");
  const auto payload = std::make_shared<const std::string>("scan");
  EXPECT_EQ(h.run({Message::share<std::string>(payload), Message::make(true)}).raw(), payload.get());
  EXPECT_TRUE(h.run({Message::share<std::string>(payload), Message::make(false)}).isNothing());
  EXPECT_EQ(*h.run({Message::make(3), Message::make(true)}).as<int>(), 3);
  EXPECT_TRUE(h.error().empty()) << h.error();
}

TEST(FlowNodes, StampOffsetsOrSetsTheStampAndKeepsTheRest) {
  NodeHarness h("apex_nodes/Stamp", {"in"}, "out");
  h.set("mode", "offset");
  h.set("offset", "-0.25");
  const auto in = cloudAt(10.0);
  const Message out = h.run(in);
  const auto cloud = out.as<apex_nodes::Cloud>();
  ASSERT_TRUE(cloud) << out.typeName() << ": " << h.error();
  EXPECT_DOUBLE_EQ(cloud->header.stamp.toSec(), 9.75);
  EXPECT_EQ(cloud->header.frame_id, "lidar");
  EXPECT_EQ(cloud->header.seq, 7u);
  EXPECT_EQ(cloud->points, in->points);  // the points shared, not copied
  EXPECT_DOUBLE_EQ(in->header.stamp.toSec(), 10.0);  // the input untouched
  auto exact = std::make_shared<apex_nodes::Cloud>(*in);
  exact->header.stamp = ros::Time(1700000000, 123456789);
  h.set("offset", "0");
  EXPECT_EQ(h.run(std::shared_ptr<const apex_nodes::Cloud>(exact)).as<apex_nodes::Cloud>()->header.stamp,
            ros::Time(1700000000, 123456789));  // to the nanosecond
  h.set("offset", "-20");
  EXPECT_TRUE(h.run(in).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("outside ROS time"));
  h.set("mode", "fixed");
  h.set("stamp", "42.5");
  EXPECT_DOUBLE_EQ(h.run(in).as<apex_nodes::Cloud>()->header.stamp.toSec(), 42.5);
}

TEST(FlowNodes, StampNowIsTheClocksTime) {
  NodeHarness h("apex_nodes/Stamp", {"in"}, "out");  // mode now by default
  const double before = ros::WallTime::now().toSec();
  const double stamp = h.run(cloudAt(10.0)).as<apex_nodes::Cloud>()->header.stamp.toSec();
  EXPECT_GE(stamp, before);
  EXPECT_LE(stamp, ros::WallTime::now().toSec());
}

TEST(FlowNodes, StampRefusesAMessageWithoutAHeaderNamingItsType) {
  NodeHarness h("apex_nodes/Stamp", {"in"}, "out");
  EXPECT_TRUE(h.run({Message::make(3)}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("cannot stamp a int: it has no header (stamped types: apex_nodes/Image,"));
}

/** withHeader sets what headerOf reads, for each stamped type, in a new object of the same type. */
template <class... Ts>
void expectRestampable(apex_nodes::TypeList<Ts...>) {
  std_msgs::Header header;
  header.stamp = ros::Time(5, 6);
  header.frame_id = "map";
  auto one = [&](const Message& in) {
    const auto out = apex_nodes::withHeader(in, header);
    ASSERT_TRUE(out) << in.typeName();
    EXPECT_EQ(out->type(), in.type()) << in.typeName();
    EXPECT_NE(out->raw(), in.raw()) << in.typeName();
    EXPECT_EQ(apex_nodes::headerOf(*out)->stamp, header.stamp) << in.typeName();
    EXPECT_EQ(apex_nodes::headerOf(*out)->frame_id, "map") << in.typeName();
    EXPECT_EQ(apex_nodes::headerOf(in)->frame_id, "") << in.typeName();
  };
  (one(Message::make(Ts{})), ...);
}

TEST(FlowNodes, WithHeaderRestampsEveryTypeHeaderOfReads) {
  expectRestampable(apex_nodes::StampedTypes{});
  EXPECT_FALSE(apex_nodes::withHeader(Message::make(1.0), std_msgs::Header()));
  EXPECT_FALSE(apex_nodes::withHeader(Message(), std_msgs::Header()));
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
