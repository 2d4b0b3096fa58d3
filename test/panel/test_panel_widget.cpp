// The panel widget (what GraphPanel shows in rviz) driven by simulated mouse and
// keyboard input against a real runtime, offscreen. Each step is checked in the
// runtime's own graph (~get_graph), not in the panel. Screenshots are written.
//   test_panel_widget SCREENSHOT.png DEMO_BAG GRAPHS_FOLDER
// This file: adding, connecting, tuning, subgraphs, editing. The tests go on in
// test_panel_palette.cpp, test_panel_tuning_and_layout.cpp and test_panel_runtimes.cpp (linked in that order).
#include "panel_test_support.hpp"

namespace panel_test {
namespace {

TEST_F(PanelWidgetTest, AddMoveConnectTuneAndUndoByMouseAndKeyboard) {
  // add two nodes from the palette with the keyboard
  addByKeyboard("Clock", "clock_1");
  addByKeyboard("Counter", "counter_1");
  addByKeyboard("apex_nodes/Scale", "scale_1");
  auto g = runtimeGraph();
  ASSERT_TRUE(find(g, "clock_1") && find(g, "counter_1") && find(g, "scale_1"));

  // move them apart by dragging their titles; the positions reach the graph's UI metadata
  NodeItem* counter = panel.editor()->scene()->node("counter_1");
  NodeItem* scale = panel.editor()->scene()->node("scale_1");
  NodeItem* clock = panel.editor()->scene()->node("clock_1");
  clock->setZValue(0), counter->setZValue(2), scale->setZValue(3);  // the titles to grab are on top
  drag(view, scale->scenePos() + QPointF(60, 10), scale->scenePos() + QPointF(60 + 300, 10 + 260));
  drag(view, counter->scenePos() + QPointF(60, 10), counter->scenePos() + QPointF(60 + 300, 10 - 30));
  const auto counter_ui = counter->scenePos();
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.model().position("counter_1").first == int(counter_ui.x()); }, kWaitMs));
  const YAML::Node ui = YAML::Load(find(runtimeGraph(), "counter_1")->ui);
  EXPECT_EQ(ui["x"].as<int>(), int(counter_ui.x()));
  EXPECT_EQ(ui["y"].as<int>(), int(counter_ui.y()));

  // connect clock/count -> counter/in by dragging from the output to the input
  panel.editor()->fitGraph();
  drag(view, portAt("clock_1", "count", true), portAt("counter_1", "in", false));
  ASSERT_TRUE(QTest::qWaitFor([&] { return connected(panel.model().graph(), "clock_1", "count", "counter_1", "in"); }, kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_TRUE(connected(runtimeGraph(), "clock_1", "count", "counter_1", "in"));

  // an int output onto a double input is refused in the panel, with the reason, and nothing is sent
  drag(view, portAt("clock_1", "count", true), portAt("scale_1", "in", false));
  EXPECT_NE(panel.editor()->message().toStdString().find("type mismatch"), std::string::npos)
      << panel.editor()->message().toStdString();
  EXPECT_FALSE(connected(runtimeGraph(), "clock_1", "count", "scale_1", "in"));

  // type a new rate into the clock's spin box: the runtime applies it, the widget shows it
  ParamEditor* rate = clock->editor("rate");
  ASSERT_TRUE(rate);
  auto* spin = rate->findChild<QDoubleSpinBox*>("spin");
  ASSERT_TRUE(spin);
  spin->setFocus();
  spin->selectAll();
  QTest::keyClicks(spin, "25");
  QTest::keyClick(spin, Qt::Key_Return);
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(panel.model().graph(), "clock_1", "rate") == 25; }, kWaitMs))
      << "rate is " << param(panel.model().graph(), "clock_1", "rate") << "; " << panel.editor()->message().toStdString();
  EXPECT_EQ(number(runtimeGraph(), "clock_1", "rate"), 25);
  EXPECT_DOUBLE_EQ(spin->value(), 25.0);

  // undo (button) restores the rate; redo sets it again
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  auto* redo = panel.editor()->findChild<QToolButton*>("redo");
  // the edit is in the history once the runtime's answer is in (the new ~graph may come first)
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->toolTip().contains("Set clock_1/rate"); }, kWaitMs))
      << undo->toolTip().toStdString();
  QTest::mouseClick(undo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(panel.model().graph(), "clock_1", "rate") == 10; }, kWaitMs));
  EXPECT_EQ(number(runtimeGraph(), "clock_1", "rate"), 10);
  EXPECT_DOUBLE_EQ(spin->value(), 10.0);
  QTest::mouseClick(redo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(panel.model().graph(), "clock_1", "rate") == 25; }, kWaitMs));

  // the spin box keeps to the declared range: the digit that would leave it (max 1000) is not taken
  spin->setFocus();
  spin->selectAll();
  QTest::keyClicks(spin, "5000");
  QTest::keyClick(spin, Qt::Key_Return);
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(panel.model().graph(), "clock_1", "rate") == 500; }, kWaitMs))
      << "rate is " << param(panel.model().graph(), "clock_1", "rate");

  // data flows: the boxes show firings, rate and timing from ~status as they grow
  ASSERT_TRUE(QTest::qWaitFor([&] { return counter->firings() > 100 && clock->firings() > 100; }, kWaitMs))
      << counter->timing().toStdString();
  EXPECT_TRUE(counter->timing().contains(" Hz")) << counter->timing().toStdString();

  // a double click on an output inspects it: a scalar's value is shown in the node
  const QPointF count_port = portAt("counter_1", "count", true);
  mouse(view, QEvent::MouseButtonPress, count_port, Qt::LeftButton);
  mouse(view, QEvent::MouseButtonRelease, count_port, Qt::NoButton);
  mouse(view, QEvent::MouseButtonDblClick, count_port, Qt::LeftButton);
  mouse(view, QEvent::MouseButtonRelease, count_port, Qt::NoButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return counter->values().startsWith("count = "); }, kWaitMs))
      << panel.editor()->message().toStdString();

  // a click on its title selects a node; Delete removes it
  const QPointF title = scale->scenePos() + QPointF(60, 10);
  mouse(view, QEvent::MouseButtonPress, title, Qt::LeftButton);
  mouse(view, QEvent::MouseButtonRelease, title, Qt::NoButton);
  ASSERT_TRUE(scale->isSelected());
  EXPECT_FALSE(counter->isSelected() || clock->isSelected());
  view->setFocus();
  QTest::keyClick(view, Qt::Key_Delete);
  ASSERT_TRUE(QTest::qWaitFor([&] { return !panel.model().node("scale_1"); }, kWaitMs));
  EXPECT_FALSE(find(runtimeGraph(), "scale_1"));

  panel.editor()->fitGraph();
  QApplication::processEvents();
  ASSERT_TRUE(panel.grab().save(QString::fromStdString(g_shot))) << "cannot write " << g_shot;
}

