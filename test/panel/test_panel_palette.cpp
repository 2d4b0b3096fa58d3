// The palette of a library of 100+ node types: headings by category in the runtime's order, search
// over ids, categories and descriptions, tooltips with ports and parameters, adding by keyboard.
#include "panel_test_support.hpp"

#include <QTreeWidget>

#include "apex/core/categories.hpp"

namespace panel_test {
namespace {

TEST_F(PanelWidgetTest, ThePaletteListsTheTypesByCategoryAndSearchFindsThem) {
  apex::ListNodeTypes list;  // what the palette should show: the runtime's types under their categories
  ASSERT_TRUE(ros::service::call("/apex/list_node_types", list));
  std::map<std::string, std::vector<std::string>> by_category;  // short names, in the runtime's order
  const std::string own = "apex_nodes/";
  for (const auto& t : list.response.types)
    if (t.id.compare(0, own.size(), own) == 0) by_category[t.category].push_back(t.id.substr(own.size()));
  ASSERT_TRUE(by_category.count("detection") && by_category.count("flow")) << "the image and generic nodes are loaded";
  auto* tree = panel.editor()->findChild<QTreeWidget*>("palette");
  ASSERT_TRUE(tree);
  std::vector<std::string> headings, expected;  // APEX's categories first, in their order, each with its types
  int listed = 0;
  for (int i = 0; i < tree->topLevelItemCount(); ++i) {
    QTreeWidgetItem* heading = tree->topLevelItem(i);
    headings.push_back(heading->text(0).toStdString());
    listed += heading->childCount();
    if (!by_category.count(headings.back())) continue;
    std::vector<std::string> types;
    for (int j = 0; j < heading->childCount(); ++j) types.push_back(heading->child(j)->text(0).toStdString());
    EXPECT_EQ(types, by_category[headings.back()]) << "under " << headings.back();
  }
  for (const auto& c : apex::nodeCategories())
    if (by_category.count(c)) expected.push_back(c);
  ASSERT_GE(headings.size(), expected.size());
  EXPECT_EQ(std::vector<std::string>(headings.begin(), headings.begin() + expected.size()), expected);
  EXPECT_EQ(listed, static_cast<int>(list.response.types.size())) << "every type once";

  // "hough": HoughCircles and HoughLines under "detection", opened; nothing else shows
  auto shown = [&] {
    std::string out;
    for (int i = 0; i < tree->topLevelItemCount(); ++i) {
      QTreeWidgetItem* heading = tree->topLevelItem(i);
      if (heading->isHidden()) continue;
      out += heading->text(0).toStdString() + (heading->isExpanded() ? ":" : " (closed):");
      for (int j = 0; j < heading->childCount(); ++j)
        if (!heading->child(j)->isHidden()) out += " " + heading->child(j)->text(0).toStdString();
      out += "; ";
    }
    return out;
  };
  search->setFocus();
  search->selectAll();
  QTest::keyClicks(search, "hough");
  EXPECT_TRUE(QTest::qWaitFor([&] { return shown() == "detection: HoughCircles HoughLines; "; }, kWaitMs)) << shown();
  QTreeWidgetItem* circles = tree->currentItem();  // the first match, which Enter would add
  ASSERT_TRUE(circles);
  EXPECT_EQ(circles->text(0), "HoughCircles");
  // its tooltip: the description, every port with its type, every parameter with its kind
  const QString tip = circles->toolTip(0);
  const auto type = std::find_if(list.response.types.begin(), list.response.types.end(),
                                 [](const apex::NodeTypeInfo& t) { return t.id == "apex_nodes/HoughCircles"; });
  ASSERT_NE(type, list.response.types.end());
  auto in_tip = [&](const std::string& text) { return tip.contains(QString::fromStdString(text).toHtmlEscaped()); };
  EXPECT_TRUE(in_tip(type->description)) << tip.toStdString();
  for (const auto& p : type->ports) EXPECT_TRUE(in_tip(p.type.empty() ? p.name : p.name + ": " + p.type)) << tip.toStdString();
  for (const auto& p : type->parameters) EXPECT_TRUE(in_tip(p.name + " (" + p.kind + ")")) << tip.toStdString();
  EXPECT_TRUE(in_tip("image: apex_nodes/Image") && in_tip("circles: apex_nodes/Circles")) << tip.toStdString();
  QTest::keyClicks(search, " lines");  // every word must match
  EXPECT_EQ(shown(), "detection: HoughLines; ");

  // Down from the search goes to the best match in the list; Enter there adds it (one undo step)
  QTest::keyClick(search, Qt::Key_Down);
  EXPECT_TRUE(tree->hasFocus());
  ASSERT_TRUE(tree->currentItem());
  EXPECT_EQ(tree->currentItem()->text(0), "HoughLines");
  QTest::keyClick(tree, Qt::Key_Return);
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editor()->scene()->node("hough_lines_1") != nullptr; }, kWaitMs))
      << panel.editor()->message().toStdString();
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->toolTip().contains("hough_lines_1"); }, kWaitMs))
      << undo->toolTip().toStdString();
  QTest::mouseClick(undo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return !find(runtimeGraph(), "hough_lines_1"); }, kWaitMs));

  // no match: Enter says so; cleared, every heading is back, closed as before the search
  search->selectAll();
  QTest::keyClicks(search, "zzq_no_such_type");
  EXPECT_EQ(shown(), "");
  QTest::keyClick(search, Qt::Key_Return);
  EXPECT_TRUE(panel.editor()->message().contains("no node type matches")) << panel.editor()->message().toStdString();
  search->clear();
  for (int i = 0; i < tree->topLevelItemCount(); ++i) {
    EXPECT_FALSE(tree->topLevelItem(i)->isHidden()) << headings[i];
    EXPECT_FALSE(tree->topLevelItem(i)->isExpanded()) << headings[i];
  }
}

}  // namespace
}  // namespace panel_test
