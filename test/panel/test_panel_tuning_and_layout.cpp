// Panel tests, continued (after test_panel_widget.cpp, same runtime): presets,
// previews, errors on nodes, layout, box sizes, text edits, New, the optimiser.
#include "panel_test_support.hpp"

namespace panel_test {
namespace {

TEST_F(PanelWidgetTest, APresetIsSavedComparedWithNowAndRestoredInOneUndoStep) {
  ASSERT_TRUE(addNode("apex_nodes/Clock", "preset_clock", "{rate: 12.0}"));
  GraphScene* scene = panel.editor()->scene();
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("preset_clock") != nullptr; }, kWaitMs));
  // the node's menu: save its parameters under a name
  QMenu menu;
  panel.editor()->fillNodeMenu(menu, "preset_clock");
  ASSERT_TRUE(action(menu, "Save parameters as preset"));
  action(menu, "Save parameters as preset")->trigger();
  auto* ask = panel.editor()->findChild<QInputDialog*>("preset_dialog");
  ASSERT_TRUE(ask);
  ask->setTextValue("slow_clock");
  ask->accept();
  EXPECT_TRUE(QFile::exists(PanelWidget::presetFolder() + "/slow_clock.yaml"));

  ASSERT_TRUE(setParameter("preset_clock", "rate", "40"));  // then it changes
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(panel.model().graph(), "preset_clock", "rate") == 40; }, kWaitMs));
  QMenu presets;
  panel.editor()->fillPresetMenu(presets);
  QAction* entry = action(presets, "slow_clock");
  ASSERT_TRUE(entry && entry->menu());
  action(*entry->menu(), "Compare with now")->trigger();
  auto* diff = panel.editor()->findChild<QMessageBox*>("preset_diff");
  ASSERT_TRUE(diff);
  EXPECT_TRUE(diff->text().contains("preset_clock/rate: 40.0 -> 12.0")) << diff->text().toStdString();
  diff->close();
  action(*entry->menu(), "Restore")->trigger();
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(runtimeGraph(), "preset_clock", "rate") == 12; }, kWaitMs));
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->toolTip().contains("Restore preset slow_clock"); }, kWaitMs));
  QTest::mouseClick(undo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(runtimeGraph(), "preset_clock", "rate") == 40; }, kWaitMs));

  // the whole graph: Presets → "Save all parameters as..."; two nodes changed, both restored in one step
  ASSERT_TRUE(addNode("apex_nodes/Clock", "preset_other", "{rate: 7.0}"));
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("preset_other") != nullptr; }, kWaitMs));
  QMenu all;
  panel.editor()->fillPresetMenu(all);
  action(all, "Save all parameters as")->trigger();
  ask = panel.editor()->findChild<QInputDialog*>("preset_dialog");
  ASSERT_TRUE(ask);
  ask->setTextValue("whole_graph");
  ask->accept();
  ASSERT_TRUE(setParameter("preset_clock", "rate", "30") && setParameter("preset_other", "rate", "31"));
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(panel.model().graph(), "preset_other", "rate") == 31; }, kWaitMs));
  QMenu later;
  panel.editor()->fillPresetMenu(later);
  QAction* whole = action(later, "whole_graph");
  ASSERT_TRUE(whole && whole->menu());
  action(*whole->menu(), "Restore")->trigger();
  ASSERT_TRUE(QTest::qWaitFor(
      [&] { return number(runtimeGraph(), "preset_clock", "rate") == 40 && number(runtimeGraph(), "preset_other", "rate") == 7; },
      kWaitMs))
      << panel.editor()->message().toStdString();
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->toolTip().contains("Restore preset whole_graph"); }, kWaitMs));
  QTest::mouseClick(undo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor(
      [&] {
        return number(runtimeGraph(), "preset_clock", "rate") == 30 && number(runtimeGraph(), "preset_other", "rate") == 31;
      },
      kWaitMs));

  // the node's menu: every parameter of one node back to its default, one step
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(panel.model().graph(), "preset_other", "rate") == 31; }, kWaitMs));
  QMenu node_menu;
  panel.editor()->fillNodeMenu(node_menu, "preset_other");
  ASSERT_TRUE(action(node_menu, "Reset parameters to defaults"));
  action(node_menu, "Reset parameters to defaults")->trigger();
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(runtimeGraph(), "preset_other", "rate") == 10; }, kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_EQ(number(runtimeGraph(), "preset_clock", "rate"), 30);  // the other node keeps its own
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->toolTip().contains("preset_other") && panel.editsPending() == 0; }, kWaitMs))
      << undo->toolTip().toStdString();
  QTest::mouseClick(undo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(runtimeGraph(), "preset_other", "rate") == 31; }, kWaitMs));
}