TEST_F(PanelWidgetTest, ARefusedEditShowsTheRuntimesMessage) {
  addByKeyboard("Clock", "clock_2");
  // a value the runtime refuses (the widget cannot: use the model's edit as a script would)
  ParamEditor* rate = panel.editor()->scene()->node("clock_2")->editor("rate");
  emit rate->edited("rate", "fast");
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editor()->message().contains("refused"); }, kWaitMs));
  EXPECT_TRUE(panel.editor()->message().contains("rate")) << panel.editor()->message().toStdString();
  EXPECT_EQ(number(runtimeGraph(), "clock_2", "rate"), 10);
}

TEST_F(PanelWidgetTest, GroupIntoASubgraphOpenItWithADoubleClickGoUpAndUndo) {
  addByKeyboard("Clock", "clock_3");
  addByKeyboard("apex_nodes/Print", "print_1");
  ASSERT_TRUE(link("clock_3", "count", "print_1", "in"));
  GraphScene* scene = panel.editor()->scene();
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->connections().size() == 1; }, kWaitMs));
  scene->node("clock_3")->setSelected(true);
  scene->node("print_1")->setSelected(true);
  emit panel.editor()->groupIntoSubgraphRequested({"clock_3", "print_1"});  // what the node menu's entry sends
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("subgraph_1") && !scene->node("clock_3"); }, kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_TRUE(find(runtimeGraph(), "subgraph_1/clock_3"));

  // a double-click on it opens it: its nodes and the connection between them
  waitPlaced("subgraph_1");  // a new box is placed a moment after it shows
  NodeItem* sub = scene->node("subgraph_1");
  sub->setZValue(10);
  mouse(view, QEvent::MouseButtonDblClick, sub->scenePos() + QPointF(60, 10), Qt::LeftButton);
  ASSERT_EQ(scene->level(), "subgraph_1");
  ASSERT_TRUE(scene->node("subgraph_1/clock_3") && scene->node("subgraph_1/print_1"));
  EXPECT_EQ(scene->connections().size(), 1u);
  // one level deeper: the clock grouped again, inside; the breadcrumb names every level
  emit panel.editor()->groupIntoSubgraphRequested({"subgraph_1/clock_3"});
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("subgraph_1/subgraph_1") != nullptr; }, kWaitMs))
      << panel.editor()->message().toStdString();
  waitPlaced("subgraph_1/subgraph_1");
  NodeItem* inner = scene->node("subgraph_1/subgraph_1");
  inner->setZValue(10);
  mouse(view, QEvent::MouseButtonDblClick, inner->scenePos() + QPointF(60, 10), Qt::LeftButton);
  ASSERT_EQ(scene->level(), "subgraph_1/subgraph_1");
  EXPECT_TRUE(scene->node("subgraph_1/subgraph_1/clock_3"));
  auto crumb = [&](const QString& path) { return panel.editor()->findChild<QToolButton*>("crumb:" + path); };
  ASSERT_TRUE(crumb("") && crumb("subgraph_1") && crumb("subgraph_1/subgraph_1"));
  EXPECT_TRUE(crumb("")->isVisible());
  EXPECT_FALSE(crumb("subgraph_1/subgraph_1")->isEnabled());  // where the view is
  // each level is shown whole, wherever the view was (#48: an empty canvas until Fit, a box in a corner)
  EXPECT_EQ(outOfView(view, *scene), "");
  view->centerOn(5000, 5000);  // looked away, then up
  QTest::mouseClick(crumb("subgraph_1"), Qt::LeftButton);  // the middle one: one level up
  EXPECT_EQ(scene->level(), "subgraph_1");
  EXPECT_FALSE(crumb("subgraph_1/subgraph_1"));
  EXPECT_EQ(outOfView(view, *scene), "");
  view->centerOn(-5000, 5000);
  QTest::mouseClick(panel.editor()->findChild<QToolButton*>("up"), Qt::LeftButton);  // Up: the top
  EXPECT_EQ(scene->level(), "");
  EXPECT_EQ(outOfView(view, *scene), "");
  EXPECT_FALSE(crumb("")->isVisible());  // the bar is hidden at the top
  // each level's boxes are made anew when it is shown: the ones to click on top again (the
  // grouped box may lie under print_1's: the group took clock_3's place)
  scene->node("subgraph_1")->setZValue(10);
  mouse(view, QEvent::MouseButtonDblClick, scene->node("subgraph_1")->scenePos() + QPointF(60, 10), Qt::LeftButton);
  scene->node("subgraph_1/subgraph_1")->setZValue(10);
  mouse(view, QEvent::MouseButtonDblClick, scene->node("subgraph_1/subgraph_1")->scenePos() + QPointF(60, 10), Qt::LeftButton);
  ASSERT_EQ(scene->level(), "subgraph_1/subgraph_1");
  QTest::mouseClick(crumb(""), Qt::LeftButton);  // "graph": straight to the top
  EXPECT_EQ(scene->level(), "");
  EXPECT_TRUE(scene->node("subgraph_1"));

  // undo the inner group, then the outer one
  QTest::mouseClick(panel.editor()->findChild<QToolButton*>("undo"), Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return find(runtimeGraph(), "subgraph_1/clock_3") != nullptr; }, kWaitMs))
      << panel.editor()->message().toStdString();
  // one undo step: the nodes are back beside each other, still connected
  QTest::mouseClick(panel.editor()->findChild<QToolButton*>("undo"), Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("clock_3") && !scene->node("subgraph_1"); }, kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_TRUE(connected(runtimeGraph(), "clock_3", "count", "print_1", "in"));

  // Undo before the runtime answered the edit it undoes (its new graph may show first): it waits
  // for the answer and undoes that edit, not the one before it (it removed print_1, seen under load)
  panel.editor()->showMessage("", false);
  emit panel.editor()->groupIntoSubgraphRequested({"clock_3", "print_1"});
  QTest::mouseClick(panel.editor()->findChild<QToolButton*>("undo"), Qt::LeftButton);  // no event handled in between
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editor()->message().startsWith("und"); }, kWaitMs));
  EXPECT_TRUE(panel.editor()->message().startsWith("undid: Group into"))  // not refused, and what it undid
      << panel.editor()->message().toStdString();
  // (the message comes as the undo is sent: the runtime's graph shows it a moment later)
  EXPECT_TRUE(QTest::qWaitFor(
      [&] {
        const auto after = runtimeGraph();
        return find(after, "clock_3") && find(after, "print_1") && !find(after, "subgraph_1");
      },
      kWaitMs));
  EXPECT_TRUE(connected(runtimeGraph(), "clock_3", "count", "print_1", "in"));
}

