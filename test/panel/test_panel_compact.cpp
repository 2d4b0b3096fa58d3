// Panel tests, continued (same runtime): compact boxes (issue #35, item 6). A new player is a
// small box (its name, ports, transport bar, file and frame) with a toggle to every parameter;
// the toggle and a pin from a parameter's menu are undoable edits kept in the node's ui
// metadata; the older image_topic and cloud_topic show only in a graph that set them.
#include "panel_test_support.hpp"

#include <QMenu>

namespace panel_test {
namespace {

std::string ui(const std::string& node) {
  const apex::NodeInfo* n = find(runtimeGraph(), node);
  return n ? n->ui : "(no node " + node + ")";
}

TEST_F(PanelWidgetTest, ANewPlayerIsACompactBoxThatExpandsAndKeepsWhatIsPinned) {
  emptyGraph();
  addByKeyboard("apex_nodes/BagReader", "bag_reader_1");
  waitPlaced("bag_reader_1");
  NodeItem* box = panel.editor()->scene()->node("bag_reader_1");
  ASSERT_TRUE(box);
  const double compact_height = box->boundingRect().height();
  // compact: the file to choose and the frame slider under the transport bar; nothing else
  EXPECT_TRUE(box->editor("file") && box->editor("frame") && box->transport());
  for (const char* hidden : {"rate", "loop", "sync_window", "topics", "image_topic", "cloud_topic"})
    EXPECT_FALSE(box->editor(hidden)) << hidden << " is shown in the compact box";
  QToolButton* toggle = box->expandToggle();
  ASSERT_TRUE(toggle);
  EXPECT_TRUE(toggle->text().contains("more parameters")) << toggle->text().toStdString();

  // expanded: every parameter but the two older ones, which a new player does not use
  QTest::mouseClick(toggle, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return box->editor("rate") != nullptr; }, kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_NE(ui("bag_reader_1").find("expanded: true"), std::string::npos) << ui("bag_reader_1");
  EXPECT_TRUE(box->editor("loop") && box->editor("sync_window") && box->editor("topics"));
  EXPECT_FALSE(box->editor("image_topic") || box->editor("cloud_topic"));
  EXPECT_GT(box->boundingRect().height(), compact_height + 100);

  // pinned from the parameter's menu: it stays when the box is compact again
  QMenu menu;
  panel.editor()->fillParamMenu(menu, "bag_reader_1", "loop");
  QAction* pin = menu.findChild<QAction*>("pin");
  ASSERT_TRUE(pin);
  EXPECT_EQ(pin->text().toStdString(), "Pin to the compact box");
  pin->trigger();
  ASSERT_TRUE(QTest::qWaitFor([&] { return ui("bag_reader_1").find("pinned: [loop]") != std::string::npos; }, kWaitMs))
      << ui("bag_reader_1");
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editsPending() == 0 && box->expandToggle(); }, kWaitMs));
  QTest::mouseClick(box->expandToggle(), Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return box->editor("rate") == nullptr; }, kWaitMs)) << ui("bag_reader_1");
  // the collapse kept the pin, even if the ~graph showing the pin came after the pin's answer
  EXPECT_TRUE(QTest::qWaitFor([&] { return ui("bag_reader_1").find("expanded: false") != std::string::npos; }, kWaitMs));
  EXPECT_NE(ui("bag_reader_1").find("pinned: [loop]"), std::string::npos) << ui("bag_reader_1");
  EXPECT_TRUE(QTest::qWaitFor([&] { return box->editor("loop") != nullptr; }, kWaitMs));
  EXPECT_TRUE(box->expandToggle() && box->expandToggle()->text().contains("more parameters"));

  // each was one undo step: the collapse first
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editsPending() == 0; }, kWaitMs));
  QTest::mouseClick(panel.editor()->findChild<QToolButton*>("undo"), Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return box->editor("rate") != nullptr; }, kWaitMs))
      << panel.editor()->message().toStdString();
  // said once the runtime answered the undo, which may come after the ~graph that shows it
  EXPECT_TRUE(QTest::qWaitFor([&] { return panel.editor()->message().startsWith("undid: Collapse bag_reader_1"); }, kWaitMs))
      << panel.editor()->message().toStdString();
}

TEST_F(PanelWidgetTest, AGraphThatSetTheOlderTopicParametersShowsThem) {
  emptyGraph();
  ASSERT_TRUE(
      addNode("apex_nodes/BagReader", "old_bag", "{file: '" + g_bag + "', image_topic: /camera/image_raw, cloud_topic: ''}"));
  waitPlaced("old_bag");
  NodeItem* box = panel.editor()->scene()->node("old_bag");
  ASSERT_TRUE(box);
  EXPECT_TRUE(box->editor("cloud_topic")) << "set away from its default: the box says what the player plays";
  EXPECT_FALSE(box->editor("image_topic"));  // at its default: as in a new player
}

}  // namespace
}  // namespace panel_test
