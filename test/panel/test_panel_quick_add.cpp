// Panel tests, continued (same runtime): adding where you work. Tab (or a double-click on empty
// canvas) opens a search box at the cursor that finds types as the palette does and adds the one
// chosen there; a link let go on empty canvas offers only the types that can take it, and adds one
// with the link as one undo step.
#include "panel_test_support.hpp"

#include <QCursor>
#include <QListWidget>
#include <QTreeWidget>

#include <set>

#include "apex_rviz_plugin/quick_add.hpp"

namespace panel_test {
namespace {

class QuickAddTest : public PanelWidgetTest {
 protected:
  /** The ids the palette shows for `words`, sorted. */
  QStringList paletteShows(const QString& words) {
    search->setText(words);
    auto* tree = panel.editor()->findChild<QTreeWidget*>("palette");
    QStringList out;
    for (int i = 0; tree && i < tree->topLevelItemCount(); ++i)
      for (int j = 0; j < tree->topLevelItem(i)->childCount(); ++j)
        if (!tree->topLevelItem(i)->child(j)->isHidden())
          out << tree->topLevelItem(i)->child(j)->data(0, Qt::UserRole).toString();
    search->clear();
    out.sort();
    return out;
  }
  /** The mouse (and the cursor) over the view at `at` (viewport pixels). */
  void pointAt(QPoint at) {
    QCursor::setPos(view->viewport()->mapToGlobal(at));
    mouse(view, QEvent::MouseMove, view->mapToScene(at), Qt::NoButton);
  }
};

TEST_F(QuickAddTest, TabOpensASearchAtTheCursorThatFindsAsThePaletteDoesAndAddsThere) {
  emptyGraph();
  GraphScene* scene = panel.editor()->scene();
  const QPoint at(view->viewport()->width() / 4, view->viewport()->height() / 4);
  const QPointF where = view->mapToScene(at);
  view->setFocus();
  pointAt(at);
  QTest::keyClick(view, Qt::Key_Tab);
  QuickAdd* quick = panel.editor()->quickAdd();
  ASSERT_TRUE(quick && quick->isVisible());
  EXPECT_EQ(quick->shown().size(), panel.nodeTypeCount()) << "every type, before anything is typed";

  // the same rule as the palette: every word in the name, category or description
  for (const QString words : {"hough", "blur", "image filters", "counts messages"}) {
    quick->search()->clear();
    QTest::keyClicks(quick->search(), words);
    QStringList shown = quick->shown();
    shown.sort();
    EXPECT_FALSE(shown.isEmpty()) << words.toStdString();
    EXPECT_EQ(shown, paletteShows(words)) << words.toStdString();
  }
  quick->search()->clear();
  QTest::keyClicks(quick->search(), "hough");
  EXPECT_EQ(quick->shown(), QStringList({"apex_nodes/HoughCircles", "apex_nodes/HoughLines"}));
  QTest::keyClicks(quick->search(), " lines");
  EXPECT_EQ(quick->shown(), QStringList({"apex_nodes/HoughLines"}));

  // Enter adds it with its corner at the cursor
  const std::string name = panel.model().freshName("apex_nodes/HoughLines");
  QTest::keyClick(quick->search(), Qt::Key_Return);
  EXPECT_FALSE(quick->isVisible());
  waitPlaced(name);
  EXPECT_NEAR(panel.model().position(name).first, where.x(), 1.0);
  EXPECT_NEAR(panel.model().position(name).second, where.y(), 1.0);
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->toolTip().contains(QString::fromStdString("Add " + name)); }, kWaitMs))
      << undo->toolTip().toStdString();

  // a double-click on empty canvas opens it there too; Esc closes it and adds nothing
  const QPoint below(view->viewport()->width() * 3 / 4, view->viewport()->height() * 4 / 5);
  ASSERT_TRUE(scene->emptyAt(view->mapToScene(below)));
  for (auto type : {QEvent::MouseButtonPress, QEvent::MouseButtonRelease, QEvent::MouseButtonDblClick})
    mouse(view, type, view->mapToScene(below), type == QEvent::MouseButtonRelease ? Qt::NoButton : Qt::LeftButton);
  mouse(view, QEvent::MouseButtonRelease, view->mapToScene(below), Qt::NoButton);
  ASSERT_TRUE(quick->isVisible());
  EXPECT_EQ(quick->shown().size(), panel.nodeTypeCount()) << "what was typed before is gone";
  QTest::keyClick(quick->search(), Qt::Key_Escape);
  EXPECT_FALSE(quick->isVisible());
  QTest::qWait(200);
  EXPECT_EQ(runtimeGraph().nodes.size(), 1u);
}