TEST_F(PanelWidgetTest, ANodeThatCannotFireSaysWhatItWaitsFor) {
  addByKeyboard("Counter", "counter_2");  // its input is not connected: cut off from every source
  NodeItem* counter = panel.editor()->scene()->node("counter_2");
  ASSERT_TRUE(counter);
  ASSERT_TRUE(QTest::qWaitFor([&] { return !counter->waiting().isEmpty(); }, kWaitMs)) << "no waiting_for from ~status";
  EXPECT_EQ(counter->waiting().toStdString(), "cut off: input 'in' is not connected");
  EXPECT_TRUE(counter->toolTip().startsWith(counter->waiting()))
      << "first, then what it keeps: " << counter->toolTip().toStdString();
}

TEST_F(PanelWidgetTest, APlayerHasATransportBar) {
  addByKeyboard("BagReader", "bag_reader_1");
  NodeItem* player = panel.editor()->scene()->node("bag_reader_1");
  ASSERT_TRUE(player && player->transport()) << "a BagReader shows no transport bar";
  EXPECT_FALSE(panel.editor()->scene()->node("counter_2") && panel.editor()->scene()->node("counter_2")->transport());
  auto* play = player->transport()->findChild<QToolButton*>("play");
  ASSERT_TRUE(play);
  EXPECT_EQ(player->transport()->text().toStdString(), "❚❚ frame 0 · 0.00 s");  // playing (no bag yet)
  QTest::mouseClick(play, Qt::LeftButton);  // pause: the runtime's parameter changes, the bar follows
  ASSERT_TRUE(QTest::qWaitFor([&] { return param(runtimeGraph(), "bag_reader_1", "playing") == "false"; }, kWaitMs));
  ASSERT_TRUE(QTest::qWaitFor([&] { return player->transport()->text() == "▶ held · frame 0 · 0.00 s"; }, kWaitMs))
      << player->transport()->text().toStdString();
  // A bag: the frame slider spans its 40 frames; next and previous step through them.
  ASSERT_TRUE(setParameter("bag_reader_1", "file", g_bag));
  ASSERT_TRUE(setParameter("bag_reader_1", "topics", "[/camera/image_raw, /camera/points]"));
  ASSERT_TRUE(QTest::qWaitFor(
      [&] { return player->transport() && player->transport()->text() == "▶ held · frame 0 / 40 · 0.00 s"; }, kWaitMs))
      << (player->transport() ? player->transport()->text().toStdString() : "no transport bar");
  auto* bar = player->transport();
  for (const char* button : {"next", "next", "next", "previous"}) {
    QToolButton* b = nullptr;
    for (auto* t : bar->findChildren<QToolButton*>())
      if (t->toolTip().startsWith(button)) b = t;
    ASSERT_TRUE(b) << button;
    QTest::mouseClick(b, Qt::LeftButton);
  }
  ASSERT_TRUE(
      QTest::qWaitFor([&] { return player->transport()->text() == "▶ held · frame 1 / 40 · 0.10 s"; }, kWaitMs))  // 0, 1, 2, 1
      << player->transport()->text().toStdString();
  // Played to the end of a pass that does not loop: "ended", and play starts the bag again (#48:
  // a pause icon and "frame 39 / 40" said nothing of an end).
  ASSERT_TRUE(setParameter("bag_reader_1", "rate", "0.0"));
  play = player->transport()->findChild<QToolButton*>("play");  // (the bar was made anew with the bag's ports)
  QTest::mouseClick(play, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return player->transport()->text().startsWith("▶ ended · frame 39 / 40"); }, kWaitMs))
      << player->transport()->text().toStdString();
  EXPECT_EQ(param(runtimeGraph(), "bag_reader_1", "frame"), "39");
  ASSERT_TRUE(setParameter("bag_reader_1", "rate", "1.0"));  // (the pass again at its pace: 4 s, seen going)
  play = player->transport()->findChild<QToolButton*>("play");
  QTest::mouseClick(play, Qt::LeftButton);  // again, from the first frame, to the end
  ASSERT_TRUE(QTest::qWaitFor([&] { return !player->transport()->text().contains("ended"); }, kWaitMs))
      << player->transport()->text().toStdString();
  ASSERT_TRUE(QTest::qWaitFor([&] { return player->transport()->text().startsWith("▶ ended · frame 39 / 40"); }, kWaitMs))
      << player->transport()->text().toStdString();
  ASSERT_TRUE(setParameter("bag_reader_1", "playing", "false"));
  // The node's parameter box with its transport bar (docs/panel_transport.png).
  player->transport()->parentWidget()->grab().save(QString::fromStdString(g_shot).replace(".png", "_transport.png"));
}