TEST_F(PanelWidgetTest, PreviewsDrawThumbnailsAndSparklinesOfNodesInViewOnly) {
  ASSERT_TRUE(addNode("apex_nodes/BagReader", "thumbs_bag",
                      "{file: '" + g_bag + "', topics: [/camera/image_raw], rate: 10.0, loop: true, playing: true}"));
  GraphScene* scene = panel.editor()->scene();
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("thumbs_bag") && panel.model().hasPosition("thumbs_bag"); }, kWaitMs));
  NodeItem* bag = scene->node("thumbs_bag");
  view->resetTransform();
  view->centerOn(bag);
  auto* previews = panel.editor()->findChild<QToolButton*>("previews");
  ASSERT_TRUE(previews);
  const double closed = bag->boundingRect().height();
  QTest::mouseClick(previews, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return !scene->node("thumbs_bag")->image("camera_image_raw").isNull(); }, kWaitMs))
      << "no thumbnail; " << panel.editor()->message().toStdString();
  bag = scene->node("thumbs_bag");
  EXPECT_EQ(bag->image("camera_image_raw").width(), 160);  // as the runtime shrank it
  EXPECT_GT(bag->boundingRect().height(), closed);  // the box grew for it, and pushed those below down
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editsPending() == 0 && overlapping(*scene).empty(); }, kWaitMs))
      << overlapping(*scene);
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("thumbs_bag")->samples("stamp") >= 2; }, kWaitMs))
      << "no sparkline of the stamp";
  const apex::PortInfo* image_port = nullptr;
  for (const auto& p : bag->info().ports)
    if (p.name == "camera_image_raw") image_port = &p;
  ASSERT_TRUE(image_port);
  // what hovering the port shows: its type, the last image's real size (the bag's 480×640), the rate
  ASSERT_TRUE(
      QTest::qWaitFor([&] { return bag->portTip(*image_port).contains("last: 480×640 bgr8 image (preview 160×"); }, kWaitMs))
      << bag->portTip(*image_port).toStdString();
  const QString tip = bag->portTip(*image_port);
  EXPECT_TRUE(tip.contains("apex_nodes/Image") && tip.contains(" Hz")) << tip.toStdString();
  view->centerOn(bag);
  QApplication::processEvents();
  panel.grab().save(QString::fromStdString(g_shot).replace(".png", "_previews.png"));

  // out of view: no longer previewed (unsubscribed, so the runtime sends nothing)
  EXPECT_TRUE(panel.link().watchingPreview("thumbs_bag", "camera_image_raw"));
  view->centerOn(scene->itemsBoundingRect().bottomRight() + QPointF(3000, 3000));  // as far as the view goes: no box
  ASSERT_TRUE(QTest::qWaitFor([&] { return !panel.link().watchingPreview("thumbs_bag", "camera_image_raw"); }, kWaitMs));
  view->centerOn(scene->node("thumbs_bag"));
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.link().watchingPreview("thumbs_bag", "camera_image_raw"); }, kWaitMs));
  QTest::mouseClick(previews, Qt::LeftButton);  // off
  ASSERT_TRUE(QTest::qWaitFor([&] { return !panel.link().watchingPreview("thumbs_bag", "camera_image_raw"); }, kWaitMs));
  EXPECT_FALSE(scene->node("thumbs_bag")->previews());
}

