// The panel's model without a display: graph state from ~graph messages, what
// may connect, positions, and edits with their undo and redo as service calls.
#include <gmock/gmock.h>

#include "apex_rviz_plugin/graph_model.hpp"
#include "graph_model_fixture.hpp"

using namespace apex_rviz_plugin;
using namespace graph_model_fixture;
using ::testing::HasSubstr;

namespace {

TEST(GraphModel, TakesOnlyNewerRevisions) {
  GraphModel m;
  EXPECT_TRUE(m.update(graph(5)));
  auto older = graph(4);
  older.nodes.clear();
  EXPECT_FALSE(m.update(older));
  EXPECT_EQ(m.graph().nodes.size(), 3u);
  EXPECT_TRUE(m.update(graph(6)));
}

TEST(GraphModel, SaysWhyAConnectionCannotBeMadeWithTheRuntimesRules) {
  GraphModel m;
  m.update(graph(1));
  EXPECT_THAT(m.whyNot("clock", "time", "count", "in"), HasSubstr("is already connected (from relay)"));
  EXPECT_THAT(m.whyNot("clock", "processed", "relay", "in"), HasSubstr("a trigger connects only to slots"));
  EXPECT_THAT(m.whyNot("relay", "in", "count", "in"), HasSubstr("'in' is an input of node 'relay'"));
  EXPECT_THAT(m.whyNot("ghost", "out", "count", "in"), HasSubstr("no node named 'ghost'"));
  EXPECT_THAT(m.whyNot("clock", "processed", "count", "reset"), HasSubstr("they are already connected"));
  auto g = graph(2);
  g.connections.erase(g.connections.begin() + 1);  // relay -> count
  g.connections.pop_back();  // clock/processed -> count/reset
  m.update(g);
  EXPECT_EQ(m.whyNot("clock", "time", "count", "in"), "");  // any input takes a double
  EXPECT_EQ(m.whyNot("clock", "processed", "count", "reset"), "");
  g = graph(3);
  g.connections.erase(g.connections.begin());  // clock -> relay: relay/in is free, relay feeds count
  m.update(g);
  EXPECT_THAT(m.whyNot("count", "count", "relay", "in"), HasSubstr("it would close a cycle (relay already feeds count)"));
}

TEST(GraphModel, PositionsComeFromUiMetadata) {
  GraphModel m;
  m.update(graph(1));
  EXPECT_EQ(m.position("clock"), std::make_pair(10.0, 20.0));
  EXPECT_EQ(m.position("relay"), std::make_pair(0.0, 0.0));
  auto move = m.move("clock", 100, 50);
  ASSERT_TRUE(move);
  EXPECT_EQ(std::get<apex::SetUi::Request>(move->apply[0].request).ui, "{x: 100, y: 50}");
  EXPECT_EQ(std::get<apex::SetUi::Request>(move->revert[0].request).ui, "{x: 10, y: 20}");
}

TEST(GraphModel, AUiEditTheRuntimeTookIsTheBaseOfTheNextBeforeTheGraphShowsIt) {
  // A pin, then a collapse before the ~graph that shows the pin came: the collapse must keep the
  // pin (CI: the panel's compact box test lost it; the collapse wrote the ui the ~graph had).
  GraphModel m;
  m.update(graph(1));
  const auto pin = m.setPinned("clock", "rate", true);
  ASSERT_TRUE(pin);
  m.took(pin->apply);  // the runtime answered: done
  const auto collapse = m.setExpanded("clock", false);
  ASSERT_TRUE(collapse);
  const std::string ui = std::get<apex::SetUi::Request>(collapse->apply[0].request).ui;
  EXPECT_THAT(ui, HasSubstr("pinned: [rate]"));
  EXPECT_THAT(ui, HasSubstr("expanded: false"));
  EXPECT_THAT(std::get<apex::SetUi::Request>(collapse->revert[0].request).ui, HasSubstr("pinned: [rate]"))
      << "undoing the collapse keeps the pin too";
  EXPECT_FALSE(m.update(graph(1))) << "the graph's revision is unchanged: the ~graph after the edit is still taken";
  EXPECT_TRUE(m.update(graph(2)));
}

TEST(GraphModel, ArrangingIsUndoneToWhereThePanelShowedTheBoxes) {
  // Tidy right after a drag: the runtime's graph may not show the drag yet; Undo puts the box
  // back where the user dropped it, not where it was before (CI: the panel's Tidy test).
  GraphModel m;
  m.update(graph(1));
  auto tidy = m.arrange({{"clock", {300, 0}}, {"relay", {400, 0}}}, "Tidy", {{"clock", {55, 66}}});
  ASSERT_TRUE(tidy);
  ASSERT_EQ(tidy->revert.size(), 2u);
  EXPECT_EQ(std::get<apex::SetUi::Request>(tidy->revert[0].request).ui, "{x: 55, y: 66}") << "where the panel showed it";
  EXPECT_EQ(std::get<apex::SetUi::Request>(tidy->revert[1].request).ui, "{x: 0, y: 0}") << "where the graph has it";
  EXPECT_EQ(std::get<apex::SetUi::Request>(tidy->apply[0].request).ui, "{x: 300, y: 0}");
}

TEST(GraphModel, RemovingANodeIsUndoneWithItsSettingsAndConnections) {
  GraphModel m;
  m.update(graph(1));
  auto e = m.removeNode("relay");
  ASSERT_TRUE(e);
  ASSERT_EQ(e->apply.size(), 1u);
  EXPECT_EQ(e->apply[0].service, "remove_node");
  std::vector<std::string> services;
  for (const auto& c : e->revert) services.push_back(c.service);
  EXPECT_THAT(services, ::testing::ElementsAre("add_node", "set_enabled", "connect", "connect"));
  const auto& add = std::get<apex::AddNode::Request>(e->revert[0].request);
  EXPECT_EQ(add.type, "apex_nodes/Relay");
  EXPECT_EQ(add.thread_group, "vision");
  auto clock = m.removeNode("clock");
  ASSERT_TRUE(clock);
  EXPECT_EQ(std::get<apex::AddNode::Request>(clock->revert[0].request).parameters, "{rate: 20.0}");
  EXPECT_TRUE(std::get<apex::SetInteractive::Request>(clock->revert[1].request).interactive);
  EXPECT_FALSE(m.removeNode("ghost"));
}

TEST(GraphModel, ARestartedRuntimeIsTakenAfterReset) {
  GraphModel m;
  m.update(graph(40));
  EXPECT_FALSE(m.update(graph(2)));  // a new runtime process counts from the start again
  m.reset();
  EXPECT_FALSE(m.hasGraph());
  EXPECT_TRUE(m.update(graph(2)));
  EXPECT_EQ(m.graph().revision, 2u);
}

TEST(GraphModel, FreshNamesFollowTheTypeAndAreUnused) {
  GraphModel m;
  m.update(graph(1));
  EXPECT_EQ(m.freshName("apex_nodes/GaussianBlur"), "gaussian_blur_1");
  EXPECT_EQ(m.freshName("my_nodes/HSVFilter"), "hsv_filter_1");  // the runtime's rule (was h_s_v_filter here)
  auto g = graph(2);
  g.nodes[0].name = "clock_1";
  m.update(g);
  EXPECT_EQ(m.freshName("apex_nodes/Clock"), "clock_2");
  EXPECT_EQ(m.freshName("apex_nodes/Clock", "", {"clock_2"}), "clock_3");  // sent a moment ago, not shown yet
  EXPECT_EQ(m.freshName("apex_nodes/Clock", "sub"), "clock_1");  // inside a subgraph: its own names
  EXPECT_EQ(m.freshName("apex_nodes/Clock", "sub", {"sub/clock_1"}), "clock_2");
}

TEST(GraphModel, DuplicateCopiesNodesWithTheirSettingsAndTheConnectionsAmongThem) {
  GraphModel m;
  m.update(graph(1));
  auto one = m.duplicate({"relay"}, 40, 40);
  ASSERT_TRUE(one.edit) << one.error;
  EXPECT_EQ(one.names, (std::vector<std::string>{"relay_1"}));
  EXPECT_EQ(one.edit->label, "Duplicate relay as relay_1");
  const auto& add = std::get<apex::AddNode::Request>(one.edit->apply[0].request);
  EXPECT_EQ(add.type, "apex_nodes/Relay");
  EXPECT_EQ(add.thread_group, "vision");
  EXPECT_EQ(one.edit->apply[1].service, "set_enabled");  // it was disabled: so is the copy
  EXPECT_EQ(std::get<apex::SetUi::Request>(one.edit->apply[2].request).ui, "{x: 40, y: 40}");
  ASSERT_EQ(one.edit->revert.size(), 1u);
  EXPECT_EQ(one.edit->revert[0].service, "remove_node");

  // two connected nodes: the copies are connected the same way, not to the originals
  auto two = m.duplicate({"clock", "count"}, 40, 40);
  ASSERT_TRUE(two.edit) << two.error;
  EXPECT_EQ(two.names, (std::vector<std::string>{"clock_1", "count_1"}));
  std::vector<std::string> links;
  for (const auto& c : two.edit->apply)
    if (c.service == "connect") {
      const auto& r = std::get<apex::Connect::Request>(c.request);
      links.push_back(r.from_node + "/" + r.from_port + " " + r.to_node + "/" + r.to_port);
    }
  EXPECT_EQ(links, (std::vector<std::string>{"clock_1/processed count_1/reset"}));
  bool rate_ports = false;  // the copy's parameter keeps its ports
  for (const auto& c : two.edit->apply)
    rate_ports =
        rate_ports || (c.service == "set_interactive" && std::get<apex::SetInteractive::Request>(c.request).node == "clock_1");
  EXPECT_TRUE(rate_ports);
  EXPECT_EQ(std::get<apex::SetUi::Request>(two.edit->apply[2].request).ui, "{x: 50, y: 60}");
  EXPECT_FALSE(m.duplicate({"nobody"}, 0, 0).edit);
}

TEST(GraphModel, CopiedTextIsAGraphFileThatPastesIntoAnotherGraphUnderFreeNames) {
  GraphModel m;
  m.update(graph(1));
  const std::string text = m.copy({"clock", "relay"});
  EXPECT_THAT(text, HasSubstr("apex_graph: 2"));
  EXPECT_THAT(text, HasSubstr("{from: clock/count, to: relay/in}"));
  EXPECT_EQ(text.find("count/"), std::string::npos) << text;  // not copied: its connections neither

  GraphModel other;  // another graph: the names are free there, so they stay
  apex::GraphState empty;
  empty.revision = 1;
  other.update(empty);
  auto p = other.paste(text, "", 100, 200);
  ASSERT_TRUE(p.edit) << p.error;
  EXPECT_EQ(p.names, (std::vector<std::string>{"clock", "relay"}));
  EXPECT_EQ(std::get<apex::AddNode::Request>(p.edit->apply[0].request).parameters, "{rate: 20.0}");
  // inside a subgraph level, and pasted again where the names are taken
  auto in = m.paste(text, "sub", 0, 0);
  EXPECT_EQ(in.names, (std::vector<std::string>{"sub/clock", "sub/relay"}));
  auto again = m.paste(text, "", 0, 0);
  EXPECT_EQ(again.names, (std::vector<std::string>{"clock_1", "relay_1"}));
  EXPECT_EQ(again.edit->revert.size(), 2u);  // undone by removing them

  EXPECT_THAT(m.paste("hello", "", 0, 0).error, HasSubstr("the clipboard holds no APEX nodes"));
  EXPECT_THAT(m.paste("apex_graph: 2\nnodes:\n  - {name: s, subgraph: {nodes: []}}\n", "", 0, 0).error,
              HasSubstr("'s' is an inline subgraph"));
}

TEST(GraphModel, RenameIsOneEditUndoneByRenamingBack) {
  GraphModel m;
  m.update(graph(1));
  auto e = m.rename("relay", "pass");
  ASSERT_TRUE(e);
  const auto& to = std::get<apex::RenameNode::Request>(e->apply[0].request);
  EXPECT_EQ(to.name, "relay");
  EXPECT_EQ(to.new_name, "pass");
  const auto& back = std::get<apex::RenameNode::Request>(e->revert[0].request);
  EXPECT_EQ(back.name, "pass");
  EXPECT_EQ(back.new_name, "relay");
  EXPECT_FALSE(m.rename("nobody", "x"));
}

TEST(GraphModel, ResetToDefaultSetsOneOrAllParametersAndIsUndoneToTheValuesBefore) {
  GraphModel m;
  auto g = graph(1);
  g.nodes[0].parameters = {param("rate", "20.0"), param("offset", "3"), param("name", "x")};
  g.nodes[0].parameters[0].default_value = "10.0";
  g.nodes[0].parameters[1].default_value = "0";
  g.nodes[0].parameters[2].default_value = "x";
  m.update(g);
  auto one = m.resetToDefault("clock", "rate");
  ASSERT_TRUE(one);
  ASSERT_EQ(one->apply.size(), 1u);
  EXPECT_EQ(std::get<apex::SetParameter::Request>(one->apply[0].request).value, "10.0");
  EXPECT_EQ(std::get<apex::SetParameter::Request>(one->revert[0].request).value, "20.0");
  auto all = m.resetToDefault("clock");
  ASSERT_TRUE(all);
  EXPECT_EQ(all->apply.size(), 2u);  // 'name' is at its default already
  EXPECT_EQ(all->revert.size(), 2u);
  EXPECT_FALSE(m.resetToDefault("clock", "name"));
  EXPECT_FALSE(m.resetToDefault("nobody"));
}

TEST(GraphModel, SeveralParametersOfANodeAreOneEditUndoneInReverse) {
  GraphModel m;
  auto g = graph(1);
  g.nodes[0].parameters = {param("x", "0"), param("y", "0"), param("width", "64")};
  m.update(g);
  auto box = m.setParameters("clock", {{"x", "10"}, {"y", "20"}, {"width", "30"}}, "Start clock on a box");
  ASSERT_TRUE(box);
  EXPECT_EQ(box->label, "Start clock on a box");
  ASSERT_EQ(box->apply.size(), 3u);
  ASSERT_EQ(box->revert.size(), 3u);
  EXPECT_EQ(std::get<apex::SetParameter::Request>(box->apply[0].request).parameter, "x");
  EXPECT_EQ(std::get<apex::SetParameter::Request>(box->apply[2].request).value, "30");
  EXPECT_EQ(std::get<apex::SetParameter::Request>(box->revert[0].request).parameter, "width");
  EXPECT_EQ(std::get<apex::SetParameter::Request>(box->revert[0].request).value, "64");
  EXPECT_EQ(std::get<apex::SetParameter::Request>(box->revert[2].request).value, "0");
  EXPECT_FALSE(m.setParameters("clock", {{"x", "1"}, {"height", "5"}}, "part of a box")) << "all of them or none";
  EXPECT_FALSE(m.setParameters("nobody", {{"x", "1"}}, "no node"));
}

TEST(GraphModel, ALinkOntoAnInputInUseReplacesTheOldOneInOneEdit) {
  GraphModel m;
  m.update(graph(1));
  EXPECT_THAT(m.whyNot("clock", "time", "count", "in"), HasSubstr("already connected"));
  EXPECT_EQ(m.whyNotReplacing("clock", "time", "count", "in"), "");  // the drag may end there
  EXPECT_THAT(m.whyNotReplacing("clock", "processed", "count", "in"), HasSubstr("a trigger connects only to slots"));
  apex::Connection c;
  c.from_node = "clock", c.from_port = "time", c.to_node = "count", c.to_port = "in";
  const Edit e = m.connect(c);
  ASSERT_EQ(e.apply.size(), 2u);
  EXPECT_EQ(e.apply[0].service, "disconnect");
  EXPECT_EQ(std::get<apex::Connect::Request>(e.apply[0].request).from_node, "relay");
  EXPECT_EQ(e.apply[1].service, "connect");
  ASSERT_EQ(e.revert.size(), 2u);
  EXPECT_EQ(e.revert[1].service, "connect");  // the old link back
  EXPECT_EQ(std::get<apex::Connect::Request>(e.revert[1].request).from_node, "relay");
  c.to_port = "reset";  // a slot takes many events: nothing replaced
  c.from_port = "processed";
  EXPECT_EQ(m.connect(c).apply.size(), 1u);
}

TEST(GraphModel, ANodeDroppedOntoALinkIsPutInItInOneEdit) {
  GraphModel m;
  auto g = graph(1);
  apex::NodeInfo scale;
  scale.name = "scale", scale.type = "apex_nodes/Relay", scale.enabled = true;
  scale.ports = {port("in", "input", "any"), port("out", "output", "any")};
  scale.ui = "{x: 1, y: 2}";
  g.nodes.push_back(scale);
  m.update(g);
  const apex::Connection c = g.connections[1];  // relay/out -> count/in
  auto e = m.insert("scale", c, 300, 40);
  ASSERT_TRUE(e);
  std::vector<std::string> calls;
  for (const auto& k : e->apply) {
    if (k.service == "set_ui") {
      calls.push_back("set_ui");
      continue;
    }
    const auto& r = std::get<apex::Connect::Request>(k.request);
    calls.push_back(k.service + " " + r.from_node + "/" + r.from_port + " " + r.to_node + "/" + r.to_port);
  }
  EXPECT_EQ(calls, (std::vector<std::string>{"set_ui", "disconnect relay/out count/in", "connect relay/out scale/in",
                                             "connect scale/out count/in"}));
  EXPECT_EQ(std::get<apex::SetUi::Request>(e->revert.back().request).ui, "{x: 1, y: 2}");
  EXPECT_FALSE(m.insert("relay", g.connections[0], 0, 0));  // connected already: it stays as it is
  EXPECT_FALSE(m.insert("clock", c, 0, 0));  // no input
}

TEST(GraphModel, APresetIsComparedWithTheGraphAndRestoredInOneEdit) {
  GraphModel m;
  auto g = graph(1);
  g.nodes[2].parameters = {param("mode", "'fast'"), param("limits", "[1, 2]")};
  m.update(g);
  const std::string all = m.preset({});
  EXPECT_THAT(all, HasSubstr("apex_preset: 1"));
  EXPECT_THAT(all, HasSubstr("clock: {rate: 20.0}"));
  EXPECT_TRUE(m.compare(all).empty());  // saved now: nothing differs
  const std::string only_count = m.preset({"count"});
  EXPECT_EQ(only_count.find("clock"), std::string::npos) << only_count;

  g.revision = 2;  // then the graph changes
  g.nodes[0].parameters[0].value = "35.5";
  g.nodes[2].parameters[1].value = "[1, 3]";
  m.update(g);
  auto changes = m.compare(all);
  ASSERT_EQ(changes.size(), 2u);
  EXPECT_EQ(changes[0].node + "/" + changes[0].param + ": " + changes[0].now + " -> " + changes[0].then,
            "clock/rate: 35.5 -> 20.0");
  EXPECT_EQ(changes[1].then, "[1, 2]");
  auto e = m.restore(all, "tuned");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->label, "Restore preset tuned");
  ASSERT_EQ(e->apply.size(), 2u);
  EXPECT_EQ(std::get<apex::SetParameter::Request>(e->apply[0].request).value, "20.0");
  EXPECT_EQ(std::get<apex::SetParameter::Request>(e->revert[1].request).value, "35.5");  // undone to now