TEST_F(PanelWidgetTest, ASliderDragIsOneUndoStepAndResetToDefaultAnother) {
  ASSERT_TRUE(addNode("apex_nodes/Clock", "drag_clock", "{rate: 10.0}"));
  GraphScene* scene = panel.editor()->scene();
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("drag_clock") != nullptr; }, kWaitMs));
  ParamEditor* rate = scene->node("drag_clock")->editor("rate");
  auto* slider = rate->findChild<QSlider*>();
  auto* spin = rate->findChild<QDoubleSpinBox*>("spin");
  ASSERT_TRUE(slider && spin);
  // 0.01 to 1000 spans five decades: the slider is logarithmic, 10 is three decades along
  EXPECT_NEAR(slider->value(), 600, 1);
  EXPECT_TRUE(rate->toolTip().contains("0.01 to 1000")) << rate->toolTip().toStdString();
  EXPECT_TRUE(rate->toolTip().contains("ticks per second")) << rate->toolTip().toStdString();
  // a drag as QSlider sees one: held down, moved over several throttle intervals, released
  slider->setSliderDown(true);
  for (int i = 1; i <= 6; ++i) {
    slider->setValue(slider->value() + 25);
    QTest::qWait(ParamEditor::kThrottleMs + 20);
  }
  slider->setSliderDown(false);
  const double dragged = spin->value();
  ASSERT_GT(dragged, 20);
  ASSERT_TRUE(QTest::qWaitFor(
      [&] { return panel.editsPending() == 0 && std::abs(number(runtimeGraph(), "drag_clock", "rate") - dragged) < 1e-3; },
      kWaitMs))
      << number(runtimeGraph(), "drag_clock", "rate") << " vs " << dragged;
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  auto* redo = panel.editor()->findChild<QToolButton*>("redo");
  QTest::mouseClick(undo, Qt::LeftButton);  // the whole drag, in one step
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(runtimeGraph(), "drag_clock", "rate") == 10; }, kWaitMs));
  EXPECT_FALSE(undo->isEnabled()) << "more than one undo step for one drag: " << undo->toolTip().toStdString();
  QTest::mouseClick(redo, Qt::LeftButton);
  ASSERT_TRUE(
      QTest::qWaitFor([&] { return std::abs(number(panel.model().graph(), "drag_clock", "rate") - dragged) < 1e-3; }, kWaitMs));

  // the parameter's menu: back to the default, one more step
  QMenu menu;
  panel.editor()->fillParamMenu(menu, "drag_clock", "rate");
  QAction* reset = action(menu, "Reset to default");
  ASSERT_TRUE(reset && reset->isEnabled());
  reset->trigger();
  ASSERT_TRUE(
      QTest::qWaitFor([&] { return number(runtimeGraph(), "drag_clock", "rate") == 10 && panel.editsPending() == 0; }, kWaitMs));
  ASSERT_TRUE(QTest::qWaitFor([&] { return spin->value() == 10.0; }, kWaitMs));
  QTest::mouseClick(undo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return std::abs(number(runtimeGraph(), "drag_clock", "rate") - dragged) < 1e-3; }, kWaitMs));
}

