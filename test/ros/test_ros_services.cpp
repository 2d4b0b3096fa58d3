// Every service of the runtime as a client sees it: the success path, the error
// paths with their messages, and the graph unchanged after a refused edit.
#include "services_fixture.hpp"

using namespace services_test;

namespace {

TEST_F(Services, ListNodeTypesDescribesEveryTypeAndNamesLoadErrors) {
  auto res = call<apex::ListNodeTypes>("list_node_types");
  ASSERT_TRUE(res.success);
  const apex::NodeTypeInfo* clock = nullptr;
  for (const auto& t : res.types)
    if (t.id == "apex_nodes/Clock") clock = &t;
  ASSERT_NE(clock, nullptr);
  EXPECT_FALSE(clock->description.empty());
  ASSERT_EQ(clock->parameters.size(), 1u);
  EXPECT_EQ(clock->parameters[0].name, "rate");
  EXPECT_EQ(clock->parameters[0].kind, "double range");
  EXPECT_EQ(clock->parameters[0].max, 1000.0);
  EXPECT_THAT(clock->ports[0].kind, "output");
  std::string errors;
  for (const auto& e : res.load_errors) errors += e + "\n";
  EXPECT_THAT(errors, HasSubstr("node library 'apex_test/NoLibrary'"));
  EXPECT_THAT(errors, HasSubstr("libapex_not_built"));
  EXPECT_THAT(errors, HasSubstr("node library 'apex_test/NotExported'"));
  // A type that fails to register refuses its whole library, saying why
  EXPECT_THAT(errors, HasSubstr("node library 'apex_test/BadRegistration'"));
  EXPECT_THAT(errors, HasSubstr("1 of its node types failed to register, so none is loaded: node type "
                                "'apex_test/Misnamed': Output<int> 'value': manifest() declares no output 'value'"));
  for (const auto& t : res.types) EXPECT_NE(t.id, "apex_test/FineButRefused") << "a refused library's type was loaded";
}

TEST_F(Services, AddNodeAppliesParametersAndRefusesBadInput) {
  auto res = addNode("apex_nodes/Clock", "", "{rate: 25}");
  ASSERT_TRUE(res.success) << res.message;
  EXPECT_EQ(res.name, "clock_1");
  EXPECT_EQ(res.node.parameters.at(0).value, "25.0");
  const std::string before = graphText();
  refused(addNode("apex_nodes/Nope", "x"), before, "unknown node type 'apex_nodes/Nope'");
  refused(addNode("Clok", "x"), before, "unknown node type 'Clok': did you mean apex_nodes/Clock?");
  refused(addNode("apex_nodes/Clock", "x", "{rate: 0}"), before, "parameter 'rate': 0 is out of range [0.01, 1000]");
  refused(addNode("apex_nodes/Clock", "x", "{speed: 1}"), before, "has no parameter 'speed'");
  refused(addNode("apex_nodes/Clock", "x", "rate: [1"), before, "not valid YAML");
  refused(addNode("apex_nodes/Clock", "clock_1"), before, "a node named 'clock_1' already exists");
  refused(addNode("apex_nodes/Clock", "bad name"), before, "node name 'bad name'");
}

TEST_F(Services, AddNodeTakesATypesNameWithoutItsPackage) {
  auto res = addNode("Clock", "", "{rate: 5}");  // as a user types it: apex_nodes/Clock
  ASSERT_TRUE(res.success) << res.message;
  EXPECT_EQ(res.name, "clock_1");
  EXPECT_EQ(res.node.type, "apex_nodes/Clock");
  EXPECT_EQ(res.node.parameters.at(0).value, "5.0");
  EXPECT_THAT(graphText(), HasSubstr("type: apex_nodes/Clock"));  // saved under its whole id
}

TEST_F(Services, RemoveNode) {
  ASSERT_TRUE(addNode("apex_nodes/Relay", "r").success);
  apex::RemoveNode::Request req;
  req.name = "r";
  EXPECT_TRUE(call<apex::RemoveNode>("remove_node", req).success);
  const std::string before = graphText();
  refused(call<apex::RemoveNode>("remove_node", req), before, "no node named 'r'");
}

TEST_F(Services, ConnectAndDisconnectFollowEveryRule) {
  ASSERT_TRUE(addNode("apex_nodes/Clock", "clock").success);
  ASSERT_TRUE(addNode("apex_nodes/Relay", "a").success);
  ASSERT_TRUE(addNode("apex_nodes/Relay", "b").success);
  ASSERT_TRUE(addNode("apex_nodes/Scale", "scale").success);
  ASSERT_TRUE(addNode("apex_nodes/Counter", "count").success);
  EXPECT_TRUE(connectPorts("connect", "clock", "count", "a", "in").success);
  EXPECT_TRUE(connectPorts("connect", "a", "out", "b", "in").success);
  EXPECT_TRUE(connectPorts("connect", "clock", "processed", "count", "reset").success);  // an event
  const std::string before = graphText();
  refused(connectPorts("connect", "clock", "count", "scale", "in"), before, "type mismatch");
  refused(connectPorts("connect", "b", "out", "a", "in"), before, "already connected (from clock)");
  refused(connectPorts("connect", "clock", "cnt", "b", "in"), before, "outputs: count, time");
  refused(connectPorts("connect", "ghost", "out", "b", "in"), before, "no node named 'ghost'");
  refused(connectPorts("connect", "clock", "processed", "b", "in"), before, "a trigger connects only to slots");
  ASSERT_TRUE(connectPorts("disconnect", "a", "out", "b", "in").success);
  refused(connectPorts("connect", "b", "out", "a", "in"), graphText(), "already connected");
  refused(connectPorts("disconnect", "a", "out", "b", "in"), graphText(), "not connected");
}

TEST_F(Services, CyclesAreRefused) {
  ASSERT_TRUE(addNode("apex_nodes/Relay", "a").success);
  ASSERT_TRUE(addNode("apex_nodes/Relay", "b").success);
  ASSERT_TRUE(connectPorts("connect", "a", "out", "b", "in").success);
  refused(connectPorts("connect", "b", "out", "a", "in"), graphText(), "would close a cycle");
}

TEST_F(Services, SetParameterReturnsTheAppliedValue) {
  ASSERT_TRUE(addNode("apex_nodes/Clock", "clock").success);
  apex::SetParameter::Request req;
  req.node = "clock", req.parameter = "rate", req.value = " 20 ";
  auto res = call<apex::SetParameter>("set_parameter", req);
  ASSERT_TRUE(res.success) << res.message;
  EXPECT_EQ(res.value, "20.0");
  const std::string before = graphText();
  req.value = "fast";
  res = call<apex::SetParameter>("set_parameter", req);
  refused(res, before, "parameter 'rate' (double range) expects a number, got 'fast'");
  EXPECT_EQ(res.value, "20.0");  // what stays
  req.parameter = "speed";
  refused(call<apex::SetParameter>("set_parameter", req), before, "no parameter 'speed' (parameters: rate)");
}

TEST_F(Services, NodeSettingsServices) {
  ASSERT_TRUE(addNode("apex_nodes/Scale", "scale").success);
  ASSERT_TRUE(addNode("apex_nodes/Counter", "count").success);
  apex::SetInteractive::Request inter;
  inter.node = "scale", inter.parameter = "factor", inter.interactive = true;
  EXPECT_TRUE(call<apex::SetInteractive>("set_interactive", inter).success);
  inter.parameter = "gain";
  refused(call<apex::SetInteractive>("set_interactive", inter), graphText(), "no parameter 'gain'");
  apex::SetEnabled::Request en;
  en.node = "scale", en.enabled = false;
  EXPECT_TRUE(call<apex::SetEnabled>("set_enabled", en).success);
  en.node = "ghost";
  refused(call<apex::SetEnabled>("set_enabled", en), graphText(), "no node named 'ghost'");
  apex::SetThreadGroup::Request grp;
  grp.node = "scale", grp.group = "vision";
  EXPECT_TRUE(call<apex::SetThreadGroup>("set_thread_group", grp).success);
  grp.group = "bad-name";
  refused(call<apex::SetThreadGroup>("set_thread_group", grp), graphText(), "thread group name 'bad-name'");
  apex::SetUi::Request ui;
  ui.node = "scale", ui.ui = "{x: 10, y: 20}";
  EXPECT_TRUE(call<apex::SetUi>("set_ui", ui).success);
  ui.ui = "{x: 1";
  refused(call<apex::SetUi>("set_ui", ui), graphText(), "not valid YAML");
  ui.ui = "{x: .nan, y: 1}";  // what a file could not hold back
  refused(call<apex::SetUi>("set_ui", ui), graphText(), "node 'scale': UI metadata holds '.nan', a number that is not finite");
  ui.ui = "{x: 1e309}";
  refused(call<apex::SetUi>("set_ui", ui), graphText(), "holds '1e309', a number that is not finite");
  apex::FireSlot::Request slot;
  slot.node = "count", slot.slot = "reset";
  EXPECT_TRUE(call<apex::FireSlot>("fire_slot", slot).success);
  slot.slot = "rest";
  refused(call<apex::FireSlot>("fire_slot", slot), graphText(), "slots: enable, disable, reset");

  auto graph = call<apex::GetGraph>("get_graph");
  ASSERT_EQ(graph.graph.nodes.size(), 2u);
  const auto& scale = graph.graph.nodes[0];
  EXPECT_EQ(scale.thread_group, "vision");
  EXPECT_EQ(scale.state, "disabled");
  EXPECT_EQ(scale.ui, "{x: 10, y: 20}");
  EXPECT_TRUE(scale.parameters[0].interactive);
  EXPECT_THAT(graph.yaml, HasSubstr("interactive: [factor]"));
}

TEST_F(Services, EveryServiceNamesANodeThatIsNotThere) {
  ASSERT_TRUE(addNode("apex_nodes/Clock", "clock").success);
  const std::string before = graphText();
  const std::string ghost = "no node named 'ghost'";
  refused(call<apex::RemoveNode>("remove_node",
                                 [] {
                                   apex::RemoveNode::Request r;
                                   r.name = "ghost";
                                   return r;
                                 }()),
          before, ghost);
  for (const char* service : {"connect", "disconnect"}) {
    apex::Connect::Request r;
    r.from_node = "ghost", r.from_port = "out", r.to_node = "clock", r.to_port = "rate";
    refused(call<apex::Connect>(service, r), before, "'ghost'");
  }
  apex::SetParameter::Request p;
  p.node = "ghost", p.parameter = "rate", p.value = "1";
  refused(call<apex::SetParameter>("set_parameter", p), before, ghost);
  apex::SetInteractive::Request i;
  i.node = "ghost", i.parameter = "rate", i.interactive = true;
  refused(call<apex::SetInteractive>("set_interactive", i), before, ghost);
  apex::SetEnabled::Request e;
  e.node = "ghost";
  refused(call<apex::SetEnabled>("set_enabled", e), before, ghost);
  apex::SetThreadGroup::Request t;
  t.node = "ghost", t.group = "vision";
  refused(call<apex::SetThreadGroup>("set_thread_group", t), before, ghost);
  apex::SetUi::Request u;
  u.node = "ghost", u.ui = "{x: 1}";
  refused(call<apex::SetUi>("set_ui", u), before, ghost);
  apex::FireSlot::Request f;
  f.node = "ghost", f.slot = "enable";
  refused(call<apex::FireSlot>("fire_slot", f), before, ghost);
  for (bool enable : {true, false}) {
    apex::Inspect::Request in;
    in.node = "ghost", in.port = "count", in.enable = enable;
    refused(call<apex::Inspect>("inspect", in), before, ghost);
  }
  apex::Group::Request g;
  g.nodes = {"clock", "ghost"}, g.name = "sub";
  refused(call<apex::Group>("group", g), before, "'ghost'");
  apex::Ungroup::Request ug;
  ug.name = "ghost";
  refused(call<apex::Ungroup>("ungroup", ug), before, "'ghost'");
  apex::RenameNode::Request rn;
  rn.name = "ghost", rn.new_name = "spirit";
  refused(call<apex::RenameNode>("rename_node", rn), before, ghost);
  apex::GetNodeProfile::Request np;
  np.node = "ghost";
  refused(call<apex::GetNodeProfile>("node_profile", np), before, ghost);
}

TEST_F(Services, NodeProfileGivesAFiringNodesHistogramAsBars) {
  ASSERT_TRUE(addNode("apex_nodes/Clock", "profiled", "{rate: 200}").success);
  apex::GetNodeProfile::Request req;
  req.node = "profiled";
  apex::GetNodeProfile::Response res;
  const auto until = ros::WallTime::now() + ros::WallDuration(30);
  std::uint64_t firings = 0;
  while (firings < 20 && ros::WallTime::now() < until) {  // a clock at 200 Hz: a few tenths of a second
    res = call<apex::GetNodeProfile>("node_profile", req);
    ASSERT_TRUE(res.success) << res.message;
    firings = 0;
    for (auto c : res.time_counts) firings += c;
    if (firings < 20) ros::WallDuration(0.05).sleep();
  }
  ASSERT_GE(firings, 20u);
  ASSERT_EQ(res.time_lower_ms.size(), res.time_counts.size());
  ASSERT_EQ(res.time_upper_ms.size(), res.time_counts.size());
  for (std::size_t i = 0; i < res.time_counts.size(); ++i) {
    EXPECT_LT(res.time_lower_ms[i], res.time_upper_ms[i]);
    EXPECT_GT(res.time_counts[i], 0u) << "only bars that hold any";
  }
  EXPECT_GT(res.window_s, 0);
  EXPECT_TRUE(res.latency_counts.empty()) << "a clock's numbers carry no stamp";
  EXPECT_THAT(res.message, ::testing::HasSubstr("no latency"));
}

TEST_F(Services, EveryServiceRefusesTextThatIsNotUtf8NamingTheField) {
  // set_ui once took "\xff\xfe"; get_graph then returned it, and save_graph named a file with it.
  ASSERT_TRUE(addNode("apex_nodes/Counter", "count").success);
  const std::string before = graphText(), bad = "{x: 1, note: \"\xff\xfe\"}";
  apex::SetUi::Request u;
  u.node = "count", u.ui = bad;
  refused(call<apex::SetUi>("set_ui", u), before,
          "set_ui: 'ui' is refused: not UTF-8 at byte 15 ('{x: 1, note: \"\\xff\\xfe\"}')");
  apex::SaveGraph::Request save;
  save.path = "/tmp/apex_\xff\xfe.yaml";
  const auto saved = call<apex::SaveGraph>("save_graph", save);
  EXPECT_FALSE(saved.success);
  EXPECT_THAT(saved.message, HasSubstr("save_graph: 'path' is refused: not UTF-8 at byte 11"));
  EXPECT_FALSE(std::filesystem::exists(save.path));
  apex::AddNode::Request add;
  add.type = "apex_nodes/Counter", add.name = "c", add.parameters = "{start: 1, note: \"\x01\"}";
  refused(call<apex::AddNode>("add_node", add), before, "add_node: 'parameters' is refused: a control character at byte 19");
  apex::Group::Request g;
  g.nodes = {"count", "\xc0\xaf"}, g.name = "sub";  // in a list
  refused(call<apex::Group>("group", g), before, "group: 'nodes' is refused: not UTF-8");
  u.ui = "{note: \"caf\xc3\xa9 \xe2\x9c\x93\"}";  // UTF-8: taken
  ASSERT_TRUE(call<apex::SetUi>("set_ui", u).success);
  EXPECT_THAT(graphText(), HasSubstr("caf\xc3\xa9"));
}

TEST_F(Services, ControlPausesResumesSteps) {
  apex::Control::Request req;
  req.command = "pause";
  EXPECT_TRUE(call<apex::Control>("control", req).paused);
  req.command = "step";
  EXPECT_TRUE(call<apex::Control>("control", req).success);
  req.command = "resume";
  EXPECT_FALSE(call<apex::Control>("control", req).paused);
  req.command = "step";
  EXPECT_THAT(call<apex::Control>("control", req).message, HasSubstr("pause it first"));
  req.command = "jump";
  EXPECT_THAT(call<apex::Control>("control", req).message, HasSubstr("unknown command 'jump'"));
}

TEST_F(Services, InspectPublishesAPortAndGraphIsLatched) {
  ros::NodeHandle nh;
  ASSERT_TRUE(addNode("apex_nodes/Clock", "clock", "{rate: 200}").success);
  apex::Inspect::Request req;
  req.node = "clock", req.port = "count", req.enable = true;
  auto res = call<apex::Inspect>("inspect", req);
  ASSERT_TRUE(res.success) << res.message;
  EXPECT_EQ(res.topic, "/apex/inspect/clock/count");
  EXPECT_EQ(res.message_type, "std_msgs/Int32");
  std_msgs::Int32 value;
  EXPECT_TRUE(receive(nh, res.topic, value));
  req.port = "nope";
  EXPECT_THAT(call<apex::Inspect>("inspect", req).message, HasSubstr("no output or interactive parameter 'nope'"));
  req.enable = false;  // stopping what was never started: fine, but not for a node or port that is not there
  EXPECT_TRUE(call<apex::Inspect>("inspect", req).message.find("'nope'") != std::string::npos);
  req.node = "ghost", req.port = "count";
  auto ghost = call<apex::Inspect>("inspect", req);
  EXPECT_FALSE(ghost.success);
  EXPECT_EQ(ghost.message, "no node named 'ghost'");
  req.node = "clock";
  EXPECT_TRUE(call<apex::Inspect>("inspect", req).success);

  apex::GraphState state;
  ASSERT_TRUE(receive(nh, "/apex/graph", state));  // latched: arrives without a change
  EXPECT_EQ(state.nodes.size(), 1u);
  double rate = 0;  // mirrored on the parameter server after ~graph went out (both off the call)
  ASSERT_TRUE(waitUntil([&] { return ros::param::get("/apex/nodes/clock/rate", rate); }, 10));
  EXPECT_EQ(rate, 200.0);
}

/** A burst of edits is published together: each edit's call answers at once, ~graph follows on a
 *  thread of its own, and the last edit is always in what goes out. Before, every call described,
 *  converted and published the whole graph before it answered (~50 ms an edit at 5,000 nodes). */
TEST_F(Services, ABurstOfEditsGoesOutOnGraphTogetherAndTheLastOneAlways) {
  ros::NodeHandle nh;
  const std::string big = tempPath("big.yaml");
  std::string text = "apex_graph: 2\nnodes:\n";
  for (int i = 0; i < 1000; ++i) text += "  - {name: r" + std::to_string(i) + ", type: apex_nodes/Relay}\n";
  writeFile(big, text);
  apex::LoadGraph::Request load;
  load.path = big;
  ASSERT_TRUE(call<apex::LoadGraph>("load_graph", load).success);
  std::mutex m;
  std::size_t nodes = 0;
  long messages = 0;
  auto sub = nh.subscribe<apex::GraphState>("/apex/graph", 100, [&](const apex::GraphState::ConstPtr& g) {
    std::lock_guard<std::mutex> l(m);
    nodes = g->nodes.size(), ++messages;
  });
  const auto seen = [&](std::size_t n) {
    std::lock_guard<std::mutex> l(m);
    return nodes == n;
  };
  ASSERT_TRUE(waitUntil([&] { return seen(1000); }, 30));
  const long before = messages;
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(addNode("apex_nodes/Relay", "burst_" + std::to_string(i)).success);
  ASSERT_TRUE(waitUntil([&] { return seen(1050); }, 30)) << "the last edit never went out";
  std::lock_guard<std::mutex> l(m);
  EXPECT_LT(messages - before, 25) << "a ~graph for every edit";
}

/** Every number an inspected port sends arrives, however fast they come: a script scoring each
 *  frame of a pass (python/apex/tuning.py) counts them. With a queue of 1 a burst lost some (79
 *  of 5,000 beside two busy loops) and the script waited for them forever. */
TEST_F(Services, AnInspectedNumberLosesNoneOfABurst) {
  ros::NodeHandle nh;
  ASSERT_TRUE(addNode("apex_nodes/Clock", "burst", "{rate: 1000}").success);
  apex::Inspect::Request req;
  req.node = "burst", req.port = "count", req.enable = true;
  auto res = call<apex::Inspect>("inspect", req);
  ASSERT_TRUE(res.success) << res.message;
  std::mutex m;
  std::vector<int> got;
  auto sub = nh.subscribe<std_msgs::Int32>(res.topic, 100000, [&](const std_msgs::Int32::ConstPtr& v) {
    std::lock_guard<std::mutex> l(m);
    got.push_back(v->data);
  });
  const auto size = [&] {
    std::lock_guard<std::mutex> l(m);
    return got.size();
  };
  const auto until = ros::WallTime::now() + ros::WallDuration(60);
  while (size() < 3000 && ros::WallTime::now() < until) ros::WallDuration(0.01).sleep();
  std::lock_guard<std::mutex> l(m);
  ASSERT_GE(got.size(), 3000u);
  int gaps = 0;
  for (std::size_t i = 1; i < got.size(); ++i) gaps += got[i] != got[i - 1] + 1;
  EXPECT_EQ(gaps, 0) << "of " << got.size() << " counts";
}

TEST_F(Services, SubgraphsAreAddressedByPathByEveryService) {
  ros::NodeHandle nh;
  const std::string part = tempPath("ticker.yaml"), main = tempPath("main.yaml");
  writeFile(part,
            "apex_graph: 2\n"
            "exports:\n"
            "  - {output: time, from: scale/out}\n"
            "  - {parameter: rate, to: clock/rate}\n"
            "  - {parameter: factor, to: scale/factor}\n"
            "nodes:\n"
            "  - {name: clock, type: apex_nodes/Clock, parameters: {rate: 100}}\n"
            "  - {name: scale, type: apex_nodes/Scale}\n"
            "connections:\n"
            "  - {from: clock/time, to: scale/in}\n");
  const std::string ref = part.substr(part.rfind('/') + 1);  // relative to the file naming it
  writeFile(main, "apex_graph: 2\nnodes:\n  - {name: ticks, subgraph: " + ref +
                      ", parameters: {factor: 2.0}}\n  - {name: sink, type: apex_nodes/Relay}\n"
                      "connections:\n  - {from: ticks/time, to: sink/in}\n");
  apex::LoadGraph::Request load;
  load.path = main;
  auto loaded = call<apex::LoadGraph>("load_graph", load);
  ASSERT_TRUE(loaded.success) << loaded.message;

  // parameters: the inner one by its path, the exported one by the subgraph's name
  apex::SetParameter::Request set;
  set.node = "ticks/clock", set.parameter = "rate", set.value = "50";
  auto inner = call<apex::SetParameter>("set_parameter", set);
  EXPECT_TRUE(inner.success) << inner.message;
  set.node = "ticks", set.parameter = "rate", set.value = "40";
  auto outer = call<apex::SetParameter>("set_parameter", set);
  EXPECT_TRUE(outer.success) << outer.message;
  EXPECT_EQ(outer.value, "40.0");
  set.parameter = "gain";
  EXPECT_THAT(call<apex::SetParameter>("set_parameter", set).message, HasSubstr("exports no parameter 'gain'"));

  // ~graph: the subgraph node with its file, its inner nodes by path, the exports as links
  auto graph = call<apex::GetGraph>("get_graph");
  const apex::NodeInfo* sub = nullptr;
  bool clock = false, exported = false;
  for (const auto& n : graph.graph.nodes) {
    if (n.name == "ticks") sub = &n;
    clock = clock || n.name == "ticks/clock";
  }
  for (const auto& c : graph.graph.connections)
    exported = exported || (c.kind == "export" && c.from_node == "ticks/scale" && c.to_node == "ticks" && c.to_port == "time");
  ASSERT_TRUE(sub);
  EXPECT_EQ(sub->type, "subgraph");
  EXPECT_EQ(sub->subgraph, ref);
  EXPECT_TRUE(clock);
  EXPECT_TRUE(exported);
  EXPECT_THAT(graph.yaml, HasSubstr("subgraph: " + ref));

  // ~status and inspect, through the boundary
  EXPECT_TRUE(keepsFiring(nh, "ticks/clock"));
  apex::Inspect::Request inspect;
  inspect.node = "ticks", inspect.port = "time", inspect.enable = true;
  auto tapped = call<apex::Inspect>("inspect", inspect);
  ASSERT_TRUE(tapped.success) << tapped.message;
  std_msgs::Float64 time;
  EXPECT_TRUE(receive(nh, tapped.topic, time));

  // connections by inner names; a subgraph added from its file; removed with its nodes
  EXPECT_TRUE(connectPorts("disconnect", "ticks", "time", "sink", "in").success);
  auto across = connectPorts("connect", "ticks/clock", "count", "sink", "in");
  EXPECT_TRUE(across.success) << across.message;
  auto added = addNode(part, "");
  ASSERT_TRUE(added.success) << added.message;
  EXPECT_EQ(added.node.subgraph, part);
  // group and ungroup: one call each, names follow
  apex::Group::Request group;
  group.nodes = {"ticks", "sink"}, group.name = "both";
  auto grouped = call<apex::Group>("group", group);
  ASSERT_TRUE(grouped.success) << grouped.message;
  EXPECT_TRUE(keepsFiring(nh, "both/ticks/clock"));
  apex::Ungroup::Request ungroup;
  ungroup.name = "both";
  auto ungrouped = call<apex::Ungroup>("ungroup", ungroup);
  ASSERT_TRUE(ungrouped.success) << ungrouped.message;
  ungroup.name = "sink";
  EXPECT_THAT(call<apex::Ungroup>("ungroup", ungroup).message, HasSubstr("not a subgraph"));
  // rename: an inner node in its place, the subgraph with all inside it; data goes on
  apex::RenameNode::Request rename;
  rename.name = "ticks/clock", rename.new_name = "timer";
  auto renamed = call<apex::RenameNode>("rename_node", rename);
  ASSERT_TRUE(renamed.success) << renamed.message;
  EXPECT_EQ(renamed.path, "ticks/timer");
  rename.name = "ticks", rename.new_name = "ticker";
  ASSERT_TRUE(call<apex::RenameNode>("rename_node", rename).success);
  EXPECT_TRUE(keepsFiring(nh, "ticker/timer"));
  EXPECT_THAT(call<apex::GetGraph>("get_graph").yaml, HasSubstr("{from: ticker/timer/count, to: sink/in}"));
  rename.name = "sink", rename.new_name = "ticker";
  EXPECT_THAT(call<apex::RenameNode>("rename_node", rename).message, HasSubstr("a node named 'ticker' already exists"));
  rename.name = "ticker", rename.new_name = "ticks";
  ASSERT_TRUE(call<apex::RenameNode>("rename_node", rename).success);
  apex::RemoveNode::Request remove;
  remove.name = "ticks";
  EXPECT_TRUE(call<apex::RemoveNode>("remove_node", remove).success);
  graph = call<apex::GetGraph>("get_graph");
  for (const auto& n : graph.graph.nodes) EXPECT_NE(n.name.rfind("ticks", 0), 0u) << n.name;
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_ros_services");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
