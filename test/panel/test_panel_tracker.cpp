// Starting a Tracker on a box drawn on its frame (issue #53): while a bag plays, a Tracker fed by
// its images is right-clicked, "Start on a box drawn on the frame..." shows the frame it saw, and a
// box is dragged on it with the mouse. Its x, y, width and height become that box in the image's
// pixels (the window scales the frame), in one undo step, and it starts on it: its regions output
// gives that box. One undo puts all four back, and it starts on the old box. A Tracker fed by
// nothing, or by an output that has sent no frame, says so and opens no window.
#include "panel_test_support.hpp"

#include <QSignalSpy>

#include <apex/Inspect.h>
#include <apex/Regions.h>

#include <cmath>

#include "apex_rviz_plugin/label_canvas.hpp"
#include "apex_rviz_plugin/tracker_start.hpp"

namespace panel_test {
namespace {

/** A drag with the left button from `from` to `to` (widget coordinates): QTest's press and
 *  release, and between them moves with the button held, sent as the window system sends them
 *  (QTest::mouseMove only moves the cursor in Qt 5). */
void dragWithMouse(QWidget* w, QPoint from, QPoint to) {
  QTest::mousePress(w, Qt::LeftButton, Qt::NoModifier, from);
  for (int i = 1; i <= 8; ++i) {
    const QPoint at = from + (to - from) * (i / 8.0);
    QMouseEvent move(QEvent::MouseMove, at, w->mapToGlobal(at), Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(w, &move);
  }
  QTest::mouseRelease(w, Qt::LeftButton, Qt::NoModifier, to);
}

/** The box a drag from `from` to `to` covers in the image, by the canvas's mapping: its corners
 *  in image pixels, rounded. */
QRect draggedBox(const LabelCanvas& canvas, QPoint from, QPoint to) {
  const QPointF a = canvas.toImage(QPointF(from)), b = canvas.toImage(QPointF(to));
  const int x0 = static_cast<int>(std::lround(std::min(a.x(), b.x()))),
            y0 = static_cast<int>(std::lround(std::min(a.y(), b.y())));
  const int x1 = static_cast<int>(std::lround(std::max(a.x(), b.x()))),
            y1 = static_cast<int>(std::lround(std::max(a.y(), b.y())));
  return QRect(x0, y0, x1 - x0, y1 - y0);
}

/** The Tracker's start box as the runtime holds it. */
QRect startBox(const std::string& tracker) {
  const apex::GraphState g = runtimeGraph();
  return QRect(static_cast<int>(number(g, tracker, "x")), static_cast<int>(number(g, tracker, "y")),
               static_cast<int>(number(g, tracker, "width")), static_cast<int>(number(g, tracker, "height")));
}

std::string text(const QRect& r) {
  return std::to_string(r.x()) + "," + std::to_string(r.y()) + " " + std::to_string(r.width()) + "x" + std::to_string(r.height());
}

/** The boxes a Tracker's regions output gives (its first region each frame), from its inspection. */
class TrackedBoxes {
 public:
  explicit TrackedBoxes(const std::string& tracker) {
    apex::Inspect inspect;
    inspect.request.node = tracker, inspect.request.port = "regions", inspect.request.enable = true;
    EXPECT_TRUE(ros::service::call("/apex/inspect", inspect) && inspect.response.success) << inspect.response.message;
    nh_.setCallbackQueue(&queue_);
    sub_ = nh_.subscribe<apex::Regions>(
        inspect.response.topic, 100, boost::function<void(const apex::Regions::ConstPtr&)>([this](const auto& m) {
          if (!m->regions.empty())
            boxes_.emplace_back(m->regions[0].x, m->regions[0].y, m->regions[0].width, m->regions[0].height);
        }));
  }
  /** Waits until a frame's region is `box`. */
  bool comes(const QRect& box) {
    return QTest::qWaitFor(
        [&] {
          queue_.callAvailable(ros::WallDuration(0.01));
          return std::count(boxes_.begin(), boxes_.end(), box) > 0;
        },
        kWaitMs);
  }
  void forget() {
    queue_.callAvailable(ros::WallDuration(0.01));
    boxes_.clear();
  }

 private:
  ros::NodeHandle nh_;
  ros::CallbackQueue queue_;
  ros::Subscriber sub_;
  std::vector<QRect> boxes_;
};

}  // namespace

TEST(TrackerStartViewAlone, ADraggedBoxIsHandedOnInImagePixelsCutToTheImageAndAClickIsNoBox) {
  QPointer<TrackerStartView> window = new TrackerStartView("tracker", "camera/image");  // deletes itself when closed
  QSignalSpy chosen(window.data(), &TrackerStartView::boxChosen);
  EXPECT_FALSE(window->hasFrame());
  QImage frame(480, 640, QImage::Format_RGB888);
  frame.fill(Qt::darkGray);
  window->showFrame(frame);
  ASSERT_TRUE(window->isVisible() && QTest::qWaitForWindowExposed(window.data()));
  LabelCanvas* canvas = window->canvas();
  QTest::mouseClick(canvas, Qt::LeftButton, Qt::NoModifier, canvas->toWidget(QPointF(100, 100)).toPoint());
  EXPECT_TRUE(window->status().startsWith("a click is no box")) << window->status().toStdString();
  EXPECT_EQ(chosen.count(), 0);
  // past the image's bottom-right corner: the box ends at its edge
  const QPoint from = canvas->toWidget(QPointF(400, 560)).toPoint(), to = canvas->toWidget(QPointF(530, 700)).toPoint();
  const QRect want = draggedBox(*canvas, from, to) & QRect(0, 0, 480, 640);
  dragWithMouse(canvas, from, to);
  ASSERT_EQ(chosen.count(), 1) << window->status().toStdString();
  EXPECT_EQ(chosen[0][0].toString(), "tracker");
  EXPECT_EQ(chosen[0][1].toRect(), want) << text(chosen[0][1].toRect()) << " for " << text(want);
  EXPECT_EQ(want.right(), 479);
  EXPECT_EQ(want.bottom(), 639);
  EXPECT_TRUE(QTest::qWaitFor([&] { return window.isNull(); }, kWaitMs)) << "the window stays after its box was chosen";
}

TEST_F(PanelWidgetTest, ATrackerStartsOnABoxDrawnOnItsFrameInOneUndoStep) {
  emptyGraph();
  startPlaying("track_player");
  ASSERT_TRUE(QTest::qWaitFor(
      [&] {
        const apex::PortInfo* out = panel.model().port("track_player", "camera_image_raw", "output");
        return out && out->type == "apex_nodes/Image";
      },
      kWaitMs))
      << "the player's output is not typed by the bag";
  ASSERT_TRUE(addNode("apex_nodes/Tracker", "track_box", ""));
  ASSERT_TRUE(link("track_player", "camera_image_raw", "track_box", "image"));
  waitPlaced("track_box");
  ASSERT_TRUE(QTest::qWaitFor(
      [&] { return connected(panel.model().graph(), "track_player", "camera_image_raw", "track_box", "image"); }, kWaitMs));
  const QRect before = startBox("track_box");
  TrackedBoxes tracked("track_box");  // from now on: the drag's edit and its undo each restart it
  QMenu other;  // the entry is a Tracker's only
  panel.editor()->fillNodeMenu(other, "track_player");
  EXPECT_FALSE(other.findChild<QAction*>("tracker_start"));

  // Its menu: the frame it saw opens in a window (whole, scaled to fit it)
  ASSERT_GT(chooseInNodeMenu(panel, view, "track_box", "Start on a box drawn on the frame...", {}, 1), 0)
      << "no such entry in a Tracker's menu";
  QPointer<TrackerStartView> window;
  ASSERT_TRUE(QTest::qWaitFor(
      [&] {
        window = panel.trackerStartView();
        return window && window->isVisible();
      },
      kWaitMs))
      << "no window on its frame; message: " << panel.editor()->message().toStdString();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(window.data()));
  EXPECT_EQ(window->source(), "track_player/camera_image_raw");
  LabelCanvas* canvas = window->canvas();
  const QSize image = canvas->image().size();
  EXPECT_EQ(image, QSize(480, 640)) << "not the whole frame (the camera is turned: 480×640)";

