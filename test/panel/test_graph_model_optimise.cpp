// The panel's model, tuning: a parameter given to an Optimizer (a new one or the graph's) as one
// edit, with a dimension of its kind under a free name, and the best values applied as one edit.
#include <gmock/gmock.h>

#include "apex_rviz_plugin/graph_model.hpp"
#include "graph_model_fixture.hpp"

using namespace apex_rviz_plugin;
using namespace graph_model_fixture;

namespace {

TEST(GraphModel, OptimisingAParameterWithANewOptimizerIsOneEdit) {
  GraphModel m;
  m.update(tunable(false));
  EXPECT_TRUE(m.optimizers().empty());
  const apex::NodeTypeInfo type = optimizerType();
  EXPECT_FALSE(m.optimise("clock", "size", "", 10, 300, nullptr)) << "a new Optimizer's names unknown: not guessed";
  auto e = m.optimise("clock", "size", "", 10, 300, &type);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->label, "Optimise clock/size with optimizer_1");
  EXPECT_THAT(services(e->apply), ::testing::ElementsAre("add_node", "set_ui", "set_interactive", "set_parameter", "connect"));
  EXPECT_EQ(std::get<apex::AddNode::Request>(e->apply[0].request).type, kOptimizerType);
  EXPECT_EQ(std::get<apex::SetParameter::Request>(e->apply[3].request).value, "[size int]");  // an int parameter
  const auto& link = std::get<apex::Connect::Request>(e->apply[4].request);
  EXPECT_EQ(link.from_node + "/" + link.from_port + " -> " + link.to_node + "/" + link.to_port, "optimizer_1/size -> clock/size");
  EXPECT_THAT(services(e->revert), ::testing::ElementsAre("disconnect", "remove_node", "set_interactive"));
  EXPECT_FALSE(m.optimise("clock", "label", "", 0, 0, &type)) << "a string is not tuned";
  EXPECT_FALSE(m.optimise("clock", "nothing", "", 0, 0, &type));
}

TEST(GraphModel, IntervalsChoicesAndFlagsAreTunedAsTheirKind) {
  auto g = tunable(false);
  const auto add = [&](const char* name, const char* kind, const char* type, const char* value) {
    g.nodes[0].parameters.push_back(param(name, value));
    g.nodes[0].parameters.back().kind = kind, g.nodes[0].parameters.back().type = type;
  };
  add("area", "interval", "interval", "[0.0, 100.0]");
  add("method", "set", "string", "mean");
  add("on", "bool", "bool", "false");
  add("colour", "color", "color", "{r: 1, g: 2, b: 3}");
  GraphModel m;
  m.update(g);
  const apex::NodeTypeInfo type = optimizerType();
  const auto dimension = [&](const char* name) {
    const auto e = m.optimise("clock", name, "", 0, 0, &type);
    return e ? std::get<apex::SetParameter::Request>(e->apply[3].request).value : "(refused)";
  };
  EXPECT_EQ(dimension("area"), "[area interval]");
  EXPECT_EQ(dimension("method"), "[method choice]");
  EXPECT_EQ(dimension("on"), "[on bool]");
  EXPECT_EQ(dimension("colour"), "(refused)");
}

TEST(GraphModel, ADimensionIsNamedAfterNoneOfTheOptimizersOwnPortsOrParameters) {
  auto g = tunable(true);
  for (const char* name : {"seed", "fitness"}) {  // as the Optimizer's manifest names a parameter and an input
    g.nodes[0].parameters.push_back(param(name, "1"));
    g.nodes[0].parameters.back().type = "int";
  }
  GraphModel m;
  m.update(g);
  const apex::NodeTypeInfo type = optimizerType();
  auto dimension = [](const std::optional<Edit>& e) {
    return e ? std::get<apex::Connect::Request>(e->apply.back().request).from_port : "(refused)";
  };
  // a new Optimizer: the names its type lists
  const auto seed = m.optimise("clock", "seed", "", 0, 0, &type);
  ASSERT_TRUE(seed);
  EXPECT_EQ(dimension(seed), "clock_seed");
  EXPECT_EQ(std::get<apex::SetParameter::Request>(seed->apply[3].request).value, "[clock_seed int]");
  EXPECT_EQ(dimension(m.optimise("clock", "fitness", "", 0, 0, &type)), "clock_fitness");
  EXPECT_EQ(dimension(m.optimise("clock", "size", "", 0, 0, &type)), "size") << "a name the type does not have is kept";
  // the graph's Optimizer: its type's names, and without the type those the node has (`tuner` lists
  // fitness, not seed)
  EXPECT_EQ(dimension(m.optimise("clock", "seed", "tuner", 0, 0, &type)), "clock_seed");
  EXPECT_EQ(dimension(m.optimise("clock", "fitness", "tuner", 0, 0, nullptr)), "clock_fitness");
  EXPECT_EQ(dimension(m.optimise("clock", "seed", "tuner", 0, 0, nullptr)), "seed");
}

