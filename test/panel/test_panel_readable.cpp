// Readable at rviz's default size: a box's name zoomed out (BoxName), and the 11 nodes of the
// paper's pipeline at Fit in the panel as rviz docks it.
#include "panel_test_support.hpp"

#include <QFontMetricsF>
#include <QPainter>
#include <QStyleOptionGraphicsItem>

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

/** A box as a subgraph of one image output shows it: no parameters, so its previews start high. */
apex::NodeInfo subgraphBox(const std::string& state = "ok") {
  apex::NodeInfo n;
  n.name = "subgraph_1", n.type = "apex/Subgraph", n.subgraph = "inline", n.enabled = true, n.thread_group = "default";
  n.state = state, n.error = state == "error" ? "threw: out of range" : "";
  apex::PortInfo in, out;
  in.name = "image", in.kind = "input", in.type = "apex_nodes/Image";
  out.name = "mask", out.kind = "output", out.type = "apex_nodes/Image";
  n.ports = {in, out};
  return n;
}

/** What the box itself paints (not its ports or editors: items of their own), `margin` px around
 *  its bounds, on a transparent image. */
QImage painted(NodeItem& box, int margin, const QRectF& bounds) {
  QImage image((bounds.size() + QSizeF(2 * margin, 2 * margin)).toSize(), QImage::Format_ARGB32_Premultiplied);
  image.fill(Qt::transparent);
  QPainter p(&image);
  p.translate(margin - bounds.left(), margin - bounds.top());
  QStyleOptionGraphicsItem option;
  box.paint(&p, &option, nullptr);
  return image;
}

TEST(NodeItemPaint, ABoxPaintsOnlyInsideItsBoundsSoAMovedBoxLeavesNoTrail) {
  // The view repaints only an item's bounds when it moves: a pen wider than them leaves dotted
  // trails of the old frame (#48 item 9). An error's frame is the widest.
  for (const double zoom : {1.0, 0.3}) {
    NodeItem box(subgraphBox("error"));
    box.setZoom(zoom);
    const QRectF bounds = box.boundingRect();
    const int margin = 8;
    const QImage image = painted(box, margin, bounds);
    const QRect inside = QRectF(margin, margin, bounds.width(), bounds.height()).toAlignedRect();
    int outside = 0;
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x)
        if (!inside.contains(x, y) && qAlpha(image.pixel(x, y)) > 0) ++outside;
    EXPECT_EQ(outside, 0) << "pixels painted outside the bounds at zoom " << zoom;
  }
}

TEST(NodeItemPaint, ASubgraphsNameZoomedOutIsNotCoveredByItsThumbnail) {
  NodeItem box(subgraphBox());
  box.setPreviews(true);
  QImage frame(640, 480, QImage::Format_RGB32);
  frame.fill(QColor(0, 255, 0));
  box.showImage("mask", frame);
  box.setZoom(0.3);
  const BoxName name = box.name();
  const QRectF bounds = box.boundingRect();
  const QImage whole = painted(box, 0, bounds);
  QImage alone(whole.size(), QImage::Format_ARGB32_Premultiplied);  // the name's letters, drawn alone
  alone.fill(Qt::transparent);
  {
    QPainter p(&alone);
    p.translate(-bounds.left(), -bounds.top());
    p.setFont(name.font);
    p.setPen(Qt::white);
    p.drawText(box.nameArea(), name.flags, name.text);
  }
  int letters = 0, covered = 0;
  for (int y = 0; y < alone.height(); ++y)
    for (int x = 0; x < alone.width(); ++x) {
      if (qAlpha(alone.pixel(x, y)) < 200) continue;
      ++letters;
      const QRgb seen = whole.pixel(x, y);
      if (qGreen(seen) > 200 && qRed(seen) < 100) ++covered;  // the thumbnail's green where a letter is
    }
  EXPECT_GT(letters, 50) << name.text.toStdString();
  EXPECT_EQ(covered, 0) << "of " << letters << " pixels of '" << name.text.toStdString() << "', covered by the thumbnail";
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