TEST_F(PanelWidgetTest, ABagThatIsGoneIsAnErrorOnTheNodeAndStaysOneWhenPlayed) {
  namespace fs = std::filesystem;
  const std::string gone = fs::path(g_bag).parent_path() / "panel_gone.bag";
  fs::copy_file(g_bag, gone, fs::copy_options::overwrite_existing);
  ASSERT_TRUE(addNode("apex_nodes/BagReader", "gone", "{file: '" + gone + "', topics: [/camera/image_raw]}"));
  GraphScene* scene = panel.editor()->scene();
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("gone") != nullptr; }, kWaitMs));
  fs::remove(gone);
  ASSERT_TRUE(setParameter("gone", "topics", "[/camera/points]"));  // opens the file again: it is not there
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("gone")->info().state == "error"; }, kWaitMs));
  EXPECT_TRUE(scene->node("gone")->toolTip().contains("cannot open bag")) << scene->node("gone")->toolTip().toStdString();
  auto play = [&] { return scene->node("gone")->transport()->findChild<QToolButton*>("play"); };  // rebuilt with its ports
  QTest::mouseClick(play(), Qt::LeftButton);  // pause, and play again: still in error
  ASSERT_TRUE(QTest::qWaitFor([&] { return param(panel.model().graph(), "gone", "playing") == "false"; }, kWaitMs));
  QTest::mouseClick(play(), Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return param(runtimeGraph(), "gone", "playing") == "true"; }, kWaitMs));
  ASSERT_TRUE(QTest::qWaitFor([&] { return !find(runtimeGraph(), "gone")->error.empty(); }, kWaitMs));
  QTest::qWait(300);  // a firing after play would have cleared it: give it the time to
  EXPECT_EQ(find(runtimeGraph(), "gone")->state, "error");
  EXPECT_EQ(scene->node("gone")->info().state, "error");
}

/** A graph of 200 nodes with no positions, as a script or an editor would write it: a clock
 *  and a tree of relays. */
std::string writeBigGraph() {
  const std::string path = std::filesystem::path(g_bag).parent_path() / "panel_big.yaml";
  std::ofstream out(path);
  out << "apex_graph: 2\nnodes:\n  - {name: clock, type: apex_nodes/Clock, parameters: {rate: 1.0}}\n";
  for (int i = 1; i < 200; ++i) out << "  - {name: r" << i << ", type: apex_nodes/Relay}\n";
  out << "connections:\n";
  for (int i = 1; i < 200; ++i)
    out << "  - {from: " << (i < 4 ? std::string("clock/count") : "r" + std::to_string(i / 4) + "/out") << ", to: r" << i
        << "/in}\n";
  return path;
}

