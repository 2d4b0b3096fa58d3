// What the model's tests share: a small graph as a ~graph message describes it (a clock, a relay,
// a counter), the same with parameters to tune, the Optimizer node type as list_node_types
// describes it, and the services of a list of calls.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "apex_rviz_plugin/graph_model.hpp"

namespace graph_model_fixture {

inline apex::PortInfo port(const std::string& name, const std::string& kind, const std::string& type) {
  apex::PortInfo p;
  p.name = name, p.kind = kind, p.type = type;
  return p;
}

inline apex::ParamInfo param(const std::string& name, const std::string& value, bool interactive = false) {
  apex::ParamInfo p;
  p.name = name, p.value = value, p.interactive = interactive;
  return p;
}

/** clock --count--> relay --out--> count, and clock/processed --> count/reset */
inline apex::GraphState graph(std::uint64_t revision) {
  apex::GraphState g;
  g.revision = revision;
  apex::NodeInfo clock, relay, count;
  clock.name = "clock", clock.type = "apex_nodes/Clock", clock.thread_group = "default", clock.enabled = true;
  clock.ports = {port("count", "output", "int"), port("time", "output", "double"), port("processed", "trigger", "")};
  clock.parameters = {param("rate", "20.0", true)};
  clock.ui = "{x: 10, y: 20}";
  relay.name = "relay", relay.type = "apex_nodes/Relay", relay.thread_group = "vision", relay.enabled = false;
  relay.ports = {port("in", "input", "any"), port("out", "output", "any")};
  count.name = "count", count.type = "apex_nodes/Counter", count.enabled = true;
  count.ports = {port("in", "input", "any"), port("count", "output", "int"), port("reset", "slot", "")};
  g.nodes = {clock, relay, count};
  apex::Connection a, b, e;
  a.from_node = "clock", a.from_port = "count", a.to_node = "relay", a.to_port = "in";
  b.from_node = "relay", b.from_port = "out", b.to_node = "count", b.to_port = "in";
  e.from_node = "clock", e.from_port = "processed", e.to_node = "count", e.to_port = "reset";
  g.connections = {a, b, e};
  return g;
}

/** graph(1) with the clock's rate a double and an int `size`, and (if `opt`) an Optimizer tuning the rate. */
inline apex::GraphState tunable(bool opt) {
  auto g = graph(1);
  g.nodes[0].parameters[0].type = "double";
  g.nodes[0].parameters.push_back(param("size", "3"));
  g.nodes[0].parameters.back().type = "int";
  g.nodes[0].parameters.push_back(param("label", "'x'"));
  g.nodes[0].parameters.back().type = "string";
  if (!opt) return g;
  apex::NodeInfo o;
  o.name = "tuner", o.type = apex_rviz_plugin::kOptimizerType, o.enabled = true;
  o.ports = {port("fitness", "input", "double"), port("rate", "output", "double")};
  o.parameters = {param("dimensions", "[rate]"), param("best_values", "'{rate: 42.5}'")};
  g.nodes.push_back(o);
  apex::Connection c;
  c.from_node = "tuner", c.from_port = "rate", c.to_node = "clock", c.to_port = "rate";
  g.connections.push_back(c);
  return g;
}

inline std::vector<std::string> services(const std::vector<apex_rviz_plugin::Call>& calls) {
  std::vector<std::string> out;
  for (const auto& c : calls) out.push_back(c.service);
  return out;
}

/** The Optimizer node type as the runtime's list_node_types describes it (apex_nodes/generic/optimizer.cpp,
 *  with the events every node has): its ports and parameters, no dimension outputs. */
inline apex::NodeTypeInfo optimizerType() {
  apex::NodeTypeInfo t;
  t.id = apex_rviz_plugin::kOptimizerType;
  t.ports = {port("fitness", "input", "double"),
             port("best_fitness", "output", "double"),
             port("evaluations", "output", "int"),
             port("best", "output", "string"),
             port("enable", "slot", ""),
             port("disable", "slot", ""),
             port("start", "slot", ""),
             port("stop", "slot", ""),
             port("apply_best", "slot", ""),
             port("processed", "trigger", ""),
             port("evaluate", "trigger", ""),
             port("finished", "trigger", "")};
  for (const char* name :
       {"dimensions", "algorithm", "budget", "seed", "population", "F", "CR", "minimize", "state", "best_values"})
    t.parameters.push_back(param(name, ""));
  return t;
}

}  // namespace graph_model_fixture
