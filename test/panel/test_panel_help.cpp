// Panel tests, continued (same runtime): a node type's documentation in the panel. F1 on a palette
// entry, its menu's Help, a node's Help and F1 in the quick-add box show what docs/nodes.md says
// of the type: its description, ports, and parameters with kind, range, default and description.
#include "panel_test_support.hpp"

#include <QTreeWidget>

#include "apex_rviz_plugin/help_view.hpp"
#include "apex_rviz_plugin/palette.hpp"
#include "apex_rviz_plugin/quick_add.hpp"

namespace panel_test {
namespace {

/** The cells of the table rows of `type`'s section of docs/nodes.md (markup taken off), and its
 *  description line. */
std::vector<std::string> docCells(const std::string& type) {
  std::ifstream in(std::filesystem::path(g_graphs).parent_path() / "docs" / "nodes.md");
  EXPECT_TRUE(in) << "no docs/nodes.md beside " << g_graphs;
  std::string line;
  while (std::getline(in, line) && line != "### " + type) {
  }
  std::vector<std::string> cells;
  std::getline(in, line);  // blank
  if (std::getline(in, line)) cells.push_back(line);  // the description
  while (std::getline(in, line) && line.rfind("### ", 0) != 0 && line.rfind("## ", 0) != 0) {
    if (line.rfind("| `", 0) != 0) continue;  // a table row of a port or parameter
    QString row = QString::fromStdString(line.substr(2, line.size() - 4));
    row.remove('`').remove('*').replace("\\|", "\x01");
    for (QString cell : row.split(" | ")) {
      cell = cell.replace("\x01", "|").trimmed();
      if (!cell.isEmpty() && cell != "yes") cells.push_back(cell.toStdString());
    }
  }
  return cells;
}

/** The cells of docs/nodes.md's section of `type` that the help window does not show; "" if none. */
std::string missing(const HelpView& help, const std::string& type) {
  const QString text = help.text().remove('`').remove('*');  // as the cells are compared: without Markdown's marks
  std::string out;
  for (const auto& cell : docCells(type))
    if (!text.contains(QString::fromStdString(cell))) out += "'" + cell + "' ";
  return out;
}

TEST_F(PanelWidgetTest, TheHelpOfATypeShowsWhatDocsNodesMdSaysWithTheParametersRanges) {
  const std::string type = "apex_nodes/HoughCircles";
  ASSERT_GT(docCells(type).size(), 20u) << "its description, its ports and seven parameters";
  // F1 on the palette's entry
  search->setFocus();
  search->selectAll();
  QTest::keyClicks(search, "houghcircles");
  auto* tree = panel.editor()->findChild<QTreeWidget*>("palette");
  ASSERT_TRUE(tree && tree->currentItem());
  tree->setFocus();
  QTest::keyClick(tree, Qt::Key_F1);
  HelpView* help = panel.editor()->help();
  ASSERT_TRUE(help && help->isVisible());
  EXPECT_EQ(help->typeId().toStdString(), type);
  EXPECT_EQ(missing(*help, type), "");
  for (const char* range : {"[1.0, 8.0] step 0.1", "[0, 10000]", "[-1, 10000]", "gradient, gradient_alt"})
    EXPECT_TRUE(help->text().contains(range)) << range << " not in\n" << help->text().toStdString();
  EXPECT_TRUE(help->text().contains("detection")) << "its category";
  help->close();

  // Help in the entry's menu, and F1 in the quick-add box, for another type
  auto* palette = panel.editor()->findChild<Palette*>();
  ASSERT_TRUE(palette);
  QMenu menu;
  palette->fillMenu(menu, "apex_nodes/Clock");
  ASSERT_TRUE(action(menu, "Help"));
  action(menu, "Help")->trigger();
  ASSERT_TRUE(help->isVisible());
  EXPECT_EQ(help->typeId().toStdString(), "apex_nodes/Clock");
  EXPECT_EQ(missing(*help, "apex_nodes/Clock"), "");
  EXPECT_TRUE(help->text().contains("[0.01, 1000.0] step 0.01")) << help->text().toStdString();
  panel.editor()->openQuickAdd(QPointF(0, 0));
  QuickAdd* quick = panel.editor()->quickAdd();
  ASSERT_TRUE(quick && quick->isVisible());
  QTest::keyClicks(quick->search(), "houghlines");
  QTest::keyClick(quick->search(), Qt::Key_F1);
  EXPECT_EQ(help->typeId().toStdString(), "apex_nodes/HoughLines");
  QTest::keyClick(quick->search(), Qt::Key_Escape);

  // a node's menu: Help shows its type's, and the open help follows the node selected
  ASSERT_TRUE(addNode(type, "help_circles", ""));
  ASSERT_TRUE(addNode("apex_nodes/Counter", "help_counter", ""));
  GraphScene* scene = panel.editor()->scene();
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("help_circles") && scene->node("help_counter"); }, kWaitMs));
  QMenu node_menu;
  panel.editor()->fillNodeMenu(node_menu, "help_circles");
  ASSERT_TRUE(action(node_menu, "Help"));
  action(node_menu, "Help")->trigger();
  EXPECT_EQ(help->typeId().toStdString(), type);
  EXPECT_TRUE(help->windowTitle().contains("help_circles")) << help->windowTitle().toStdString();
  EXPECT_EQ(missing(*help, type), "");
  scene->clearSelection();
  scene->node("help_counter")->setSelected(true);
  EXPECT_EQ(help->typeId().toStdString(), "apex_nodes/Counter");
  EXPECT_EQ(missing(*help, "apex_nodes/Counter"), "");
  help->close();
}

}  // namespace
}  // namespace panel_test