TEST_F(PanelWidgetTest, LoadedGraphsAreLaidOutWithNoBoxOnAnotherAndTidyIsOneUndoStep) {
  GraphScene* scene = panel.editor()->scene();
  auto laid_out = [&](std::size_t nodes) {
    const auto boxes = scene->boxes();
    if (boxes.size() != nodes || panel.editsPending() > 0) return false;
    for (const auto& [name, box] : boxes)
      if (!panel.model().hasPosition(name)) return false;
    return overlapping(*scene).empty();
  };
  // the demo graph as shipped (its positions were written by hand), then 200 nodes with none
  emit panel.editor()->loadRequested(QString::fromStdString(g_graphs + "/demo.yaml"));
  ASSERT_TRUE(QTest::qWaitFor([&] { return laid_out(5); }, kWaitMs))
      << overlapping(*scene) << panel.editor()->message().toStdString();
  emit panel.editor()->loadRequested(QString::fromStdString(writeBigGraph()));
  ASSERT_TRUE(QTest::qWaitFor([&] { return laid_out(200); }, kWaitMs))
      << scene->boxes().size() << " boxes; " << overlapping(*scene) << panel.editor()->message().toStdString();
  EXPECT_LT(scene->node("clock")->x(), scene->node("r1")->x());  // sources left, sinks right
  EXPECT_LT(scene->node("r1")->x(), scene->node("r4")->x());

  // Fit zooms out until every box is in view: names alone, large; nothing is out of view, so no minimap
  panel.editor()->fitGraph();
  EXPECT_FALSE(scene->node("r1")->detailed());
  const QRectF fitted = view->mapToScene(view->viewport()->rect()).boundingRect();
  for (const auto& [name, box] : scene->boxes())
    EXPECT_TRUE(fitted.contains(QRectF(box.x, box.y, box.width, box.height))) << name << " is out of view after Fit";
  auto* minimap = panel.editor()->findChild<QWidget*>("minimap");
  ASSERT_TRUE(minimap);
  EXPECT_FALSE(minimap->isVisible());
  // 1:1 with the clock at the view's right edge: most of the graph out of view, the minimap (in a
  // corner with no box) takes the view elsewhere
  view->resetTransform();
  scene->setZoom(1);
  view->centerOn(scene->node("clock")->sceneBoundingRect().center() - QPointF(view->viewport()->width() * 0.35, 0));
  QApplication::processEvents();
  ASSERT_TRUE(minimap->isVisible());
  const QPointF centre = view->mapToScene(view->viewport()->rect().center());
  QTest::mouseClick(minimap, Qt::LeftButton, Qt::NoModifier, QPoint(minimap->width() - 6, minimap->height() - 6));
  EXPECT_NE(view->mapToScene(view->viewport()->rect().center()), centre);
  view->resetTransform();  // zoomed out, the graph still larger than the view (the view can move)
  view->scale(0.3, 0.3);
  view->centerOn(scene->itemsBoundingRect().center());
  const QPointF at = view->viewport()->rect().center() + QPoint(150, 80);  // off the view's centre
  const QPointF under = view->mapToScene(at.toPoint());
  for (int i = 0; i < 8; ++i) {  // the plain wheel zooms in, around the cursor: detail comes back
    QWheelEvent wheel(at, view->viewport()->mapToGlobal(at.toPoint()), QPoint(), QPoint(0, 120), Qt::NoButton, Qt::NoModifier,
                      Qt::NoScrollPhase, false);
    QApplication::sendEvent(view->viewport(), &wheel);
  }
  EXPECT_TRUE(scene->node("r1")->detailed());
  const QPointF still = view->mapFromScene(under);  // what was under the cursor is still there, to a few pixels
  EXPECT_LT(QLineF(still, at).length(), 6.0)
      << "(" << at.x() << ", " << at.y() << ") moved to (" << still.x() << ", " << still.y() << ")";

  // Tidy after a node was dragged onto another: laid out again, one undo step
  scene->node("r5")->setPos(scene->node("r6")->pos());
  emit scene->nodeMoved("r5", scene->node("r6")->pos());
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editsPending() == 0 && !overlapping(*scene).empty(); }, kWaitMs));
  QTest::mouseClick(panel.editor()->findChild<QToolButton*>("tidy"), Qt::LeftButton);
  // (Tidy's moves answered first: an undo sent while they are in flight is a separate question)
  ASSERT_TRUE(QTest::qWaitFor([&] { return laid_out(200) && panel.editsPending() == 0; }, kWaitMs)) << overlapping(*scene);
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  EXPECT_TRUE(undo->toolTip().contains("Tidy")) << undo->toolTip().toStdString();
  QTest::mouseClick(undo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editsPending() == 0 && !overlapping(*scene).empty(); }, kWaitMs))
      << "after the undo of Tidy: " << panel.editor()->message().toStdString() << "; undo: " << undo->toolTip().toStdString();

  const std::string empty = std::filesystem::path(g_bag).parent_path() / "panel_empty.yaml";
  std::ofstream(empty) << "apex_graph: 2\nnodes: []\n";
  emit panel.editor()->loadRequested(QString::fromStdString(empty));  // the tests after start from nothing
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->boxes().empty(); }, kWaitMs));
}