TEST_F(PanelWidgetTest, RenameCopyPasteAndDuplicateAndTheCopiesAreWhatIsSelected) {
  ASSERT_TRUE(addNode("apex_nodes/Clock", "src", "{rate: 50.0}"));
  ASSERT_TRUE(addNode("apex_nodes/Counter", "sink", ""));
  ASSERT_TRUE(link("src", "count", "sink", "in"));
  GraphScene* scene = panel.editor()->scene();
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("src") && scene->node("sink"); }, kWaitMs));

  // rename from the node's menu: a dialog asks the name; the connection is kept
  QMenu menu;
  panel.editor()->fillNodeMenu(menu, "src");
  ASSERT_TRUE(action(menu, "Rename"));
  action(menu, "Rename")->trigger();
  auto* ask = panel.editor()->findChild<QInputDialog*>("rename_dialog");
  ASSERT_TRUE(ask);
  EXPECT_EQ(ask->textValue(), "src");
  ask->setTextValue("ticker");
  ask->accept();
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("ticker") && !scene->node("src"); }, kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_TRUE(connected(runtimeGraph(), "ticker", "count", "sink", "in"));

  // copy both, paste: the copies are connected to each other and are the selection
  scene->clearSelection();
  scene->node("ticker")->setSelected(true);
  scene->node("sink")->setSelected(true);
  view->setFocus();
  QTest::keyClick(view, Qt::Key_C, Qt::ControlModifier);
  QTest::keyClick(view, Qt::Key_V, Qt::ControlModifier);
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("ticker_1") && scene->node("sink_1"); }, kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_TRUE(connected(runtimeGraph(), "ticker_1", "count", "sink_1", "in"));
  EXPECT_EQ(param(runtimeGraph(), "ticker_1", "rate"), "50.0");
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.model().hasPosition("sink_1") && panel.editsPending() == 0; }, kWaitMs));
  const std::string on = overlapping(*scene);  // pasted where nothing is
  EXPECT_EQ(on.find("ticker_1"), std::string::npos) << on;
  EXPECT_EQ(on.find("sink_1"), std::string::npos) << on;
  EXPECT_TRUE(scene->node("ticker_1")->isSelected() && scene->node("sink_1")->isSelected());
  EXPECT_FALSE(scene->node("ticker")->isSelected() || scene->node("sink")->isSelected());

  // Ctrl+D duplicates the selection and selects the duplicates: Delete then removes those
  QTest::keyClick(view, Qt::Key_D, Qt::ControlModifier);
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("ticker_2") && scene->node("ticker_2")->isSelected(); }, kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_FALSE(scene->node("ticker_1")->isSelected());
  QTest::keyClick(view, Qt::Key_Delete);
  ASSERT_TRUE(QTest::qWaitFor([&] { return !find(runtimeGraph(), "ticker_2") && !find(runtimeGraph(), "sink_2"); }, kWaitMs));
  EXPECT_TRUE(find(runtimeGraph(), "ticker_1") && find(runtimeGraph(), "sink_1"));

  // the rename is undone like any edit: back to its old name, still connected
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editsPending() == 0; }, kWaitMs));
  for (int i = 0; i < 4; ++i) QTest::mouseClick(undo, Qt::LeftButton);  // the two removals, Ctrl+D, the paste
  ASSERT_TRUE(QTest::qWaitFor([&] { return !find(runtimeGraph(), "ticker_1") && !find(runtimeGraph(), "ticker_2"); }, kWaitMs));
  QTest::mouseClick(undo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return find(runtimeGraph(), "src") != nullptr; }, kWaitMs));
  EXPECT_TRUE(connected(runtimeGraph(), "src", "count", "sink", "in"));
}