  std::string error;
  EXPECT_TRUE(m.compare("just: text", &error).empty());
  EXPECT_THAT(error, HasSubstr("not an APEX preset"));
  EXPECT_FALSE(m.restore(m.preset({}), "same"));  // nothing differs: no edit
}

TEST(GraphModel, EnableGroupAndInteractiveEditsAreUndoneToTheOldState) {
  GraphModel m;
  m.update(graph(1));
  auto en = m.setEnabled("relay", true);
  ASSERT_TRUE(en);
  EXPECT_TRUE(std::get<apex::SetEnabled::Request>(en->apply[0].request).enabled);
  EXPECT_FALSE(std::get<apex::SetEnabled::Request>(en->revert[0].request).enabled);
  auto group = m.setThreadGroup("relay", "fast");
  ASSERT_TRUE(group);
  EXPECT_EQ(std::get<apex::SetThreadGroup::Request>(group->apply[0].request).group, "fast");
  EXPECT_EQ(std::get<apex::SetThreadGroup::Request>(group->revert[0].request).group, "vision");
  // hiding a linked parameter's ports drops its connection: undo brings it back
  auto g = graph(2);
  apex::Connection link;
  link.from_node = "count", link.from_port = "count", link.to_node = "clock", link.to_port = "rate";
  g.connections.push_back(link);
  m.update(g);
  auto hide = m.setInteractive("clock", "rate", false);
  ASSERT_TRUE(hide);
  ASSERT_EQ(hide->revert.size(), 2u);
  EXPECT_TRUE(std::get<apex::SetInteractive::Request>(hide->revert[0].request).interactive);
  EXPECT_EQ(hide->revert[1].service, "connect");
  EXPECT_EQ(std::get<apex::Connect::Request>(hide->revert[1].request).to_port, "rate");
  EXPECT_FALSE(m.setInteractive("clock", "nothing", true));
}