  // A box dragged on it: x, y, width and height become it, in the image's pixels
  const QPoint from = canvas->toWidget(QPointF(image.width() * 0.2, image.height() * 0.3)).toPoint();
  const QPoint to = canvas->toWidget(QPointF(image.width() * 0.6, image.height() * 0.65)).toPoint();
  const QRect want = draggedBox(*canvas, from, to);
  ASSERT_NE(want, before);
  tracked.forget();
  dragWithMouse(canvas, from, to);
  ASSERT_TRUE(QTest::qWaitFor([&] { return startBox("track_box") == want; }, kWaitMs))
      << "dragged " << text(want) << ", the runtime has " << text(startBox("track_box"))
      << "; message: " << panel.editor()->message().toStdString();
  EXPECT_TRUE(QTest::qWaitFor([&] { return window.isNull(); }, kWaitMs)) << "the window stays after the box was drawn";
  EXPECT_TRUE(tracked.comes(want)) << "the Tracker did not start on the box drawn";

  // One undo step puts all four back; it starts on the old box again
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  ASSERT_TRUE(undo);
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->toolTip().contains("Start track_box on"); }, kWaitMs))
      << undo->toolTip().toStdString();
  tracked.forget();
  QTest::mouseClick(undo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return startBox("track_box") == before; }, kWaitMs))
      << "after one undo the runtime has " << text(startBox("track_box")) << ", not " << text(before);
  EXPECT_TRUE(tracked.comes(before)) << "the Tracker did not start on its old box after the undo";
  emptyGraph();
}