TEST_F(PanelWidgetTest, FitsANarrowDock) {
  // rviz's docks are narrow: the buttons that do not fit go behind the tool bar's » button
  EXPECT_LE(panel.minimumSizeHint().width(), 480);
  EXPECT_LE(panel.minimumSizeHint().height(), 300) << "rviz's default layout gives a bottom dock about 300 px";
  auto* buttons = panel.editor()->findChild<QToolBar*>("buttons");
  ASSERT_TRUE(buttons);
  for (const char* b : {"pause", "step", "undo", "redo", "fit", "tidy", "balance", "previews", "presets", "trace", "new", "save",
                        "load", "whole_window"})
    EXPECT_TRUE(buttons->findChild<QToolButton*>(b)) << b << " is not in the tool bar";
}

TEST_F(PanelWidgetTest, ATextEditIsOneUndoStepAndLeavingAFieldUntouchedIsNone) {
  ASSERT_TRUE(addNode("apex_nodes/ImagePublisher", "text_pub", "{topic: apex_test/first}"));  // not an undo step
  NodeItem* box = nullptr;
  ASSERT_TRUE(
      QTest::qWaitFor([&] { return (box = panel.editor()->scene()->node("text_pub")) && box->editor("topic"); }, kWaitMs));
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  ASSERT_FALSE(undo->isEnabled()) << "the load before should have started a fresh history";
  auto* line = box->editor("topic")->findChild<QLineEdit*>();
  ASSERT_TRUE(line);
  emit line->editingFinished();  // what Qt says when the focus leaves the field: nothing was typed
  line->selectAll();
  QTest::keyClicks(line, "apex_test/second");
  QTest::keyClick(line, Qt::Key_Return);
  emit line->editingFinished();  // and the focus leaves after Return
  ASSERT_TRUE(QTest::qWaitFor(
      [&] { return param(runtimeGraph(), "text_pub", "topic") == "apex_test/second" && panel.editsPending() == 0; }, kWaitMs))
      << param(runtimeGraph(), "text_pub", "topic");
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->isEnabled(); }, kWaitMs));
  QTest::mouseClick(undo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor(
      [&] { return param(runtimeGraph(), "text_pub", "topic") == "apex_test/first" && panel.editsPending() == 0; }, kWaitMs));
  EXPECT_FALSE(undo->isEnabled()) << "more than one undo step for one text edit: " << undo->toolTip().toStdString();
  ASSERT_TRUE(QTest::qWaitFor([&] { return line->text() == "apex_test/first"; }, kWaitMs));
}

TEST_F(PanelWidgetTest, ABoxIsAsWideAsItsNameAndValuesNeed) {
  // a long name and a file path: the box widens for them, the label and the path are shown whole
  const std::string name = "bag_reader_with_a_name_longer_than_a_usual_box";
  ASSERT_TRUE(addNode("apex_nodes/BagReader", name, "{file: '" + g_bag + "', topics: [/camera/image_raw, /camera/points]}"));
  NodeItem* box = nullptr;
  ASSERT_TRUE(QTest::qWaitFor([&] { return (box = panel.editor()->scene()->node(name)) && box->editor("file"); }, kWaitMs));
  EXPECT_GT(box->width(), NodeItem::kMinWidth);
  EXPECT_LE(box->width(), NodeItem::kMaxWidth);
  QFont bold;
  bold.setBold(true);
  bold.setPointSizeF(9.5);
  EXPECT_LE(QFontMetricsF(bold).horizontalAdvance(QString::fromStdString(name)), box->width()) << "the name is cut";
  auto* path = box->editor("file")->findChild<QLineEdit*>();
  ASSERT_TRUE(path);
  ASSERT_EQ(path->text().toStdString(), g_bag);
  const int whole = path->fontMetrics().horizontalAdvance(path->text());  // up to the widest a field gets
  EXPECT_GE(path->width(), std::min(whole, 300)) << "the path is cut: " << path->width() << " of " << whole;
  for (const auto& p : box->info().parameters) {  // no parameter's name squeezed
    if (!box->editor(p.name)) continue;  // left out of the compact box (test_panel_compact.cpp)
    auto* label = box->editor(p.name)->findChild<QLabel*>();
    ASSERT_TRUE(label) << p.name;
    EXPECT_GE(label->width(), label->fontMetrics().horizontalAdvance(label->text())) << p.name << " is cut";
  }
  EXPECT_TRUE(
      QTest::qWaitFor([&] { return panel.editsPending() == 0 && overlapping(*panel.editor()->scene()).empty(); }, kWaitMs))
      << overlapping(*panel.editor()->scene());  // placed beside the others, wide as it is
  // zoomed out, the box is its name alone: a rebuild then (previews on) does not bring its editors back
  box->setZoom(0.3);
  EXPECT_FALSE(box->editor("file")->isVisible());
  box->setPreviews(true);
  EXPECT_FALSE(box->editor("file")->isVisible());
  box->setZoom(1);
  EXPECT_TRUE(box->editor("file")->isVisible());
  box->setPreviews(false);
}

