// Editing while the data flows: a playing bag changes the graph many times a second (its frame and
// time), and no gesture in progress may be cancelled by the graphs shown meanwhile.
#include "panel_test_support.hpp"

#include <QContextMenuEvent>

#include "apex_rviz_plugin/histogram_view.hpp"
#include "apex_rviz_plugin/quick_add.hpp"

namespace panel_test {
namespace {

/** A drag as a hand makes it: a press, moves with the event loop running between them, the
 *  release once at least one graph was shown during the drag (the moment that cancelled it).
 *  Returns the number of graphs shown between the press and the release. */
int liveDrag(PanelWidget& panel, QGraphicsView* view, QPointF from, QPointF to) {
  int shown = 0;
  const auto counting = QObject::connect(&panel, &PanelWidget::graphShown, [&] { ++shown; });
  mouse(view, QEvent::MouseButtonPress, from, Qt::LeftButton);
  for (int i = 1; i <= 10; ++i) {
    QTest::qWait(20);
    mouse(view, QEvent::MouseMove, from + (to - from) * (i / 10.0), Qt::LeftButton);
  }
  (void)QTest::qWaitFor([&] { return shown > 0; }, kWaitMs);  // (the caller asserts it)
  mouse(view, QEvent::MouseMove, to, Qt::LeftButton);
  mouse(view, QEvent::MouseButtonRelease, to, Qt::NoButton);
  QObject::disconnect(counting);
  return shown;
}

/** A button held on `w` at `from`, moved to `to` in steps with the event loop running between
 *  them (over several of the editor's throttle intervals), released once a graph was shown
 *  during it. Returns the number of graphs shown between the press and the release. */
int liveWidgetDrag(PanelWidget& panel, QWidget* w, QPoint from, QPoint to) {
  int shown = 0;
  const auto counting = QObject::connect(&panel, &PanelWidget::graphShown, [&] { ++shown; });
  auto send = [w](QEvent::Type type, QPoint at, Qt::MouseButtons held) {
    QMouseEvent e(type, at, w->mapToGlobal(at), type == QEvent::MouseMove ? Qt::NoButton : Qt::LeftButton, held, Qt::NoModifier);
    QApplication::sendEvent(w, &e);
  };
  send(QEvent::MouseButtonPress, from, Qt::LeftButton);
  for (int i = 1; i <= 8; ++i) {
    QTest::qWait(ParamEditor::kThrottleMs / 2);
    send(QEvent::MouseMove, from + (to - from) * i / 8, Qt::LeftButton);
  }
  (void)QTest::qWaitFor([&] { return shown > 0; }, kWaitMs);  // (the caller asserts it)
  send(QEvent::MouseButtonRelease, to, Qt::NoButton);
  QObject::disconnect(counting);
  return shown;
}

/** Where a slider's handle is, in the slider. */
QPoint handleOf(QSlider* slider) {
  QStyleOptionSlider option;
  option.initFrom(slider);
  option.orientation = slider->orientation();
  option.minimum = slider->minimum(), option.maximum = slider->maximum();
  option.sliderPosition = option.sliderValue = slider->value();
  return slider->style()->subControlRect(QStyle::CC_Slider, &option, QStyle::SC_SliderHandle, slider).center();
}

bool disconnectLink(const std::string& a, const std::string& ap, const std::string& b, const std::string& bp) {
  apex::Connect srv;
  srv.request.from_node = a, srv.request.from_port = ap, srv.request.to_node = b, srv.request.to_port = bp;
  return ros::service::call("/apex/disconnect", srv) && srv.response.success;
}

}  // namespace

TEST_F(PanelWidgetTest, TwentyLinkDragsAllConnectWhileABagPlaysAtItsFullRate) {
  emptyGraph();
  startPlaying("live_player");
  ASSERT_TRUE(addNode("apex_nodes/Clock", "live_clock", ""));
  ASSERT_TRUE(addNode("apex_nodes/Counter", "live_count", ""));
  for (const char* n : {"live_clock", "live_count"}) waitPlaced(n);

  int connected_by_drag = 0;
  for (int i = 0; i < 20; ++i) {
    const int shown = liveDrag(panel, view, portAt("live_clock", "count", true), portAt("live_count", "in", false));
    ASSERT_GT(shown, 0) << "drag " << i << ": no graph came during it";
    const bool made =
        QTest::qWaitFor([&] { return connected(runtimeGraph(), "live_clock", "count", "live_count", "in"); }, kWaitMs);
    ASSERT_TRUE(made) << "drag " << i << " of 20 made no link while the bag played (" << shown
                      << " graphs shown during it); message: " << panel.editor()->message().toStdString();
    ++connected_by_drag;
    ASSERT_TRUE(disconnectLink("live_clock", "count", "live_count", "in"));  // as a script would: the next drag makes it again
    ASSERT_TRUE(QTest::qWaitFor(
        [&] { return !connected(panel.model().graph(), "live_clock", "count", "live_count", "in") && panel.editsPending() == 0; },
        kWaitMs));
  }
  EXPECT_EQ(connected_by_drag, 20);
  emptyGraph();
}

TEST_F(PanelWidgetTest, ALinkDraggedToEmptyCanvasAndAMenuBothWorkWhileABagPlays) {
  emptyGraph();
  startPlaying("menu_player");
  ASSERT_TRUE(addNode("apex_nodes/Clock", "menu_clock", ""));
  waitPlaced("menu_clock");

  // drag-to-add: a link from the clock let go on empty canvas, graphs coming meanwhile; the box
  // that opens adds a Counter with the link
  const QPointF count = portAt("menu_clock", "count", true);
  QPointF drop = count + QPointF(260, 0);
  view->ensureVisible(QRectF(drop, QSizeF(1, 1)));
  ASSERT_TRUE(panel.editor()->scene()->emptyAt(drop));
  ASSERT_GT(liveDrag(panel, view, portAt("menu_clock", "count", true), drop), 0) << "no graph came during the drag";
  QuickAdd* quick = panel.editor()->quickAdd();
  ASSERT_TRUE(quick && quick->isVisible()) << "no quick add after the drag; " << panel.editor()->message().toStdString();
  QTest::keyClicks(quick->search(), "apex_nodes/Counter");
  const std::string counter = panel.model().freshName("apex_nodes/Counter");
  QTest::keyClick(quick->search(), Qt::Key_Return);
  ASSERT_TRUE(QTest::qWaitFor([&] { return connected(runtimeGraph(), "menu_clock", "count", counter, "in"); }, kWaitMs))
      << panel.editor()->message().toStdString();

  // a right-click menu held open while graphs come, then "Disable" chosen in it
  const int shown = chooseInNodeMenu(panel, view, "menu_clock", "Disable");
  ASSERT_GE(shown, 3) << "the node's menu did not stay open through " << -shown << " graphs";
  ASSERT_TRUE(QTest::qWaitFor(
      [&] {
        const auto* n = find(runtimeGraph(), "menu_clock");
        return n && !n->enabled;
      },
      kWaitMs))
      << panel.editor()->message().toStdString();
  emptyGraph();
}

TEST_F(PanelWidgetTest, TheSelectedNodesParametersAreSetInItsPropertiesWhileABagPlays) {
  emptyGraph();
  startPlaying("prop_player");
  ASSERT_TRUE(addNode("apex_nodes/Clock", "prop_clock", "{rate: 10.0}"));
  waitPlaced("prop_clock");

  // a click on the box's title: its parameters beside the canvas, at the panel's size
  NodeItem* clock = panel.editor()->scene()->node("prop_clock");
  const QPointF title = clock->scenePos() + QPointF(40, 8);
  view->ensureVisible(QRectF(title, QSizeF(1, 1)));
  mouse(view, QEvent::MouseButtonPress, title, Qt::LeftButton);
  mouse(view, QEvent::MouseButtonRelease, title, Qt::NoButton);
  PropertiesView* properties = panel.editor()->properties();
  ASSERT_EQ(properties->node(), "prop_clock");
  auto* side = panel.editor()->findChild<QTabWidget*>("side");
  ASSERT_TRUE(side && side->currentWidget() == properties) << "the properties are not the tab shown";
  const QPointer<ParamEditor> rate = properties->editor("rate");
  ASSERT_TRUE(rate);
  auto* slider = rate->findChild<QSlider*>();
  auto* spin = rate->findChild<QDoubleSpinBox*>("spin");
  ASSERT_TRUE(slider && spin);
  QApplication::processEvents();

  // a slider drag by the mouse while graphs come: the editor stays, the runtime takes the value
  const QPoint from = handleOf(slider);
  const int shown = liveWidgetDrag(panel, slider, from, from + QPoint(slider->width() / 5, 0));
  ASSERT_GT(shown, 0) << "no graph came during the drag";
  ASSERT_TRUE(rate) << "the properties' editor was rebuilt under the drag";
  const double dragged = spin->value();
  ASSERT_GT(dragged, 10.0) << "the drag did not move the slider";
  ASSERT_TRUE(QTest::qWaitFor(
      [&] { return panel.editsPending() == 0 && std::abs(number(runtimeGraph(), "prop_clock", "rate") - dragged) < 1e-3; },
      kWaitMs))
      << number(runtimeGraph(), "prop_clock", "rate") << " vs " << dragged;

  // a value typed key by key while graphs come, then Enter: that value, not one a graph brought back
  QLineEdit* field = spin->findChild<QLineEdit*>();
  ASSERT_TRUE(field);
  panel.activateWindow();  // typed into as a person does: the window active, the field focused
  ASSERT_TRUE(QTest::qWaitForWindowActive(&panel));
  spin->setFocus();
  ASSERT_TRUE(QTest::qWaitFor([&] { return spin->hasFocus(); }, kWaitMs));
  field->selectAll();
  for (const QChar c : QString("25")) {
    const auto at = panel.model().graph().revision;
    QTest::keyClicks(field, QString(c));
    ASSERT_TRUE(QTest::qWaitFor([&] { return panel.model().graph().revision > at; }, kWaitMs));
  }
  QTest::keyClick(field, Qt::Key_Return);
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(runtimeGraph(), "prop_clock", "rate") == 25.0; }, kWaitMs))
      << number(runtimeGraph(), "prop_clock", "rate");
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(panel.model().graph(), "prop_clock", "rate") == 25.0; }, kWaitMs));
  EXPECT_EQ(panel.editor()->scene()->node("prop_clock")->editor("rate")->findChild<QDoubleSpinBox*>("spin")->value(), 25.0)
      << "the box does not show the value set in the properties";
  panel.editor()->scene()->clearSelection();
  EXPECT_TRUE(properties->node().isEmpty());
  emptyGraph();
}