TEST(GraphModel, OptimisingWithAnExistingOptimizerAddsADimensionUnderAFreeName) {
  GraphModel m;
  auto g = tunable(true);
  apex::NodeInfo other = g.nodes[0];
  other.name = "clock2";  // a second node with a parameter named `rate`, already a dimension
  g.nodes.push_back(other);
  m.update(g);
  EXPECT_EQ(m.optimizers(), std::vector<std::string>{"tuner"});
  auto e = m.optimise("clock2", "rate", "tuner", 0, 0, nullptr);  // the type not known: the node's own names
  ASSERT_TRUE(e);
  EXPECT_THAT(services(e->apply), ::testing::ElementsAre("set_parameter", "connect"));  // rate is interactive already
  EXPECT_EQ(std::get<apex::SetParameter::Request>(e->apply[0].request).value, "[rate, clock2_rate]");
  EXPECT_EQ(std::get<apex::Connect::Request>(e->apply[1].request).from_port, "clock2_rate");
  EXPECT_THAT(services(e->revert), ::testing::ElementsAre("disconnect", "set_parameter"));
  EXPECT_EQ(std::get<apex::SetParameter::Request>(e->revert[1].request).value, "[rate]");
  EXPECT_FALSE(m.optimise("clock", "rate", "nobody", 0, 0, nullptr));
}

TEST(GraphModel, ApplyingTheBestValuesIsOneEditUndoneToTheValuesBefore) {
  GraphModel m;
  m.update(tunable(true));
  auto e = m.applyBest("tuner");
  ASSERT_TRUE(e);
  ASSERT_EQ(e->apply.size(), 1u);
  const auto& set = std::get<apex::SetParameter::Request>(e->apply[0].request);
  EXPECT_EQ(set.node + "/" + set.parameter + " = " + set.value, "clock/rate = 42.5");
  EXPECT_EQ(std::get<apex::SetParameter::Request>(e->revert[0].request).value, "20.0");
  auto g = tunable(true);
  g.revision = 2;
  g.nodes.back().parameters[1].value = "''";  // no run yet
  m.update(g);
  EXPECT_FALSE(m.applyBest("tuner"));
}

TEST(GraphModel, APointOfTheFrontIsAppliedAsOneEditUndoneToTheValuesBefore) {
  auto g = tunable(true);
  g.nodes.back().parameters.push_back(param("front",
                                            "'[{evaluation: 4, fitness: 0.5, ms_per_frame: 1.25, values: {rate: 10}}, "
                                            "{evaluation: 9, fitness: 0.75, ms_per_frame: 3.5, values: {rate: 30.5}}]'"));
  GraphModel m;
  m.update(g);
  const auto front = m.front("tuner");
  ASSERT_EQ(front.size(), 2u);
  EXPECT_EQ(front[1].evaluation, 9);
  EXPECT_EQ(front[1].fitness, 0.75);
  EXPECT_EQ(front[1].ms_per_frame, 3.5);
  EXPECT_EQ(front[1].values, "{rate: 30.5}");
  auto e = m.applyFrontPoint("tuner", 9);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->label, "Apply evaluation 9 of tuner's front");
  ASSERT_EQ(e->apply.size(), 1u);
  const auto& set = std::get<apex::SetParameter::Request>(e->apply[0].request);
  EXPECT_EQ(set.node + "/" + set.parameter + " = " + set.value, "clock/rate = 30.5");
  EXPECT_EQ(std::get<apex::SetParameter::Request>(e->revert[0].request).value, "20.0");
  EXPECT_FALSE(m.applyFrontPoint("tuner", 5)) << "no such point";
  EXPECT_TRUE(m.front("clock").empty());
  g.revision = 2;
  g.nodes.back().parameters.push_back(param("state", "'running: evaluation 3 of 60'"));
  m.update(g);
  EXPECT_FALSE(m.applyFrontPoint("tuner", 9)) << "not while it runs";
}

}  // namespace