TEST_F(PanelWidgetTest, TwoQuickAddsOfOneTypeGetTwoNames) {
  // Enter twice in the palette before the runtime has shown the first node: two nodes, two names
  auto adds = [&] {
    int n = 0;
    for (const auto& node : runtimeGraph().nodes) n += node.type == "apex_nodes/Add";
    return n;
  };
  const int before = adds();
  search->setFocus();
  search->selectAll();
  QTest::keyClicks(search, "apex_nodes/Add");
  QTest::keyClick(search, Qt::Key_Return);
  QTest::keyClick(search, Qt::Key_Return);
  ASSERT_TRUE(QTest::qWaitFor([&] { return adds() == before + 2; }, kWaitMs)) << panel.editor()->message().toStdString();
  EXPECT_EQ(panel.editor()->message().toStdString().find("already"), std::string::npos)
      << panel.editor()->message().toStdString();
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.model().graph().nodes.size() == runtimeGraph().nodes.size(); }, kWaitMs));
  EXPECT_TRUE(QTest::qWaitFor([&] { return overlapping(*panel.editor()->scene()).empty(); }, kWaitMs))
      << overlapping(*panel.editor()->scene());
}

TEST_F(PanelWidgetTest, NewEmptiesTheGraphAndStartsAFreshHistory) {
  GraphScene* scene = panel.editor()->scene();
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  ASSERT_TRUE(panel.editor()->findChild<QToolButton*>("new"));
  emit panel.editor()->newRequested();  // what the New button sends once the person said yes
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->boxes().empty() && runtimeGraph().nodes.empty(); }, kWaitMs));

  addByKeyboard("Clock", "clock_1");  // at once after New: an edit of the new graph, in its history
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->isEnabled(); }, kWaitMs));
  addByKeyboard("Counter", "counter_1");  // at once after the clock: beside it, not on it
  addByKeyboard("BagReader", "bag_reader_1");
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editsPending() == 0 && panel.model().hasPosition("bag_reader_1"); }, kWaitMs));
  // the clock fires and shows its timing: a box that grows pushes none onto another
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("clock_1")->firings() > 0 && panel.editsPending() == 0; }, kWaitMs));
  EXPECT_EQ(overlapping(*scene), "");

  emit panel.editor()->newRequested();
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->boxes().empty() && runtimeGraph().nodes.empty(); }, kWaitMs));
  EXPECT_FALSE(undo->isEnabled()) << "the edits before New were of another graph: " << undo->toolTip().toStdString();

  addByKeyboard("Clock", "clock_1");  // a Load, too, starts a fresh history
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->isEnabled(); }, kWaitMs));
  emit panel.editor()->loadRequested(QString::fromStdString(g_graphs + "/demo.yaml"));
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("camera_detector") && !scene->node("clock_1"); }, kWaitMs));
  EXPECT_FALSE(undo->isEnabled()) << "the edits before Load were of another graph: " << undo->toolTip().toStdString();

  emit panel.editor()->newRequested();  // the tests after start from nothing
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->boxes().empty(); }, kWaitMs));
}