TEST(GraphModel, BalancesMovesAreOneEditUndoneToTheGroupsBefore) {
  GraphModel m;
  m.update(graph(1));  // clock in default, relay in vision, count in ""
  auto e = m.setThreadGroups({{"clock", "default"}, {"relay", "stage2"}, {"count", "stage2"}, {"gone", "x"}}, "Balance");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->label, "Balance");
  ASSERT_EQ(e->apply.size(), 2u);  // the clock is in its group already; "gone" is not in the graph
  EXPECT_EQ(std::get<apex::SetThreadGroup::Request>(e->apply[0].request).node, "relay");
  EXPECT_EQ(std::get<apex::SetThreadGroup::Request>(e->apply[1].request).group, "stage2");
  ASSERT_EQ(e->revert.size(), 2u);  // the last moved goes back first
  EXPECT_EQ(std::get<apex::SetThreadGroup::Request>(e->revert[0].request).node, "count");
  EXPECT_EQ(std::get<apex::SetThreadGroup::Request>(e->revert[1].request).node, "relay");
  EXPECT_EQ(std::get<apex::SetThreadGroup::Request>(e->revert[1].request).group, "vision");
  EXPECT_FALSE(m.setThreadGroups({{"clock", "default"}}, "Balance"));  // nothing to move: no edit
}

