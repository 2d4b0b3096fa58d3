// What a node's box shows (BoxView): compact by default, expanded on demand, pinned
// parameters; the choice kept in the node's ui metadata beside its position.
#include <gmock/gmock.h>

#include "apex_rviz_plugin/box_view.hpp"
#include "apex_rviz_plugin/graph_model.hpp"

using namespace apex_rviz_plugin;
using ::testing::ElementsAre;

namespace {

apex::ParamInfo param(const std::string& name, const std::string& value, const std::string& def,
                      const std::string& kind = "double") {
  apex::ParamInfo p;
  p.name = name, p.kind = kind, p.value = value, p.default_value = def;
  return p;
}

/** A player as a fresh BagReader is: a file to choose, topics, the older image_topic (legacy). */
apex::NodeInfo player(const std::string& ui = "{x: 10, y: 20}") {
  apex::NodeInfo n;
  n.name = "bag", n.type = "apex_nodes/BagReader", n.ui = ui;
  n.parameters = {param("file", "''", "''", "path"),
                  param("topics", "[]", "[]", "text list"),
                  param("image_topic", "/camera/image_raw", "/camera/image_raw", "string"),
                  param("rate", "1", "1"),
                  param("loop", "false", "false", "bool"),
                  param("start", "0", "0")};
  n.parameters[2].legacy = true;
  return n;
}

TEST(BoxView, ABoxOfManyParametersIsCompactShowingFilesAndWhatWasSet) {
  apex::NodeInfo n = player();
  BoxView v = BoxView::of(n.ui);
  EXPECT_FALSE(v.isExpanded(n));
  EXPECT_THAT(v.shown(n), ElementsAre("file"));  // a file to choose: without it a player plays nothing
  EXPECT_EQ(v.hidden(n), 4u);  // topics, rate, loop, start; the legacy one is not counted
  n.parameters[3].value = "2";  // set away from its default: shown, so the box says what it does
  n.parameters[5].interactive = true;  // with ports: data drives it
  EXPECT_THAT(v.shown(n), ElementsAre("file", "rate", "start"));
}

TEST(BoxView, ExpandedShowsEveryParameterButALegacyOneAtItsDefault) {
  apex::NodeInfo n = player("{x: 10, y: 20, expanded: true}");
  const BoxView v = BoxView::of(n.ui);
  EXPECT_TRUE(v.isExpanded(n));
  EXPECT_THAT(v.shown(n), ElementsAre("file", "topics", "rate", "loop", "start"));
  n.parameters[2].value = "/cam/image";  // an older graph that set it: it shows
  EXPECT_THAT(v.shown(n), ElementsAre("file", "topics", "image_topic", "rate", "loop", "start"));
}

TEST(BoxView, AFewParametersAreAllShownAndPinnedOnesStayInTheCompactBox) {
  apex::NodeInfo few;
  few.parameters = {param("rate", "10", "10"), param("jitter", "0", "0")};
  EXPECT_TRUE(BoxView::of("").isExpanded(few));  // no toggle for two rows
  EXPECT_FALSE(BoxView::collapsible(few));
  apex::NodeInfo n = player("{x: 1, y: 2, pinned: [loop]}");
  BoxView v = BoxView::of(n.ui);
  EXPECT_THAT(v.shown(n), ElementsAre("file", "loop"));
  v.always = {"start"}, v.elsewhere = {"rate"};  // a player's frame slider; its transport bar
  n.parameters[3].value = "2";
  EXPECT_THAT(v.shown(n), ElementsAre("file", "loop", "start"));
}

TEST(BoxView, MetadataIsEditedKeyByKeyKeepingThePositionAndOtherKeys) {
  EXPECT_EQ(withUiKey("{x: 1, y: 2, colour: red}", "expanded", "true"), "{x: 1, y: 2, colour: red, expanded: true}");
  EXPECT_EQ(withPosition("{x: 1, y: 2, expanded: true}", 30.7, 40), "{x: 30, y: 40, expanded: true}");
  EXPECT_EQ(withPosition("", 5, 6), "{x: 5, y: 6}");
  EXPECT_EQ(withPosition("not: [a map", 5, 6), "{x: 5, y: 6}");  // unreadable metadata: replaced
  EXPECT_FALSE(BoxView::of("[1, 2]").expanded);
  EXPECT_FALSE(BoxView::of("{expanded: [1]}").expanded);  // a value of another shape: the default
}

TEST(BoxView, AStampReadsWholeNotInExponentForm) {
  // #48: a stamp on a box read "1.7e+09"
  EXPECT_EQ(scalarText(1700000123.456789), "1700000123.457");
  EXPECT_EQ(scalarText(123456.5), "123456.5");
  EXPECT_EQ(scalarText(200000), "200000");
  EXPECT_EQ(scalarText(12.3456789), "12.3457");
  EXPECT_EQ(scalarText(-0.5), "-0.5");
  EXPECT_EQ(scalarText(1e-7), "1e-07");  // where whole digits would say nothing
  EXPECT_EQ(scalarText(3e20), "3e+20");
}

TEST(BoxView, TheHeaderNamesAThreadGroupOnlyWhenItIsNotTheDefault) {
  // #48: "[default]" on every box read as "defaults"
  EXPECT_EQ(kindLine("apex_nodes/Blur", "default"), "apex_nodes/Blur");
  EXPECT_EQ(kindLine("apex_nodes/Blur", ""), "apex_nodes/Blur");
  EXPECT_EQ(kindLine("apex_nodes/Blur", "vision"), "apex_nodes/Blur  · group vision");
}

TEST(BoxView, APlayerAtTheEndOfAPassThatDoesNotLoopSaysEnded) {
  // #48: the end of a bag showed "frame 794 / 795" and a pause icon, no "ended"
  EXPECT_EQ(playerPlace(794, 794, true, 79.4, true, false), "ended · frame 794 / 795 · 79.40 s");
  EXPECT_EQ(playerPlace(794, 794, true, 79.4, true, true), "frame 794 / 795 · 79.40 s");  // a loop goes on
  EXPECT_EQ(playerPlace(3, 794, true, 0.3, true, false), "frame 3 / 795 · 0.30 s");
  EXPECT_EQ(playerPlace(3, 794, true, 0.3, false, false), "held · frame 3 / 795 · 0.30 s");
  EXPECT_EQ(playerPlace(0, 0, false, 0, true, false), "frame 0 · 0.00 s");  // no bag yet: no end known
}

TEST(GraphModel, ExpandPinAndMoveAreEditsOfTheUiMetadataUndoneToItAsItWas) {
  apex::GraphState g;
  g.revision = 1;
  g.nodes = {player("{x: 10, y: 20}")};
  GraphModel m;
  m.update(g);
  auto ui = [](const Call& c) { return std::get<apex::SetUi::Request>(c.request).ui; };
  auto expand = m.setExpanded("bag", true);
  ASSERT_TRUE(expand);
  EXPECT_EQ(expand->label, "Expand bag");
  EXPECT_EQ(ui(expand->apply[0]), "{x: 10, y: 20, expanded: true}");
  EXPECT_EQ(ui(expand->revert[0]), "{x: 10, y: 20}");
  g.revision = 2;
  g.nodes[0].ui = "{x: 10, y: 20, expanded: true, pinned: [rate]}";
  m.update(g);
  auto pin = m.setPinned("bag", "loop", true);
  ASSERT_TRUE(pin);
  EXPECT_EQ(ui(pin->apply[0]), "{x: 10, y: 20, expanded: true, pinned: [rate, loop]}");
  auto unpin = m.setPinned("bag", "rate", false);
  ASSERT_TRUE(unpin);
  EXPECT_EQ(ui(unpin->apply[0]), "{x: 10, y: 20, expanded: true, pinned: []}");
  EXPECT_FALSE(m.setPinned("bag", "no_such_parameter", true));
  auto move = m.move("bag", 300, 400);  // a move keeps the box as it is
  ASSERT_TRUE(move);
  EXPECT_EQ(ui(move->apply[0]), "{x: 300, y: 400, expanded: true, pinned: [rate]}");
}

}  // namespace