TEST_F(PanelWidgetTest, ANodeShownBeforeItsPlaceIsSetStillHoldsThatPlaceForTheNextOne) {
  // A new node is add_node, then set_ui. On a loaded machine a ~graph comes between the two and
  // shows the node without its place for a moment: a node added then went onto the place the
  // first one was sent to (clean CI: "bag_reader_1 on counter_1"). That moment, made certain:
  emptyGraph();
  addByKeyboard("Clock", "clock_1");
  waitPlaced("clock_1");
  apex::ListNodeTypes types;
  ASSERT_TRUE(ros::service::call("/apex/list_node_types", types));
  const auto counter = std::find_if(types.response.types.begin(), types.response.types.end(),
                                    [](const apex::NodeTypeInfo& t) { return t.id == "apex_nodes/Counter"; });
  ASSERT_NE(counter, types.response.types.end());

  search->setFocus();
  search->selectAll();
  QTest::keyClicks(search, "Counter");
  QTest::keyClick(search, Qt::Key_Return);  // its add_node and set_ui on their way; no event handled yet
  apex::GraphState between = panel.model().graph();  // as the runtime shows it right after the add_node
  between.revision += 1;
  between.nodes.push_back(GraphModel::newNode(*counter, "counter_1"));
  emit const_cast<RuntimeLink&>(panel.link()).graphReceived(between);
  ASSERT_TRUE(panel.editor()->scene()->node("counter_1"));

  addByKeyboard("BagReader", "bag_reader_1");
  waitPlaced("counter_1");
  waitPlaced("bag_reader_1");
  EXPECT_EQ(overlapping(*panel.editor()->scene()), "");
  emptyGraph();
}