TEST(GraphModel, UndoOfAParameterThatShapesPortsConnectsWhatItDropped) {
  auto g = graph(1);
  g.nodes[0].parameters.push_back(param("outputs", "2"));
  g.nodes[0].parameters.back().shapes_ports = true;
  GraphModel m;
  m.update(g);
  auto plain = m.setParameter("clock", "rate", "5");
  ASSERT_TRUE(plain);
  EXPECT_EQ(plain->revert.size(), 1u);  // a value only
  auto shaping = m.setParameter("clock", "outputs", "1");
  ASSERT_TRUE(shaping);
  ASSERT_EQ(shaping->revert.size(), 3u);  // the value, then clock's two connections, if missing
  EXPECT_EQ(std::get<apex::SetParameter::Request>(shaping->revert[0].request).value, "2");
  for (std::size_t i = 1; i < 3; ++i) {
    EXPECT_EQ(shaping->revert[i].service, "connect");
    EXPECT_TRUE(shaping->revert[i].if_missing);
    EXPECT_EQ(std::get<apex::Connect::Request>(shaping->revert[i].request).from_node, "clock");
  }
}

TEST(GraphModel, GroupingIsOneEditUndoneByUngroupingAndTheOtherWayRound) {
  GraphModel m;
  ASSERT_TRUE(m.update(graph(1)));
  auto grouped = m.group({"relay", "count"});
  ASSERT_TRUE(grouped);
  ASSERT_EQ(grouped->apply.size(), 1u);
  const auto& g = std::get<apex::Group::Request>(grouped->apply[0].request);
  EXPECT_EQ(grouped->apply[0].service, "group");
  EXPECT_EQ(g.name, "subgraph_1");
  EXPECT_EQ(g.nodes, (std::vector<std::string>{"relay", "count"}));
  ASSERT_EQ(grouped->revert.size(), 1u);
  EXPECT_EQ(std::get<apex::Ungroup::Request>(grouped->revert[0].request).name, "subgraph_1");

  // as the runtime then describes it: the subgraph and its nodes by path
  auto state = graph(2);
  state.nodes[1].name = "subgraph_1/relay", state.nodes[2].name = "subgraph_1/count";
  apex::NodeInfo sub;
  sub.name = "subgraph_1", sub.type = "subgraph", sub.subgraph = "inline";
  state.nodes.push_back(sub);
  ASSERT_TRUE(m.update(state));
  EXPECT_FALSE(m.ungroup("clock")) << "not a subgraph";
  auto ungrouped = m.ungroup("subgraph_1");
  ASSERT_TRUE(ungrouped);
  EXPECT_EQ(std::get<apex::Ungroup::Request>(ungrouped->apply[0].request).name, "subgraph_1");
  const auto& again = std::get<apex::Group::Request>(ungrouped->revert[0].request);
  EXPECT_EQ(again.name, "subgraph_1");
  EXPECT_EQ(again.nodes, (std::vector<std::string>{"relay", "count"}));
  EXPECT_EQ(std::get<apex::Group::Request>(m.group({"clock"})->apply[0].request).name, "subgraph_2");
}