TEST_F(PanelWidgetTest, OnAHeldFrameANodeThatLearnsFromEveryFrameSaysThatReRunsChangeIt) {
  emptyGraph();
  ASSERT_TRUE(
      addNode("apex_nodes/BagReader", "held_player", "{file: '" + g_bag + "', topics: [/camera/image_raw], playing: false}"));
  ASSERT_TRUE(addNode("apex_nodes/BackgroundSubtraction", "held_mog", ""));
  ASSERT_TRUE(addNode("apex_nodes/GaussianBlur", "held_blur", ""));
  for (const char* n : {"held_player", "held_mog", "held_blur"}) waitPlaced(n);
  GraphScene* scene = panel.editor()->scene();
  EXPECT_TRUE(scene->node("held_mog")->heldNote().contains("re-runs")) << "MOG2 on a held frame says nothing";
  // what the type keeps comes with the types' list, which may arrive after the box is placed
  EXPECT_TRUE(QTest::qWaitFor([&] { return scene->node("held_mog")->toolTip().contains("background model"); }, kWaitMs))
      << scene->node("held_mog")->toolTip().toStdString();
  EXPECT_TRUE(scene->node("held_blur")->heldNote().isEmpty()) << "a blur keeps nothing from frame to frame";
  scene->node("held_mog")->setSelected(true);
  auto* kind = panel.editor()->properties()->findChild<QLabel*>("properties_kind");
  ASSERT_TRUE(kind);
  EXPECT_TRUE(kind->text().contains("Keeps from frame to frame")) << kind->text().toStdString();
  ASSERT_TRUE(setParameter("held_player", "playing", "true"));  // frames flow: nothing is re-run
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("held_mog")->heldNote().isEmpty(); }, kWaitMs));
  ASSERT_TRUE(setParameter("held_player", "playing", "false"));
  ASSERT_TRUE(QTest::qWaitFor([&] { return !scene->node("held_mog")->heldNote().isEmpty(); }, kWaitMs));
  scene->clearSelection();
  emptyGraph();
}