TEST_F(QuickAddTest, ALinkLetGoOnEmptyCanvasOffersOnlyTypesThatTakeItAndAddsBothInOneUndoStep) {
  emptyGraph();
  GraphScene* scene = panel.editor()->scene();
  ASSERT_TRUE(addNode("apex_nodes/Clock", "qa_clock", ""));  // by a script: not in the history
  waitPlaced("qa_clock");
  panel.editor()->fitGraph();
  const QPointF count = portAt("qa_clock", "count", true);
  const QPointF drop = count + QPointF(200, 0);
  ASSERT_TRUE(scene->emptyAt(drop));
  drag(view, count, drop);
  QuickAdd* quick = panel.editor()->quickAdd();
  ASSERT_TRUE(quick && quick->isVisible()) << panel.editor()->message().toStdString();

  // offered: exactly the types with an input (or a parameter with ports by default) taking an int
  apex::ListNodeTypes list;
  ASSERT_TRUE(ros::service::call("/apex/list_node_types", list));
  std::set<std::string> expected, offered;
  for (const auto& t : list.response.types) {
    bool takes = false;
    for (const auto& p : t.ports) takes = takes || (p.kind == "input" && (p.type == "int" || p.type == "any"));
    for (const auto& p : t.parameters) takes = takes || (p.interactive && (p.type == "int" || p.type == "any"));
    if (takes) expected.insert(t.id);
  }
  for (const QString& id : quick->shown()) offered.insert(id.toStdString());
  EXPECT_EQ(offered, expected);
  EXPECT_TRUE(offered.count("apex_nodes/Counter"));
  EXPECT_LT(offered.size(), list.response.types.size()) << "image filters cannot take an int";

  // the Counter, added where the link was let go, with the link: one edit
  QTest::keyClicks(quick->search(), "apex_nodes/Counter");
  ASSERT_TRUE(quick->list()->currentItem());
  EXPECT_EQ(quick->list()->currentItem()->text(), QString::fromUtf8("Counter \u00b7 in"));
  const std::string name = panel.model().freshName("apex_nodes/Counter");
  QTest::keyClick(quick->search(), Qt::Key_Return);
  ASSERT_TRUE(QTest::qWaitFor([&] { return connected(runtimeGraph(), "qa_clock", "count", name, "in"); }, kWaitMs))
      << panel.editor()->message().toStdString();
  waitPlaced(name);
  EXPECT_GE(panel.model().position(name).first, drop.x() - 1) << "right of where the link was let go";
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  auto* redo = panel.editor()->findChild<QToolButton*>("redo");
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->toolTip().contains(QString::fromStdString("Add " + name)); }, kWaitMs))
      << undo->toolTip().toStdString();

  // one Undo takes both away (and nothing else was in the history); one Redo brings both back
  QTest::mouseClick(undo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return !find(runtimeGraph(), name); }, kWaitMs)) << panel.editor()->message().toStdString();
  EXPECT_TRUE(find(runtimeGraph(), "qa_clock"));
  EXPECT_FALSE(undo->isEnabled()) << undo->toolTip().toStdString();
  QTest::mouseClick(redo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return connected(runtimeGraph(), "qa_clock", "count", name, "in"); }, kWaitMs))
      << panel.editor()->message().toStdString();
}