TEST_F(PanelWidgetTest, DropANodeOntoALinkToPutItInAndDragALinkOntoAnInputInUseToReplaceIt) {
  ASSERT_TRUE(addNode("apex_nodes/Clock", "ins_clock", "{rate: 20.0}"));
  ASSERT_TRUE(addNode("apex_nodes/Counter", "ins_count", ""));
  ASSERT_TRUE(addNode("apex_nodes/Relay", "ins_mid", ""));
  ASSERT_TRUE(link("ins_clock", "count", "ins_count", "in"));
  GraphScene* scene = panel.editor()->scene();
  auto link_item = [&]() -> ConnectionItem* {
    for (ConnectionItem* c : scene->connections())
      if (c->connection().from_node == "ins_clock" && c->connection().to_node == "ins_count") return c;
    return nullptr;
  };
  ASSERT_TRUE(QTest::qWaitFor(
      [&] {  // placed by the panel (added by a script, with no position)
        for (const char* n : {"ins_clock", "ins_count", "ins_mid"})
          if (!scene->node(n) || !panel.model().hasPosition(n)) return false;
        return link_item() && panel.editsPending() == 0;
      },
      kWaitMs));
  const auto boxes = scene->boxes();  // three nodes added at once by a script: side by side
  EXPECT_FALSE(boxes.at("ins_mid").overlaps(boxes.at("ins_count")) || boxes.at("ins_mid").overlaps(boxes.at("ins_clock")) ||
               boxes.at("ins_clock").overlaps(boxes.at("ins_count")));
  panel.editor()->fitGraph();
  NodeItem* mid = scene->node("ins_mid");
  mid->setZValue(10);
  const QPointF on_link = link_item()->path().pointAtPercent(0.5);
  const auto before = panel.model().position("ins_mid");
  drag(view, mid->scenePos() + QPointF(60, 10), on_link);  // its title onto the link
  ASSERT_TRUE(QTest::qWaitFor([&] { return connected(runtimeGraph(), "ins_mid", "out", "ins_count", "in"); }, kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_TRUE(connected(runtimeGraph(), "ins_clock", "count", "ins_mid", "in"));
  EXPECT_FALSE(connected(runtimeGraph(), "ins_clock", "count", "ins_count", "in"));
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->toolTip().contains("Insert ins_mid"); }, kWaitMs))
      << undo->toolTip().toStdString();
  QTest::mouseClick(undo, Qt::LeftButton);  // one step: the link as it was
  ASSERT_TRUE(QTest::qWaitFor([&] { return connected(runtimeGraph(), "ins_clock", "count", "ins_count", "in"); }, kWaitMs));
  EXPECT_FALSE(connected(runtimeGraph(), "ins_mid", "out", "ins_count", "in"));

  // a new link dragged onto the input in use takes its place
  ASSERT_TRUE(QTest::qWaitFor([&] { return link_item() && panel.model().position("ins_mid") == before; }, kWaitMs));
  panel.editor()->fitGraph();
  drag(view, portAt("ins_clock", "time", true), portAt("ins_count", "in", false));
  ASSERT_TRUE(QTest::qWaitFor([&] { return connected(runtimeGraph(), "ins_clock", "time", "ins_count", "in"); }, kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_FALSE(connected(runtimeGraph(), "ins_clock", "count", "ins_count", "in"));
}

TEST_F(PanelWidgetTest, FindANodeByNameOrTypeAlsoInsideASubgraph) {
  ASSERT_TRUE(addNode("apex_nodes/Clock", "needle_clock", ""));
  apex::Group group;
  group.request.nodes = {"needle_clock"}, group.request.name = "haystack";
  ASSERT_TRUE(ros::service::call("/apex/group", group) && group.response.success) << group.response.message;
  GraphScene* scene = panel.editor()->scene();
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("haystack") != nullptr; }, kWaitMs));
  auto* find = panel.editor()->findChild<QLineEdit*>("find");
  ASSERT_TRUE(find);
  QTest::keyClick(view, Qt::Key_F, Qt::ControlModifier);  // Ctrl+F: to the find field
  EXPECT_TRUE(find->hasFocus());
  QTest::keyClicks(find, "needle");
  QTest::keyClick(find, Qt::Key_Return);
  EXPECT_EQ(scene->level(), "haystack");  // its subgraph is opened
  ASSERT_TRUE(scene->node("haystack/needle_clock"));
  EXPECT_TRUE(scene->node("haystack/needle_clock")->isSelected());
  EXPECT_TRUE(panel.editor()->message().contains("(1 of 1)")) << panel.editor()->message().toStdString();
  find->clear();
  QTest::keyClicks(find, "apex_nodes/Clock");  // by type: every clock, one after the other
  QTest::keyClick(find, Qt::Key_Return);
  QTest::keyClick(find, Qt::Key_Return);
  EXPECT_TRUE(panel.editor()->message().contains("(2 of ")) << panel.editor()->message().toStdString();
  find->clear();
  QTest::keyClicks(find, "no such thing");
  QTest::keyClick(find, Qt::Key_Return);
  EXPECT_TRUE(panel.editor()->message().contains("no node's name or type contains")) << panel.editor()->message().toStdString();
}

}  // namespace
}  // namespace panel_test

using namespace panel_test;

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_panel_widget");
  g_shot = argc > 1 ? argv[1] : "panel_widget.png";
  g_bag = argc > 2 ? argv[2] : "";
  g_graphs = argc > 3 ? argv[3] : "";
  qputenv("QT_QPA_PLATFORM", "offscreen");
  QApplication app(argc, argv);
  return RUN_ALL_TESTS();
}