TEST_F(PanelWidgetTest, ATrackerFedNothingOrNoFrameYetSaysSoAndOpensNoWindow) {
  auto startFromMenu = [&](const QString& tracker) {  // its node menu's entry, as a right-click shows it
    QMenu menu;
    panel.editor()->fillNodeMenu(menu, tracker);
    QAction* start = menu.findChild<QAction*>("tracker_start");
    ASSERT_TRUE(start) << "no Start on a box drawn on the frame... in a Tracker's menu";
    EXPECT_EQ(start->text(), "Start on a box drawn on the frame...");
    start->trigger();
  };
  emptyGraph();
  ASSERT_TRUE(addNode("apex_nodes/GaussianBlur", "unfed_blur", ""));  // its input unlinked: it never sends a frame
  ASSERT_TRUE(addNode("apex_nodes/Tracker", "unfed_tracker", ""));
  waitPlaced("unfed_blur");
  waitPlaced("unfed_tracker");
  startFromMenu("unfed_tracker");
  EXPECT_TRUE(panel.editor()->message().startsWith("nothing feeds unfed_tracker's image input"))
      << panel.editor()->message().toStdString();
  EXPECT_FALSE(panel.trackerStartView());

  ASSERT_TRUE(link("unfed_blur", "image", "unfed_tracker", "image"));
  ASSERT_TRUE(QTest::qWaitFor([&] { return connected(panel.model().graph(), "unfed_blur", "image", "unfed_tracker", "image"); },
                              kWaitMs));
  startFromMenu("unfed_tracker");
  ASSERT_TRUE(
      QTest::qWaitFor([&] { return panel.editor()->message().startsWith("no frame has reached unfed_tracker yet"); }, kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_TRUE(QTest::qWaitFor([&] { return !panel.trackerStartView(); }, kWaitMs)) << "a window waits for a frame still";
  emptyGraph();
}

}  // namespace panel_test