TEST_F(QuickAddTest, FromAThresholdsOutputContoursOffersFindContoursFirst) {
  // what can run with the one link comes first: DrawContours needs contours besides the image
  emptyGraph();
  ASSERT_TRUE(addNode("apex_nodes/Threshold", "qa_threshold", ""));
  waitPlaced("qa_threshold");
  panel.editor()->fitGraph();
  const QPointF out = portAt("qa_threshold", "image", true);
  const QPointF drop = out + QPointF(200, 0);
  ASSERT_TRUE(panel.editor()->scene()->emptyAt(drop));
  drag(view, out, drop);
  QuickAdd* quick = panel.editor()->quickAdd();
  ASSERT_TRUE(quick && quick->isVisible()) << panel.editor()->message().toStdString();
  QTest::keyClicks(quick->search(), "contours");
  const QStringList shown = quick->shown();
  ASSERT_TRUE(shown.contains("apex_nodes/FindContours") && shown.contains("apex_nodes/DrawContours"))
      << shown.join(", ").toStdString();
  EXPECT_EQ(shown.front(), "apex_nodes/FindContours") << shown.join(", ").toStdString();
  QTest::keyClick(quick->search(), Qt::Key_Escape);
  emptyGraph();
}

TEST_F(QuickAddTest, ALinkFromAnInputLetGoOnEmptyCanvasAddsANodeThatFeedsIt) {
  emptyGraph();
  GraphScene* scene = panel.editor()->scene();
  ASSERT_TRUE(addNode("apex_nodes/Scale", "qa_scale", ""));
  waitPlaced("qa_scale");
  panel.editor()->fitGraph();
  const QPointF in = portAt("qa_scale", "in", false);
  const QPointF drop = in - QPointF(150, 0);
  ASSERT_TRUE(scene->emptyAt(drop));
  drag(view, in, drop);
  QuickAdd* quick = panel.editor()->quickAdd();
  ASSERT_TRUE(quick && quick->isVisible()) << panel.editor()->message().toStdString();
  EXPECT_FALSE(quick->shown().contains("apex_nodes/HoughLines")) << "its outputs are lines, not numbers";
  QTest::keyClicks(quick->search(), "apex_nodes/Clock");
  ASSERT_TRUE(quick->list()->currentItem());
  EXPECT_EQ(quick->list()->currentItem()->text(), QString::fromUtf8("Clock \u00b7 time")) << "its double output, not the int";
  const std::string name = panel.model().freshName("apex_nodes/Clock");
  QTest::keyClick(quick->search(), Qt::Key_Return);
  ASSERT_TRUE(QTest::qWaitFor([&] { return connected(runtimeGraph(), name, "time", "qa_scale", "in"); }, kWaitMs))
      << panel.editor()->message().toStdString();
  waitPlaced(name);
  EXPECT_LT(panel.model().position(name).first, drop.x()) << "left of where the link was let go";
  emptyGraph();  // the tests after start from nothing
}

TEST_F(QuickAddTest, OpenedNearTheWindowsCornerTheSearchStaysInsideTheWindow) {
  // rviz's window is smaller than the screen: a box hanging past its edge is half out of reach
  const QSize before = panel.size();
  panel.resize(720, 520);
  QApplication::processEvents();
  const QPoint corner(view->viewport()->width() - 5, view->viewport()->height() - 5);
  view->setFocus();
  pointAt(corner);
  QTest::keyClick(view, Qt::Key_Tab);
  QuickAdd* quick = panel.editor()->quickAdd();
  ASSERT_TRUE(quick && quick->isVisible());
  const QRect window = panel.window()->geometry(), box = quick->frameGeometry();
  EXPECT_TRUE(window.contains(box)) << "the box (" << box.x() << ", " << box.y() << ", " << box.width() << " x " << box.height()
                                    << ") is not inside the window (" << window.width() << " x " << window.height() << ")";
  QTest::keyClick(quick->search(), Qt::Key_Escape);
  panel.resize(before);
}

}  // namespace
}  // namespace panel_test
