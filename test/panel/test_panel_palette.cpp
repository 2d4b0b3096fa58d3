// The palette of a library of 100+ node types (and of 150, with another package's type under its own
// heading): headings by category in the runtime's order, search
// over ids, categories and descriptions, tooltips with ports and parameters, adding by keyboard.
#include "panel_test_support.hpp"

#include <QTreeWidget>

#include "apex_rviz_plugin/palette.hpp"

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

/** The example package's type (test/example_package/gain.cpp) as list_node_types describes it. */
apex::NodeTypeInfo exampleGain() {
  apex::NodeTypeInfo t;
  t.id = "demo/Gain";
  t.description = "Multiplies its input by a gain";
  auto port = [](const std::string& name, const std::string& kind, const std::string& type, const std::string& about) {
    apex::PortInfo p;
    p.name = name, p.kind = kind, p.type = type, p.description = about;
    return p;
  };
  t.ports = {port("in", "input", "int", "the value"), port("out", "output", "int", "in times gain"),
             port("overflow", "trigger", "", "fires when the result passes 1000"),
             port("reset", "slot", "", "forgets what it learned")};
  apex::ParamInfo gain;
  gain.name = "gain", gain.kind = "int range", gain.type = "int", gain.default_value = gain.value = "2";
  gain.min = -100, gain.max = 100, gain.description = "the factor";
  t.parameters = {gain};
  return t;
}

TEST_F(PanelWidgetTest, APaletteOf150TypesOrMoreListsAnotherPackagesTypeUnderItsNameAndSearchFindsIt) {
  apex::ListNodeTypes list;
  ASSERT_TRUE(ros::service::call("/apex/list_node_types", list));
  std::vector<apex::NodeTypeInfo> types = list.response.types;  // the library's, from their manifests
  const std::size_t library = types.size();
  types.push_back(exampleGain());
  const std::size_t want = std::max<std::size_t>(150, types.size());  // at least 150, the library's own as it grows
  for (std::size_t i = 0; types.size() < want; ++i) {  // more of its kinds
    apex::NodeTypeInfo more = list.response.types[i % library];
    more.id += "Variant" + std::to_string(i);
    types.push_back(more);
  }
  Palette palette;
  palette.resize(400, 800);
  palette.show();
  palette.showTypes(types);
  auto* tree = palette.findChild<QTreeWidget*>("palette");
  auto* find = palette.findChild<QLineEdit*>("search");
  ASSERT_TRUE(tree && find);
  int listed = 0;
  for (int i = 0; i < tree->topLevelItemCount(); ++i) listed += tree->topLevelItem(i)->childCount();
  EXPECT_EQ(listed, static_cast<int>(want));
  QTreeWidgetItem* last = tree->topLevelItem(tree->topLevelItemCount() - 1);  // other packages after APEX's headings
  ASSERT_TRUE(last);
  EXPECT_EQ(last->text(0).toStdString(), "demo");
  ASSERT_EQ(last->childCount(), 1);
  EXPECT_EQ(last->child(0)->text(0).toStdString(), "Gain");
  EXPECT_TRUE(last->child(0)->toolTip(0).contains("gain (int range)")) << last->child(0)->toolTip(0).toStdString();
  // a search by its description finds it among 150, and Enter would add it
  find->setFocus();
  QTest::keyClicks(find, "multiplies gain");
  ASSERT_TRUE(QTest::qWaitFor([&] { return palette.current() == "demo/Gain"; }, kWaitMs)) << palette.current().toStdString();
  int shown = 0;
  for (int i = 0; i < tree->topLevelItemCount(); ++i)
    for (int j = 0; j < tree->topLevelItem(i)->childCount(); ++j) shown += !tree->topLevelItem(i)->child(j)->isHidden();
  EXPECT_EQ(shown, 1);
}

}  // namespace
}  // namespace panel_test