TEST(EditHistory, UndoRedoAndANewEditClearsRedo) {
  GraphModel m;
  m.update(graph(1));
  EditHistory h;
  EXPECT_FALSE(h.canUndo());
  h.done(*m.setParameter("clock", "rate", "50"));
  h.done(m.addNode("apex_nodes/Relay", "relay_2", 5, 5));
  EXPECT_EQ(h.undoLabel(), "Add relay_2");
  auto undo = h.undo();
  ASSERT_EQ(undo.size(), 1u);
  EXPECT_EQ(undo[0].service, "remove_node");
  undo = h.undo();
  EXPECT_EQ(std::get<apex::SetParameter::Request>(undo[0].request).value, "20.0");  // back to what it was
  EXPECT_FALSE(h.canUndo());
  auto redo = h.redo();
  EXPECT_EQ(std::get<apex::SetParameter::Request>(redo[0].request).value, "50");
  h.done(m.connect(graph(1).connections[0]));
  EXPECT_FALSE(h.canRedo());
  EXPECT_FALSE(m.setParameter("clock", "speed", "1"));
}

TEST(EditHistory, OneSliderDragIsOneUndoStepAndTheNextDragAnother) {
  GraphModel m;
  m.update(graph(1));
  EditHistory h;
  for (const char* v : {"21", "22", "23"}) h.done(*m.setParameter("clock", "rate", v, true));  // dragging
  h.done(*m.setParameter("clock", "rate", "24"));  // released
  h.done(*m.setParameter("clock", "rate", "30", true));  // another drag
  h.done(*m.setParameter("clock", "rate", "31"));
  auto undo = h.undo();
  EXPECT_EQ(std::get<apex::SetParameter::Request>(undo[0].request).value, "20.0");  // the model still says 20
  undo = h.undo();
  EXPECT_EQ(std::get<apex::SetParameter::Request>(undo[0].request).value, "20.0");
  EXPECT_FALSE(h.canUndo());  // two drags, two steps
  EXPECT_EQ(std::get<apex::SetParameter::Request>(h.redo()[0].request).value, "24");  // the drag's last value

  // typed values are one step each; another parameter's drag does not join this one's
  h.clear();
  h.done(*m.setParameter("clock", "rate", "40"));
  h.done(*m.setParameter("clock", "rate", "41"));
  h.done(*m.setParameter("clock", "rate", "42", true));
  h.done(m.addNode("apex_nodes/Relay", "r", 0, 0));
  h.done(*m.setParameter("clock", "rate", "43", true));
  int steps = 0;
  while (h.canUndo()) h.undo(), ++steps;
  EXPECT_EQ(steps, 5);
}

}  // namespace