namespace {
/** The text on the link from `from`'s output ("" if none). */
QString rateText(GraphScene* scene, const std::string& from) {
  for (const ConnectionItem* c : scene->connections())
    if (c->connection().from_node == from) return c->rateText();
  return {};
}
}  // namespace

TEST_F(PanelWidgetTest, WhileABagPlaysLinksShowTheirRateAndANodesMenuColoursItsCriticalPath) {
  emptyGraph();
  startPlaying("rate_player");
  ASSERT_TRUE(addNode("apex_nodes/GaussianBlur", "rate_blur", ""));
  ASSERT_TRUE(addNode("apex_nodes/Counter", "rate_count", ""));
  for (const char* n : {"rate_blur", "rate_count"}) waitPlaced(n);
  ASSERT_TRUE(link("rate_player", "camera_image_raw", "rate_blur", "image") && link("rate_blur", "image", "rate_count", "in"));
  GraphScene* scene = panel.editor()->scene();
  // each link says how many messages a second its output sends (from two statuses, 0.5 s apart)
  const auto rates = [&] {
    std::map<std::string, double> out;
    for (const ConnectionItem* c : scene->connections()) {
      const QString text = c->rateText();
      if (text.contains("/s")) out[c->connection().from_node] = text.left(text.indexOf("/s")).toDouble();
    }
    return out;
  };
  ASSERT_TRUE(QTest::qWaitFor(
      [&] {
        const auto r = rates();
        return r.size() == 2 && r.at("rate_player") > 0 && r.at("rate_blur") > 0;
      },
      kWaitMs))
      << rates().size() << " links with a rate";

  // Right-click on the counter, "Critical path to here" chosen while graphs come: the chain is coloured
  const int shown = chooseInNodeMenu(panel, view, "rate_count", "Critical path to here");
  ASSERT_GE(shown, 3) << "not chosen in the node's menu (" << -shown << " graphs shown while it was open)";
  EXPECT_TRUE(panel.editor()->message().startsWith("critical path to rate_count: rate_player → rate_blur → rate_count: "))
      << panel.editor()->message().toStdString();
  const auto critical = [&] {
    int n = 0;
    for (const ConnectionItem* c : scene->connections()) n += c->critical() ? 1 : 0;
    return n;
  };
  ASSERT_TRUE(QTest::qWaitFor([&] { return critical() == 2; }, kWaitMs)) << critical() << " links coloured";
  for (const char* n : {"rate_player", "rate_blur", "rate_count"}) EXPECT_TRUE(scene->node(n)->critical()) << n;
  QTest::qWait(600);  // a status and graphs later (the bag plays on), it is still shown
  EXPECT_EQ(critical(), 2);
  EXPECT_LT(chooseInNodeMenu(panel, view, "rate_blur", "Hide the critical path"), 0) << "only its target's menu hides it";
  ASSERT_GE(chooseInNodeMenu(panel, view, "rate_count", "Hide the critical path"), 3);
  EXPECT_EQ(critical(), 0);
  EXPECT_FALSE(scene->node("rate_count")->critical());

  // "Latency histogram..." opens the blur's histograms, updated as it fires; the bag plays at its
  // recorded stamps, so the latency says why it has none
  ASSERT_GE(chooseInNodeMenu(panel, view, "rate_blur", "Latency histogram..."), 3);
  auto* histogram = panel.findChild<HistogramView*>("histogram_rate_blur");
  ASSERT_TRUE(histogram && histogram->isVisible());
  ASSERT_TRUE(QTest::qWaitFor([&] { return histogram->timeChart()->bars().total() >= 5; }, kWaitMs))
      << histogram->timeText().toStdString();
  const std::uint64_t first = histogram->timeChart()->bars().total();
  EXPECT_TRUE(histogram->timeText().contains(" · p50 ")) << histogram->timeText().toStdString();
  EXPECT_TRUE(histogram->latencyText().startsWith("none: ")) << histogram->latencyText().toStdString();
  ASSERT_TRUE(QTest::qWaitFor([&] { return histogram->timeChart()->bars().total() > first; }, kWaitMs)) << "not updated";
  EXPECT_FALSE(rateText(scene, "rate_blur").contains("p95")) << "no live latency yet";

  // the bag restamped as it plays, as a live camera: the links and the histogram show live latency
  ASSERT_TRUE(setParameter("rate_player", "restamp", "true"));
  ASSERT_TRUE(QTest::qWaitFor([&] { return rateText(scene, "rate_blur").contains(" · p95 "); }, kWaitMs))
      << rateText(scene, "rate_blur").toStdString();
  EXPECT_TRUE(rateText(scene, "rate_blur").endsWith(" ms")) << rateText(scene, "rate_blur").toStdString();
  ASSERT_TRUE(QTest::qWaitFor([&] { return !histogram->latencyText().startsWith("none"); }, kWaitMs))
      << histogram->latencyText().toStdString();
  histogram->grab().save(QString::fromStdString(g_shot).replace(".png", "_histogram.png"));  // the window, to look at
  ASSERT_GE(chooseInNodeMenu(panel, view, "rate_blur", "Latency histogram..."), 3);
  EXPECT_EQ(panel.findChildren<HistogramView*>().size(), 1u) << "one window per node";
  histogram->close();
  emptyGraph();
}

}  // namespace panel_test
