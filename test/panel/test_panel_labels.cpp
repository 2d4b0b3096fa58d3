// Labelling frames in the panel (issue #49): a bag's image output opened from its port's menu,
// boxes dragged on three of its frames with the mouse, their classes typed, Next pressed between
// them, saved; the file reads back through the truth reader RegionScore uses with those boxes.
#include "panel_test_support.hpp"

#include <QCheckBox>
#include <QComboBox>
#include <QPushButton>

#include "apex_nodes/truth.hpp"
#include "apex_rviz_plugin/label_canvas.hpp"
#include "apex_rviz_plugin/label_view.hpp"

namespace panel_test {
namespace {

constexpr std::uint64_t kBagStart = 1700000000000000000, kFrameStep = 100000000;  // the demo bag's stamps: 10 a second

/** A drag on a widget with the left button, from `from` to `to` (widget coordinates), in steps. */
void dragOn(QWidget* w, QPointF from, QPointF to) {
  auto send = [w](QEvent::Type type, QPointF at, Qt::MouseButtons held) {
    QMouseEvent e(type, at, w->mapToGlobal(at.toPoint()), type == QEvent::MouseMove ? Qt::NoButton : Qt::LeftButton, held,
                  Qt::NoModifier);
    QApplication::sendEvent(w, &e);
  };
  send(QEvent::MouseButtonPress, from, Qt::LeftButton);
  for (int i = 1; i <= 8; ++i) send(QEvent::MouseMove, from + (to - from) * (i / 8.0), Qt::LeftButton);
  send(QEvent::MouseButtonRelease, to, Qt::NoButton);
}

/** Types `text` into the class field, as a person does (the old text selected first). */
void typeClass(LabelView* view, const QString& text) {
  auto* field = view->findChild<QComboBox*>("label_class");
  ASSERT_TRUE(field && field->lineEdit());
  field->lineEdit()->setFocus();
  field->lineEdit()->selectAll();
  QTest::keyClicks(field->lineEdit(), text);
}

/** Drags a box on the canvas over image pixels `box`. */
void drawBox(LabelView* view, const QRect& box) {
  LabelCanvas* canvas = view->canvas();
  dragOn(canvas, canvas->toWidget(box.topLeft()), canvas->toWidget(QPointF(box.x() + box.width(), box.y() + box.height())));
}

}  // namespace

TEST(LabelViewAlone, ADragBeforeAnyFrameSaysThereIsNoFrameYetAndSavingNothingIsRefused) {
  LabelView view("camera", "image");
  view.resize(700, 500);
  view.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&view));
  dragOn(view.canvas(), QPointF(50, 50), QPointF(150, 120));
  EXPECT_EQ(view.status().toStdString(), "no frame from camera/image yet: play or step its source");
  QTest::mouseClick(view.findChild<QPushButton*>("save_labels"), Qt::LeftButton);
  EXPECT_TRUE(view.status().contains("no frame is labelled yet")) << view.status().toStdString();
  EXPECT_FALSE(view.findChild<QPushButton*>("next_frame")->isEnabled()) << "no player: nothing to step";
}

