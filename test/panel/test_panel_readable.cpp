// Readable at rviz's default size: a box's name zoomed out (BoxName), and the 11 nodes of the
// paper's pipeline at Fit in the panel as rviz docks it.
#include "panel_test_support.hpp"

#include <QFontMetricsF>

#include "apex_rviz_plugin/box_name.hpp"

namespace panel_test {
namespace {

TEST(BoxNameTest, ANameTooLongForItsBoxIsOneLineWithItsEndElidedNeverPastTheBox) {
  QFont bold;
  bold.setBold(true);
  const QRectF small(0, 0, 200, 100);  // at zoom 0.2: 40 x 20 px on screen, room for one 13-px line
  const BoxName n = BoxName::fit("preset_other_clock", small, 0.2, bold);
  EXPECT_FALSE(n.whole);
  EXPECT_TRUE(n.text.endsWith(QChar(0x2026))) << n.text.toStdString();
  EXPECT_LE(QFontMetricsF(n.font).boundingRect(small, n.flags, n.text).height(), small.height()) << "drawn past the box";
  EXPECT_GE(n.pixels(0.2), 13.0);
  // a word with no break, in a box tall enough for two lines: broken anywhere, every letter kept
  EXPECT_TRUE(BoxName::fit("passthrough", QRectF(0, 0, 200, 200), 0.3, bold).whole);
}

TEST_F(PanelWidgetTest, TheElevenNodesOfThePaperPipelineAreReadableAtFitInRvizsDefaultDock) {
  // rviz at its default size (1200 x 846) with the panel docked at the bottom, the 3D view keeping
  // more than half the window (test/panel/rviz_layout.py): the panel is ~1190 x 265 px
  const QSize before = panel.size();
  panel.resize(1190, 265);
  emit panel.editor()->loadRequested(QString::fromStdString(g_graphs + "/paper_pipeline.yaml"));
  GraphScene* scene = panel.editor()->scene();
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->boxes().size() == 11 && panel.editsPending() == 0; }, kWaitMs))
      << panel.editor()->message().toStdString();
  QTest::mouseClick(panel.editor()->findChild<QToolButton*>("fit"), Qt::LeftButton);
  const QRectF seen = view->mapToScene(view->viewport()->rect()).boundingRect();
  for (const auto& [name, item] : scene->nodes()) {
    EXPECT_TRUE(seen.contains(item->sceneBoundingRect())) << name << " is out of view after Fit";
    for (const PortItem* port : item->ports())  // the ports at the boxes' edges too
      EXPECT_TRUE(seen.contains(port->sceneBoundingRect())) << name << "/" << port->port().name << " is cut at Fit";
    EXPECT_GE(item->namePixels(), 10.0) << name << "'s name at Fit, at zoom " << view->transform().m11();
    EXPECT_TRUE(item->name().whole) << name << "'s name does not fit its box at Fit";
  }
  panel.editor()->scene()->clearSelection();
  panel.resize(before);
  emptyGraph();
}

}  // namespace
}  // namespace panel_test