TEST_F(PanelWidgetTest, OptimiseAParameterFromItsMenuWatchTheRunAndApplyTheBestUndoably) {
  // A loop through services, as a script would make it: the bag's stamps, scaled, averaged per
  // pass; the Optimizer is what the panel adds.
  ASSERT_TRUE(addNode("apex_nodes/BagReader", "player", "{file: '" + g_bag + "', topics: [/camera/image_raw], rate: 0.0}"));
  ASSERT_TRUE(addNode("apex_nodes/Scale", "scale", "{factor: 1.0}"));
  ASSERT_TRUE(addNode("apex_nodes/SequenceMean", "mean", ""));
  ASSERT_TRUE(link("player", "stamp", "scale", "in") && link("scale", "out", "mean", "value"));
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editor()->scene()->node("scale") != nullptr; }, kWaitMs));

  // Right-click on the factor: Tune automatically with > a new Optimizer.
  QMenu menu;
  panel.editor()->fillParamMenu(menu, "scale", "factor");
  auto* with = menu.findChild<QMenu*>("optimise_with");
  ASSERT_TRUE(with && !with->actions().isEmpty());
  EXPECT_EQ(with->actions().back()->text().toStdString(), "a new Optimizer (Differential Evolution)");
  EXPECT_TRUE(with->actions().back()->toolTip().contains("fitness")) << "the menu does not say what comes next";
  with->actions().back()->trigger();
  ASSERT_TRUE(QTest::qWaitFor([&] { return connected(runtimeGraph(), "optimizer_1", "factor", "scale", "factor"); }, kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_EQ(param(runtimeGraph(), "optimizer_1", "dimensions"), "[factor]");
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editor()->scene()->node("optimizer_1") != nullptr; }, kWaitMs));

  // The factor has no range: the run says so; with one it runs, and the box draws its progress.
  ASSERT_TRUE(link("mean", "mean", "optimizer_1", "fitness"));
  ASSERT_TRUE(link("optimizer_1", "evaluate", "player", "restart") && link("optimizer_1", "evaluate", "mean", "reset"));
  ASSERT_TRUE(fireSlot("optimizer_1", "start"));
  ASSERT_TRUE(QTest::qWaitFor(
      [&] { return find(runtimeGraph(), "optimizer_1")->error.find("has no range") != std::string::npos; }, kWaitMs));
  ASSERT_TRUE(setParameter("optimizer_1", "dimensions", "[factor 0 2]"));
  ASSERT_TRUE(setParameter("optimizer_1", "budget", "6"));
  // the box's progress comes from the runtime's inspection of the Optimizer: once it flows
  for (const char* port : {"evaluations", "best_fitness"})
    ASSERT_TRUE(
        QTest::qWaitFor([&] { return panel.link().receiving(std::string("/apex/inspect/optimizer_1/") + port); }, kWaitMs));
  ASSERT_TRUE(fireSlot("optimizer_1", "start"));
  ASSERT_TRUE(QTest::qWaitFor([&] { return param(runtimeGraph(), "optimizer_1", "state").find("finished") != std::string::npos; },
                              kWaitMs))
      << param(runtimeGraph(), "optimizer_1", "state");
  NodeItem* box = panel.editor()->scene()->node("optimizer_1");
  // every evaluation counted; the curve has its points (the newest value of each topic is shown, so a
  // point may be skipped on a busy machine)
  ASSERT_TRUE(QTest::qWaitFor([&] { return box->evaluations() == 6 && box->fitnessHistory().size() >= 2; }, kWaitMs))
      << box->evaluations() << " evaluations, " << box->fitnessHistory().size() << " points; "
      << panel.editor()->message().toStdString();
  EXPECT_LE(box->fitnessHistory().size(), 6u);
  EXPECT_EQ(number(runtimeGraph(), "scale", "factor"), 1.0) << "the run gives the factor its value back";

  // Apply the best values: one edit; Undo puts the factor back.
  const double best =
      YAML::Load(YAML::Load(param(runtimeGraph(), "optimizer_1", "best_values")).as<std::string>())["factor"].as<double>();
  EXPECT_GT(best, 1.0);  // larger stamps score higher
  const std::string best_text = param(runtimeGraph(), "optimizer_1", "best_values");
  ASSERT_TRUE(QTest::qWaitFor(
      [&] {
        const auto* shown = panel.model().parameter("optimizer_1", "best_values");
        return shown && shown->value == best_text;
      },
      kWaitMs))
      << "the panel's graph never showed the final best values";
  emit panel.editor()->applyBestRequested("optimizer_1");
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(runtimeGraph(), "scale", "factor") == best; }, kWaitMs))
      << panel.editor()->message().toStdString() << "; factor " << param(runtimeGraph(), "scale", "factor") << ", best "
      << param(runtimeGraph(), "optimizer_1", "best_values");
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  ASSERT_TRUE(undo);
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->toolTip().contains("Apply the best values of optimizer_1"); }, kWaitMs))
      << undo->toolTip().toStdString();
  QTest::mouseClick(undo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(runtimeGraph(), "scale", "factor") == 1.0; }, kWaitMs));

  // Saved and loaded again: the box's progress is watched again, once (each value counted once)
  const std::size_t watches = panel.link().scalarWatches();
  const std::string file = std::filesystem::path(g_bag).parent_path() / "panel_optimise.yaml";
  emit panel.editor()->saveRequested(QString::fromStdString(file));
  ASSERT_TRUE(QTest::qWaitFor([&] { return std::filesystem::exists(file) && panel.editsPending() == 0; }, kWaitMs));
  emit panel.editor()->loadRequested(QString::fromStdString(file));
  ASSERT_TRUE(QTest::qWaitFor(
      [&] {  // the load answered, and the loaded graph shown
        return panel.editor()->message().startsWith("loaded ") && panel.editor()->scene()->node("optimizer_1") != nullptr;
      },
      kWaitMs))
      << panel.editor()->message().toStdString();
  // an edit after the load: answered once the calls before it are (the link keeps their order)
  emit panel.editor()->scene()->node("optimizer_1")->parameterEdited("optimizer_1", "budget", "7");
  ASSERT_TRUE(QTest::qWaitFor([&] { return param(runtimeGraph(), "optimizer_1", "budget") == "7" && panel.editsPending() == 0; },
                              kWaitMs))
      << panel.editor()->message().toStdString();
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.link().receiving("/apex/inspect/optimizer_1/evaluations"); }, kWaitMs));
  EXPECT_EQ(panel.link().scalarWatches(), watches) << "the watches of the graph before are still there, or watched twice";
}

}  // namespace
}  // namespace panel_test