TEST_F(PanelWidgetTest, LabelThreeFramesByMouseAndSaveATruthFileRegionScoreReads) {
  emptyGraph();
  ASSERT_TRUE(addNode("apex_nodes/BagReader", "label_bag",
                      "{file: '" + g_bag + "', topics: [/camera/image_raw], rate: 1.0, loop: true, playing: true}"));
  waitPlaced("label_bag");
  ASSERT_TRUE(QTest::qWaitFor(
      [&] {
        const apex::PortInfo* out = panel.model().port("label_bag", "camera_image_raw", "output");
        return out && out->type == "apex_nodes/Image";
      },
      kWaitMs))
      << "the player's output is not typed by the bag";

  // Its output's menu: Label frames... opens the window on it and pauses the playing bag.
  QMenu menu;
  panel.editor()->fillPortMenu(menu, "label_bag", "camera_image_raw");
  QAction* open = menu.findChild<QAction*>("label_frames");
  ASSERT_TRUE(open) << "no Label frames in an image output's menu";
  open->trigger();
  LabelView* view = panel.labelView("label_bag", "camera_image_raw");
  ASSERT_TRUE(view && view->isVisible());
  ASSERT_TRUE(QTest::qWaitForWindowExposed(view));
  auto heldStamp = [&] {  // the stamp of the frame the paused player holds
    const apex::GraphState g = runtimeGraph();
    return param(g, "label_bag", "playing") == "false" ? kBagStart + kFrameStep * std::stoull(param(g, "label_bag", "frame")) : 0;
  };
  ASSERT_TRUE(QTest::qWaitFor([&] { return view->stamp() != 0 && view->stamp() == heldStamp(); }, kWaitMs))
      << "the window does not show the paused player's frame; status: " << view->status().toStdString();
  EXPECT_EQ(view->canvas()->image().size(), QSize(480, 640)) << "not the whole image (the camera is turned: 480×640)";

  // Three frames: a box dragged over each sign the bag's generator put there (its truth file), with
  // the sign's digit typed as its class first; Next between them.
  const apex_nodes::Truth generated =
      apex_nodes::loadTruth((std::filesystem::path(g_bag).parent_path() / "test_truth.yaml").string());
  const cv::Size image(480, 640);
  auto signsOn = [&](std::uint64_t stamp) {
    std::vector<apex_nodes::TruthSign> signs;
    if (const auto* f = generated.frameAt(stamp))
      for (const auto& s : *f) signs.push_back({apex_nodes::toImage(generated, s.box, image), s.digit});
    return signs;
  };
  std::vector<std::uint64_t> stamps;
  std::size_t boxes = 0;
  for (int f = 0; f < 3; ++f) {
    if (f > 0) {
      const quint64 before = view->stamp();
      QTest::mouseClick(view->findChild<QPushButton*>("next_frame"), Qt::LeftButton);
      ASSERT_TRUE(QTest::qWaitFor([&] { return view->stamp() != before && view->stamp() == heldStamp(); }, kWaitMs))
          << "Next did not bring the player's next frame; status: " << view->status().toStdString();
    }
    stamps.push_back(view->stamp());
    const auto signs = signsOn(view->stamp());
    ASSERT_FALSE(signs.empty()) << "no sign on the frame at " << view->stamp();
    for (std::size_t i = 0; i < signs.size(); ++i) {
      const bool mistyped = f == 0 && i == 0;  // this one's class is put right below, by selecting it
      typeClass(view, mistyped ? "9" : QString::number(signs[i].digit));
      const cv::Rect& b = signs[i].box;
      drawBox(view, QRect(b.x, b.y, b.width, b.height));
      ASSERT_TRUE(view->status().startsWith("box ")) << view->status().toStdString();
      ++boxes;
    }
    EXPECT_TRUE(view->findChild<QCheckBox*>("frame_labelled")->isChecked());
  }
  EXPECT_EQ(view->labels().boxCount(), boxes);
  view->grab().save(QString::fromStdString(g_shot).replace(".png", "_labels.png"));  // the window (docs/panel_labels.png)
  // A drag along a line is no box: ignored, saying so. A box drawn by mistake: clicked, Delete.
  const QPointF corner = view->canvas()->toWidget(QPointF(5, 5));
  dragOn(view->canvas(), corner, corner + QPointF(0, 40));
  EXPECT_TRUE(view->status().contains("ignored")) << view->status().toStdString();
  EXPECT_EQ(view->labels().boxCount(), boxes);
  drawBox(view, QRect(5, 5, 30, 30));
  EXPECT_EQ(view->labels().boxCount(), boxes + 1);
  QTest::mouseClick(view->canvas(), Qt::LeftButton, Qt::NoModifier, view->canvas()->toWidget(QPointF(20, 20)).toPoint());
  ASSERT_GE(view->canvas()->selected(), 0) << view->status().toStdString();
  QTest::keyClick(view->canvas(), Qt::Key_Delete);
  EXPECT_EQ(view->labels().boxCount(), boxes) << view->status().toStdString();
  // Back to the first frame (the ← key, then ◀ Previous): its mistyped box, clicked, takes the
  // digit typed on the frame.
  for (int f = 2; f > 0; --f) {
    const quint64 before = view->stamp();
    if (f == 2) QTest::keyClick(view->canvas(), Qt::Key_Left);
    else QTest::mouseClick(view->findChild<QPushButton*>("previous_frame"), Qt::LeftButton);
    ASSERT_TRUE(QTest::qWaitFor([&] { return view->stamp() != before && view->stamp() == heldStamp(); }, kWaitMs))
        << "no previous frame; status: " << view->status().toStdString();
  }
  ASSERT_EQ(view->stamp(), stamps[0]);
  const apex_nodes::TruthSign first = signsOn(stamps[0])[0];
  const cv::Point middle = (first.box.tl() + first.box.br()) / 2;
  QTest::mouseClick(view->canvas(), Qt::LeftButton, Qt::NoModifier,
                    view->canvas()->toWidget(QPointF(middle.x, middle.y)).toPoint());
  ASSERT_EQ(view->canvas()->selected(), 0) << view->status().toStdString();
  QTest::keyClicks(view->canvas(), QString::number(first.digit));
  EXPECT_EQ(view->labels().frame(stamps[0])->boxes[0].label, std::to_string(first.digit));
  // Saved where the runtime reads files (a RegionScore's truth); a folder that is not there is named.
  const std::string path = (std::filesystem::path(g_bag).parent_path() / "panel_labels.json").string();
  std::filesystem::remove(path);
  auto* where = view->findChild<QLineEdit*>("labels_path");
  where->setText("/no_such_folder/labels.json");
  QTest::mouseClick(view->findChild<QPushButton*>("save_labels"), Qt::LeftButton);
  EXPECT_TRUE(view->status().contains("cannot write '/no_such_folder/labels.json'")) << view->status().toStdString();
  where->setText(QString::fromStdString(path));
  QTest::mouseClick(view->findChild<QPushButton*>("save_labels"), Qt::LeftButton);
  ASSERT_TRUE(view->status().startsWith(QString("saved 3 frames, %1 boxes").arg(boxes))) << view->status().toStdString();

  // Read as RegionScore reads it: the three frames, each sign's box within a pixel or two of the
  // generator's, with its digit; the generator's boxes as regions all match them.
  const apex_nodes::Truth truth = apex_nodes::loadTruth(path);
  ASSERT_EQ(truth.frames.size(), 3u);
  EXPECT_TRUE(truth.has_digits);
  for (const std::uint64_t stamp : stamps) {
    const auto* labelled = truth.frameAt(stamp);
    ASSERT_TRUE(labelled) << "the frame at " << stamp << " ns is not in the file";
    const auto signs = signsOn(stamp);
    ASSERT_EQ(labelled->size(), signs.size()) << "frame at " << stamp;
    std::vector<apex_nodes::Region> regions;
    for (std::size_t i = 0; i < signs.size(); ++i) {
      const cv::Rect &got = (*labelled)[i].box, &want = signs[i].box;
      EXPECT_EQ((*labelled)[i].digit, signs[i].digit) << "frame at " << stamp << ", box " << i;
      EXPECT_LE(cv::norm(got.tl() - want.tl()) + cv::norm(got.br() - want.br()), 3) << got << " dragged over " << want;
      regions.push_back({want, static_cast<double>(want.area()), {}});
    }
    EXPECT_EQ(apex_nodes::matchSigns(*labelled, regions, 0.5).size(), signs.size()) << "frame at " << stamp;
  }
  view->close();
  std::filesystem::remove(path);
  emptyGraph();
}

}  // namespace panel_test
