// The panel widget (what GraphPanel shows in rviz) driven by simulated mouse and
// keyboard input against a real runtime, offscreen. Each step is checked in the
// runtime's own graph (~get_graph), not in the panel. A screenshot is written.
//   test_panel_widget SCREENSHOT.png DEMO_BAG GRAPHS_FOLDER
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <QApplication>
#include <QElapsedTimer>
#include <QTimer>
#include <QLabel>
#include <QDoubleSpinBox>
#include <QGraphicsView>
#include <QLineEdit>
#include <QMouseEvent>
#include <QWheelEvent>
#include <QTest>
#include <QToolBar>
#include <QToolButton>

#include <QInputDialog>
#include <QMenu>
#include <QMessageBox>
#include <QFile>
#include <QSlider>

#include <filesystem>
#include <fstream>

#include <apex/AddNode.h>
#include <apex/Connect.h>
#include <apex/FireSlot.h>
#include <apex/GetGraph.h>
#include <apex/ListNodeTypes.h>
#include <apex/Group.h>
#include <apex/SetParameter.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <yaml-cpp/yaml.h>

#include "apex_rviz_plugin/panel_widget.hpp"
#include "apex_rviz_plugin/param_editor.hpp"
#include "apex_rviz_plugin/transport_bar.hpp"

using namespace apex_rviz_plugin;

namespace {

std::string g_shot, g_bag, g_graphs;

/** Sets a parameter through the runtime's service, as a script would. */
bool setParameter(const std::string& node, const std::string& param, const std::string& value) {
  apex::SetParameter srv;
  srv.request.node = node, srv.request.parameter = param, srv.request.value = value;
  return ros::service::call("/apex/set_parameter", srv) && srv.response.success;
}
constexpr int kWaitMs = 20000;

bool addNode(const std::string& type, const std::string& name, const std::string& params) {
  apex::AddNode srv;
  srv.request.type = type, srv.request.name = name, srv.request.parameters = params;
  return ros::service::call("/apex/add_node", srv) && srv.response.success;
}

bool link(const std::string& a, const std::string& ap, const std::string& b, const std::string& bp) {
  apex::Connect srv;
  srv.request.from_node = a, srv.request.from_port = ap, srv.request.to_node = b, srv.request.to_port = bp;
  return ros::service::call("/apex/connect", srv) && srv.response.success;
}

bool fireSlot(const std::string& node, const std::string& slot) {
  apex::FireSlot srv;
  srv.request.node = node, srv.request.slot = slot;
  return ros::service::call("/apex/fire_slot", srv) && srv.response.success;
}

apex::GraphState runtimeGraph(const std::string& ns = "/apex") {
  apex::GetGraph srv;
  EXPECT_TRUE(ros::service::call(ns + "/get_graph", srv)) << ns << "/get_graph did not answer";
  return srv.response.graph;
}

const apex::NodeInfo* find(const apex::GraphState& g, const std::string& name) {
  for (const auto& n : g.nodes) if (n.name == name) return &n;
  return nullptr;
}

std::string param(const apex::GraphState& g, const std::string& node, const std::string& name) {
  if (const auto* n = find(g, node))
    for (const auto& p : n->parameters) if (p.name == name) return p.value;
  return "";
}

double number(const apex::GraphState& g, const std::string& node, const std::string& name) {
  const std::string v = param(g, node, name);
  return v.empty() ? -1 : std::stod(v);
}

bool connected(const apex::GraphState& g, const std::string& a, const std::string& ap, const std::string& b,
               const std::string& bp) {
  for (const auto& c : g.connections)
    if (c.from_node == a && c.from_port == ap && c.to_node == b && c.to_port == bp) return true;
  return false;
}

/** The boxes shown that lie on each other, as text; "" if none. */
std::string boxText(const Box& b) {
  return "(" + std::to_string(int(b.x)) + ", " + std::to_string(int(b.y)) + ", " + std::to_string(int(b.width)) + " x " +
         std::to_string(int(b.height)) + ")";
}

std::string overlapping(const GraphScene& scene) {
  const auto boxes = scene.boxes();
  std::string out;
  for (auto a = boxes.begin(); a != boxes.end(); ++a)
    for (auto b = std::next(a); b != boxes.end(); ++b)
      if (a->second.overlaps(b->second)) out += a->first + " on " + b->first + " " + boxText(a->second) + " " + boxText(b->second) + "; ";
  return out;
}

/** A mouse event as the window system would deliver it to the view. */
void mouse(QGraphicsView* view, QEvent::Type type, QPointF scene_pos, Qt::MouseButtons held) {
  const QPoint at = view->mapFromScene(scene_pos);
  QMouseEvent e(type, at, view->viewport()->mapToGlobal(at), type == QEvent::MouseMove ? Qt::NoButton : Qt::LeftButton,
                held, Qt::NoModifier);
  QApplication::sendEvent(view->viewport(), &e);
}

/** Presses at `from`, moves in steps, releases at `to`: a drag. */
void drag(QGraphicsView* view, QPointF from, QPointF to) {
  mouse(view, QEvent::MouseButtonPress, from, Qt::LeftButton);
  for (int i = 1; i <= 10; ++i) mouse(view, QEvent::MouseMove, from + (to - from) * (i / 10.0), Qt::LeftButton);
  mouse(view, QEvent::MouseButtonRelease, to, Qt::NoButton);
}

class PanelWidgetTest : public ::testing::Test {
 protected:
  void SetUp() override {
    panel.resize(1400, 900);
    panel.show();
    panel.setNamespace("/apex");
    ASSERT_TRUE(QTest::qWaitFor([&] { return panel.link().connected() && panel.nodeTypeCount() > 0; }, kWaitMs))
        << "the panel did not connect to /apex or list its node types";
    view = panel.editor()->view();
    search = panel.editor()->findChild<QLineEdit*>("search");
    ASSERT_TRUE(search);
  }

  /** Types into the palette's search field and presses Enter: adds the first match. */
  std::string addByKeyboard(const QString& type, const std::string& expected_name) {
    search->setFocus();
    search->selectAll();
    QTest::keyClicks(search, type);
    QTest::keyClick(search, Qt::Key_Return);
    EXPECT_TRUE(QTest::qWaitFor([&] { return panel.editor()->scene()->node(expected_name) != nullptr; }, kWaitMs))
        << expected_name << " not shown; message: " << panel.editor()->message().toStdString();
    return expected_name;
  }

  QPointF portAt(const std::string& node, const std::string& port, bool source) {
    NodeItem* n = panel.editor()->scene()->node(node);
    PortItem* p = n ? n->port(port, source) : nullptr;
    EXPECT_TRUE(p) << node << "/" << port;
    return p ? p->scenePos() : QPointF();
  }

  PanelWidget panel;
  QGraphicsView* view = nullptr;
  QLineEdit* search = nullptr;
};

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
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->toolTip().contains("Set clock_1/rate"); }, kWaitMs)) << undo->toolTip().toStdString();
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
  NodeItem* inner = scene->node("subgraph_1/subgraph_1");
  inner->setZValue(10);
  mouse(view, QEvent::MouseButtonDblClick, inner->scenePos() + QPointF(60, 10), Qt::LeftButton);
  ASSERT_EQ(scene->level(), "subgraph_1/subgraph_1");
  EXPECT_TRUE(scene->node("subgraph_1/subgraph_1/clock_3"));
  auto crumb = [&](const QString& path) { return panel.editor()->findChild<QToolButton*>("crumb:" + path); };
  ASSERT_TRUE(crumb("") && crumb("subgraph_1") && crumb("subgraph_1/subgraph_1"));
  EXPECT_TRUE(crumb("")->isVisible());
  EXPECT_FALSE(crumb("subgraph_1/subgraph_1")->isEnabled());  // where the view is
  QTest::mouseClick(crumb("subgraph_1"), Qt::LeftButton);  // the middle one: one level up
  EXPECT_EQ(scene->level(), "subgraph_1");
  EXPECT_FALSE(crumb("subgraph_1/subgraph_1"));
  QTest::mouseClick(panel.editor()->findChild<QToolButton*>("up"), Qt::LeftButton);  // Up: the top
  EXPECT_EQ(scene->level(), "");
  EXPECT_FALSE(crumb("")->isVisible());  // the bar is hidden at the top
  mouse(view, QEvent::MouseButtonDblClick, scene->node("subgraph_1")->scenePos() + QPointF(60, 10), Qt::LeftButton);
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
}

TEST_F(PanelWidgetTest, ANodeThatCannotFireSaysWhatItWaitsFor) {
  addByKeyboard("Counter", "counter_2");  // its input is not connected: cut off from every source
  NodeItem* counter = panel.editor()->scene()->node("counter_2");
  ASSERT_TRUE(counter);
  ASSERT_TRUE(QTest::qWaitFor([&] { return !counter->waiting().isEmpty(); }, kWaitMs)) << "no waiting_for from ~status";
  EXPECT_EQ(counter->waiting().toStdString(), "cut off: input 'in' is not connected");
  EXPECT_EQ(counter->toolTip(), counter->waiting());
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
  ASSERT_TRUE(QTest::qWaitFor([&] { return player->transport() && player->transport()->text() == "▶ held · frame 0 / 40 · 0.00 s"; }, kWaitMs))
      << (player->transport() ? player->transport()->text().toStdString() : "no transport bar");
  auto* bar = player->transport();
  for (const char* button : {"next", "next", "next", "previous"}) {
    QToolButton* b = nullptr;
    for (auto* t : bar->findChildren<QToolButton*>()) if (t->toolTip().startsWith(button)) b = t;
    ASSERT_TRUE(b) << button;
    QTest::mouseClick(b, Qt::LeftButton);
  }
  ASSERT_TRUE(QTest::qWaitFor([&] { return player->transport()->text() == "▶ held · frame 1 / 40 · 0.10 s"; }, kWaitMs))  // 0, 1, 2, 1
      << player->transport()->text().toStdString();
  // The node's parameter box with its transport bar (docs/panel_transport.png).
  player->transport()->parentWidget()->grab().save(QString::fromStdString(g_shot).replace(".png", "_transport.png"));
}

/** The action of a menu whose text starts with `text`, or nullptr. */
QAction* action(const QMenu& menu, const QString& text) {
  for (QAction* a : menu.actions()) if (a->text().startsWith(text)) return a;
  return nullptr;
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
  ASSERT_TRUE(QTest::qWaitFor([&] {
    return panel.editsPending() == 0 && std::abs(number(runtimeGraph(), "drag_clock", "rate") - dragged) < 1e-3;
  }, kWaitMs)) << number(runtimeGraph(), "drag_clock", "rate") << " vs " << dragged;
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  auto* redo = panel.editor()->findChild<QToolButton*>("redo");
  QTest::mouseClick(undo, Qt::LeftButton);  // the whole drag, in one step
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(runtimeGraph(), "drag_clock", "rate") == 10; }, kWaitMs));
  EXPECT_FALSE(undo->isEnabled()) << "more than one undo step for one drag: " << undo->toolTip().toStdString();
  QTest::mouseClick(redo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return std::abs(number(panel.model().graph(), "drag_clock", "rate") - dragged) < 1e-3; }, kWaitMs));

  // the parameter's menu: back to the default, one more step
  QMenu menu;
  panel.editor()->fillParamMenu(menu, "drag_clock", "rate");
  QAction* reset = action(menu, "Reset to default");
  ASSERT_TRUE(reset && reset->isEnabled());
  reset->trigger();
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(runtimeGraph(), "drag_clock", "rate") == 10 && panel.editsPending() == 0; }, kWaitMs));
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
  ASSERT_TRUE(QTest::qWaitFor([&] {  // placed by the panel (added by a script, with no position)
    for (const char* n : {"ins_clock", "ins_count", "ins_mid"})
      if (!scene->node(n) || !panel.model().hasPosition(n)) return false;
    return link_item() && panel.editsPending() == 0;
  }, kWaitMs));
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
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->toolTip().contains("Insert ins_mid"); }, kWaitMs)) << undo->toolTip().toStdString();
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
  ASSERT_TRUE(QTest::qWaitFor([&] {
    return number(runtimeGraph(), "preset_clock", "rate") == 40 && number(runtimeGraph(), "preset_other", "rate") == 7;
  }, kWaitMs)) << panel.editor()->message().toStdString();
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->toolTip().contains("Restore preset whole_graph"); }, kWaitMs));
  QTest::mouseClick(undo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] {
    return number(runtimeGraph(), "preset_clock", "rate") == 30 && number(runtimeGraph(), "preset_other", "rate") == 31;
  }, kWaitMs));

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
  for (const auto& p : bag->info().ports) if (p.name == "camera_image_raw") image_port = &p;
  ASSERT_TRUE(image_port);
  // what hovering the port shows: its type, the last image's real size (the bag's 480×640), the rate
  ASSERT_TRUE(QTest::qWaitFor([&] { return bag->portTip(*image_port).contains("last: 480×640 bgr8 image (preview 160×"); }, kWaitMs))
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
    out << "  - {from: " << (i < 4 ? std::string("clock/count") : "r" + std::to_string(i / 4) + "/out") << ", to: r" << i << "/in}\n";
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

  // zoomed out to see them all: names alone, large; the minimap takes the view elsewhere
  panel.editor()->fitGraph();
  EXPECT_FALSE(scene->node("r1")->detailed());
  auto* minimap = panel.editor()->findChild<QWidget*>("minimap");
  ASSERT_TRUE(minimap && minimap->isVisible());
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
  EXPECT_LT(QLineF(still, at).length(), 6.0) << "(" << at.x() << ", " << at.y() << ") moved to (" << still.x() << ", "
                                              << still.y() << ")";

  // Tidy after a node was dragged onto another: laid out again, one undo step
  scene->node("r5")->setPos(scene->node("r6")->pos());
  emit scene->nodeMoved("r5", scene->node("r6")->pos());
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editsPending() == 0 && !overlapping(*scene).empty(); }, kWaitMs));
  QTest::mouseClick(panel.editor()->findChild<QToolButton*>("tidy"), Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return laid_out(200); }, kWaitMs)) << overlapping(*scene);
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  EXPECT_TRUE(undo->toolTip().contains("Tidy")) << undo->toolTip().toStdString();
  QTest::mouseClick(undo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editsPending() == 0 && !overlapping(*scene).empty(); }, kWaitMs));

  const std::string empty = std::filesystem::path(g_bag).parent_path() / "panel_empty.yaml";
  std::ofstream(empty) << "apex_graph: 2\nnodes: []\n";
  emit panel.editor()->loadRequested(QString::fromStdString(empty));  // the tests after start from nothing
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->boxes().empty(); }, kWaitMs));
}

TEST_F(PanelWidgetTest, FitsANarrowDock) {
  // rviz's docks are narrow: the buttons that do not fit go behind the tool bar's » button
  EXPECT_LE(panel.minimumSizeHint().width(), 480);
  auto* buttons = panel.editor()->findChild<QToolBar*>("buttons");
  ASSERT_TRUE(buttons);
  for (const char* b : {"pause", "step", "undo", "redo", "fit", "tidy", "previews", "presets", "new", "save", "load"})
    EXPECT_TRUE(buttons->findChild<QToolButton*>(b)) << b << " is not in the tool bar";
}

TEST_F(PanelWidgetTest, ATextEditIsOneUndoStepAndLeavingAFieldUntouchedIsNone) {
  ASSERT_TRUE(addNode("apex_nodes/ImagePublisher", "text_pub", "{topic: apex_test/first}"));  // not an undo step
  NodeItem* box = nullptr;
  ASSERT_TRUE(QTest::qWaitFor([&] { return (box = panel.editor()->scene()->node("text_pub")) && box->editor("topic"); }, kWaitMs));
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  ASSERT_FALSE(undo->isEnabled()) << "the load before should have started a fresh history";
  auto* line = box->editor("topic")->findChild<QLineEdit*>();
  ASSERT_TRUE(line);
  emit line->editingFinished();  // what Qt says when the focus leaves the field: nothing was typed
  line->selectAll();
  QTest::keyClicks(line, "apex_test/second");
  QTest::keyClick(line, Qt::Key_Return);
  emit line->editingFinished();  // and the focus leaves after Return
  ASSERT_TRUE(QTest::qWaitFor([&] { return param(runtimeGraph(), "text_pub", "topic") == "apex_test/second" && panel.editsPending() == 0; }, kWaitMs))
      << param(runtimeGraph(), "text_pub", "topic");
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->isEnabled(); }, kWaitMs));
  QTest::mouseClick(undo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return param(runtimeGraph(), "text_pub", "topic") == "apex_test/first" && panel.editsPending() == 0; }, kWaitMs));
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
  EXPECT_GE(path->width(), path->fontMetrics().horizontalAdvance(path->text())) << "the path is cut: " << path->width();
  for (const auto& p : box->info().parameters) {  // no parameter's name squeezed
    auto* label = box->editor(p.name)->findChild<QLabel*>();
    ASSERT_TRUE(label) << p.name;
    EXPECT_GE(label->width(), label->fontMetrics().horizontalAdvance(label->text())) << p.name << " is cut";
  }
  EXPECT_TRUE(QTest::qWaitFor([&] { return panel.editsPending() == 0 && overlapping(*panel.editor()->scene()).empty(); }, kWaitMs))
      << overlapping(*panel.editor()->scene());  // placed beside the others, wide as it is
  // zoomed out, the box is its name alone: a rebuild then (previews on) does not bring its editors back
  box->setDetail(false);
  EXPECT_FALSE(box->editor("file")->isVisible());
  box->setPreviews(true);
  EXPECT_FALSE(box->editor("file")->isVisible());
  box->setDetail(true);
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
  EXPECT_EQ(panel.editor()->message().toStdString().find("already"), std::string::npos) << panel.editor()->message().toStdString();
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

TEST_F(PanelWidgetTest, OptimiseAParameterFromItsMenuWatchTheRunAndApplyTheBestUndoably) {
  // A loop through services, as a script would make it: the bag's stamps, scaled, averaged per
  // pass; the Optimizer is what the panel adds.
  ASSERT_TRUE(addNode("apex_nodes/BagReader", "player", "{file: '" + g_bag + "', topics: [/camera/image_raw], rate: 0.0}"));
  ASSERT_TRUE(addNode("apex_nodes/Scale", "scale", "{factor: 1.0}"));
  ASSERT_TRUE(addNode("apex_nodes/SequenceMean", "mean", ""));
  ASSERT_TRUE(link("player", "stamp", "scale", "in") && link("scale", "out", "mean", "value"));
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editor()->scene()->node("scale") != nullptr; }, kWaitMs));

  // Right-click on the factor: Optimise with > New Optimizer.
  QMenu menu;
  panel.editor()->fillParamMenu(menu, "scale", "factor");
  auto* with = menu.findChild<QMenu*>("optimise_with");
  ASSERT_TRUE(with && !with->actions().isEmpty());
  EXPECT_EQ(with->actions().back()->text().toStdString(), "New Optimizer");
  with->actions().back()->trigger();
  ASSERT_TRUE(QTest::qWaitFor([&] { return connected(runtimeGraph(), "optimizer_1", "factor", "scale", "factor"); }, kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_EQ(param(runtimeGraph(), "optimizer_1", "dimensions"), "[factor]");
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editor()->scene()->node("optimizer_1") != nullptr; }, kWaitMs));

  // The factor has no range: the run says so; with one it runs, and the box draws its progress.
  ASSERT_TRUE(link("mean", "mean", "optimizer_1", "fitness"));
  ASSERT_TRUE(link("optimizer_1", "evaluate", "player", "restart") && link("optimizer_1", "evaluate", "mean", "reset"));
  ASSERT_TRUE(fireSlot("optimizer_1", "start"));
  ASSERT_TRUE(QTest::qWaitFor([&] { return find(runtimeGraph(), "optimizer_1")->error.find("has no range") != std::string::npos; }, kWaitMs));
  ASSERT_TRUE(setParameter("optimizer_1", "dimensions", "[factor 0 2]"));
  ASSERT_TRUE(setParameter("optimizer_1", "budget", "6"));
  // the box's progress comes from the runtime's inspection of the Optimizer: once it flows
  for (const char* port : {"evaluations", "best_fitness"})
    ASSERT_TRUE(QTest::qWaitFor([&] { return panel.link().receiving(std::string("/apex/inspect/optimizer_1/") + port); }, kWaitMs));
  ASSERT_TRUE(fireSlot("optimizer_1", "start"));
  ASSERT_TRUE(QTest::qWaitFor([&] { return param(runtimeGraph(), "optimizer_1", "state").find("finished") != std::string::npos; }, kWaitMs))
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
  const double best = YAML::Load(YAML::Load(param(runtimeGraph(), "optimizer_1", "best_values")).as<std::string>())["factor"].as<double>();
  EXPECT_GT(best, 1.0);  // larger stamps score higher
  const std::string best_text = param(runtimeGraph(), "optimizer_1", "best_values");
  ASSERT_TRUE(QTest::qWaitFor([&] {
    const auto* shown = panel.model().parameter("optimizer_1", "best_values");
    return shown && shown->value == best_text;
  }, kWaitMs)) << "the panel's graph never showed the final best values";
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
  ASSERT_TRUE(QTest::qWaitFor([&] {  // the load answered, and the loaded graph shown
    return panel.editor()->message().startsWith("loaded ") && panel.editor()->scene()->node("optimizer_1") != nullptr;
  }, kWaitMs)) << panel.editor()->message().toStdString();
  // an edit after the load: answered once the calls before it are (the link keeps their order)
  emit panel.editor()->scene()->node("optimizer_1")->parameterEdited("optimizer_1", "budget", "7");
  ASSERT_TRUE(QTest::qWaitFor([&] { return param(runtimeGraph(), "optimizer_1", "budget") == "7" && panel.editsPending() == 0; }, kWaitMs))
      << panel.editor()->message().toStdString();
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.link().receiving("/apex/inspect/optimizer_1/evaluations"); }, kWaitMs));
  EXPECT_EQ(panel.link().scalarWatches(), watches) << "the watches of the graph before are still there, or watched twice";
}

/** A runtime of its own, in another namespace, that a test can stop and start again. */
class OwnRuntime {
 public:
  explicit OwnRuntime(const char* name) : name_(name) {}
  ~OwnRuntime() { stop(); }
  void start() {
    pid_ = fork();
    if (pid_ == 0) {
      const std::string arg = std::string("__name:=") + name_;
      execlp("rosrun", "rosrun", "apex", "apex_runtime_node", arg.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
  }
  void stop() {
    if (pid_ <= 0) return;
    kill(pid_, SIGINT);
    waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }

 private:
  const char* name_;
  pid_t pid_ = -1;
};

TEST(PanelWidgetReconnect, SaysWhenTheRuntimeIsGoneAndPicksItUpWhenItIsBack) {
  PanelWidget panel;
  panel.show();
  auto* field = panel.editor()->findChild<QLineEdit*>("namespace");
  auto* status = panel.editor()->findChild<QLabel*>("connection");
  ASSERT_TRUE(field && status);
  // a name that is not a ROS namespace is refused with the reason; the panel stays where it was
  panel.setNamespace("/apex");
  field->setFocus();
  field->selectAll();
  QTest::keyClicks(field, "not a namespace!");
  QTest::keyClick(field, Qt::Key_Return);
  EXPECT_EQ(panel.ns().toStdString(), "/apex");
  EXPECT_TRUE(status->text().contains("not a valid namespace")) << status->text().toStdString();

  OwnRuntime runtime("apex_b");
  runtime.start();
  panel.setNamespace("/apex_b");
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.link().connected() && panel.model().hasGraph(); }, kWaitMs))
      << status->text().toStdString();
  runtime.stop();
  ASSERT_TRUE(QTest::qWaitFor([&] { return !panel.link().connected(); }, kWaitMs));
  EXPECT_TRUE(status->text().contains("gone")) << status->text().toStdString();
  EXPECT_FALSE(panel.model().hasGraph());
  runtime.start();
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.link().connected() && panel.model().hasGraph(); }, kWaitMs))
      << status->text().toStdString();
  EXPECT_GT(panel.nodeTypeCount(), 0);
}

/** A runtime that answers every edit after a second and a half: only ~graph, list_node_types
 *  and set_parameter, served on a thread of its own. */
class SlowRuntime {
 public:
  SlowRuntime() : nh_("/slow") {
    nh_.setCallbackQueue(&queue_);
    graph_ = nh_.advertise<apex::GraphState>("graph", 1, true);
    apex::GraphState g;
    g.revision = 1;
    apex::NodeInfo n;
    n.name = "n", n.type = "apex_nodes/Scale", n.enabled = true, n.state = "ok";
    apex::ParamInfo p;
    p.name = "factor", p.kind = "double range", p.type = "double", p.value = "1.0", p.default_value = "1.0";
    p.min = 0, p.max = 10, p.step = 0.1;
    n.parameters = {p};
    g.nodes = {n};
    graph_.publish(g);
    types_ = nh_.advertiseService<apex::ListNodeTypes::Request, apex::ListNodeTypes::Response>(
        "list_node_types", [](auto&, auto& res) { return res.success = true; });
    set_ = nh_.advertiseService<apex::SetParameter::Request, apex::SetParameter::Response>("set_parameter", [this](auto&, auto& res) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1500));
      ++calls;
      res.success = true;
      return true;
    });
    spinner_.start();
  }
  std::atomic<int> calls{0};

 private:
  ros::NodeHandle nh_;
  ros::CallbackQueue queue_;
  ros::AsyncSpinner spinner_{1, &queue_};
  ros::Publisher graph_;
  ros::ServiceServer types_, set_;
};

TEST(PanelWidgetSlowRuntime, TheGuiThreadNeverWaitsAndSaysTheRuntimeIsSlow) {
  SlowRuntime slow;
  PanelWidget panel;
  panel.show();
  panel.setNamespace("/slow");
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.link().connected() && panel.editor()->scene()->node("n"); }, kWaitMs));
  // the GUI thread's event loop, ticking every 5 ms: the longest gap between ticks is how long it waited
  QElapsedTimer clock;
  clock.start();
  qint64 last = 0, longest = 0;
  QTimer ticker;
  QObject::connect(&ticker, &QTimer::timeout, [&] {
    longest = std::max(longest, clock.elapsed() - last);
    last = clock.elapsed();
  });
  ticker.start(5);
  ParamEditor* factor = panel.editor()->scene()->node("n")->editor("factor");
  for (const char* v : {"2", "3", "4"}) emit factor->edited("factor", v);  // each answered 1.5 s later
  auto* status = panel.editor()->findChild<QLabel*>("connection");
  ASSERT_TRUE(QTest::qWaitFor([&] { return status->text().contains("no answer for"); }, kWaitMs)) << status->text().toStdString();
  ASSERT_TRUE(QTest::qWaitFor([&] { return slow.calls == 3 && panel.editsPending() == 0; }, kWaitMs));
  ASSERT_TRUE(QTest::qWaitFor([&] { return !status->text().contains("no answer"); }, kWaitMs)) << status->text().toStdString();
  ticker.stop();
  EXPECT_LT(longest, 50) << "the GUI thread waited " << longest << " ms";
}

TEST(PanelWidgetTwoRuntimes, CopyInOnePasteInAnotherAndEachStartsItsOwnHistory) {
  PanelWidget panel;
  panel.resize(1400, 900);
  panel.show();
  panel.setNamespace("/apex");
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.link().connected() && panel.model().hasGraph(); }, kWaitMs));
  ASSERT_TRUE(addNode("apex_nodes/Clock", "xfer_src", "{rate: 21.0}") && addNode("apex_nodes/Counter", "xfer_sink", ""));
  ASSERT_TRUE(link("xfer_src", "count", "xfer_sink", "in"));
  GraphScene* scene = panel.editor()->scene();
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("xfer_src") && scene->node("xfer_sink"); }, kWaitMs));
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  emit scene->node("xfer_src")->editor("rate")->edited("rate", "22");  // an edit of /apex, in its history
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(runtimeGraph(), "xfer_src", "rate") == 22 && undo->isEnabled(); }, kWaitMs));
  ASSERT_TRUE(QTest::qWaitFor([&] { return number(panel.model().graph(), "xfer_src", "rate") == 22; }, kWaitMs));
  scene->node("xfer_src")->setSelected(true);
  scene->node("xfer_sink")->setSelected(true);
  QGraphicsView* view = panel.editor()->view();
  view->setFocus();
  QTest::keyClick(view, Qt::Key_C, Qt::ControlModifier);

  OwnRuntime other("apex_c");  // another runtime: a fresh history, and the copies go there
  other.start();
  panel.setNamespace("/apex_c");
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.link().connected() && panel.model().hasGraph(); }, kWaitMs));
  EXPECT_FALSE(undo->isEnabled()) << "the history of /apex goes on in /apex_c: " << undo->toolTip().toStdString();
  view->setFocus();
  QTest::keyClick(view, Qt::Key_V, Qt::ControlModifier);
  ASSERT_TRUE(QTest::qWaitFor([&] { return find(runtimeGraph("/apex_c"), "xfer_sink") != nullptr; }, kWaitMs))
      << panel.editor()->message().toStdString();
  const apex::GraphState there = runtimeGraph("/apex_c");
  EXPECT_TRUE(connected(there, "xfer_src", "count", "xfer_sink", "in"));
  EXPECT_EQ(param(there, "xfer_src", "rate"), "22.0");
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->isEnabled() && panel.editsPending() == 0; }, kWaitMs));
  QTest::mouseClick(undo, Qt::LeftButton);  // the paste, undone in /apex_c alone
  ASSERT_TRUE(QTest::qWaitFor([&] { return !find(runtimeGraph("/apex_c"), "xfer_src"); }, kWaitMs));
  EXPECT_TRUE(find(runtimeGraph(), "xfer_src") && find(runtimeGraph(), "xfer_sink"));
}

/** A runtime whose set_parameter never answers until released (a runtime that hangs). */
class HungRuntime {
 public:
  HungRuntime() : nh_("/hung") {
    nh_.setCallbackQueue(&queue_);
    graph_ = nh_.advertise<apex::GraphState>("graph", 1, true);
    apex::GraphState g;
    g.revision = 1;
    apex::NodeInfo n;
    n.name = "n", n.type = "apex_nodes/Scale", n.enabled = true, n.state = "ok";
    apex::ParamInfo p;
    p.name = "factor", p.kind = "double range", p.type = "double", p.value = "1.0", p.default_value = "1.0";
    p.min = 0, p.max = 10, p.step = 0.1;
    n.parameters = {p};
    g.nodes = {n};
    graph_.publish(g);
    types_ = nh_.advertiseService<apex::ListNodeTypes::Request, apex::ListNodeTypes::Response>(
        "list_node_types", [](auto&, auto& res) { return res.success = true; });
    set_ = nh_.advertiseService<apex::SetParameter::Request, apex::SetParameter::Response>("set_parameter", [this](auto&, auto& res) {
      std::unique_lock<std::mutex> lock(mutex_);
      ++called_;
      released_cv_.wait(lock, [this] { return released_; });
      return res.success = true;
    });
    spinner_.start();
  }
  ~HungRuntime() { release(); }
  void release() {
    std::lock_guard<std::mutex> lock(mutex_);
    released_ = true;
    released_cv_.notify_all();
  }
  int called() {
    std::lock_guard<std::mutex> lock(mutex_);
    return called_;
  }

 private:
  ros::NodeHandle nh_;
  ros::CallbackQueue queue_;
  ros::AsyncSpinner spinner_{2, &queue_};
  ros::Publisher graph_;
  ros::ServiceServer types_, set_;
  std::mutex mutex_;
  std::condition_variable released_cv_;
  bool released_ = false;
  int called_ = 0;
};

TEST(PanelWidgetHungRuntime, AnotherRuntimeIsServedAndClosingThePanelDoesNotWait) {
  HungRuntime hung;
  auto panel = std::make_unique<PanelWidget>();
  panel->show();
  panel->setNamespace("/hung");
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel->link().connected() && panel->editor()->scene()->node("n"); }, kWaitMs));
  emit panel->editor()->scene()->node("n")->editor("factor")->edited("factor", "2");  // never answered
  ASSERT_TRUE(QTest::qWaitFor([&] { return hung.called() == 1; }, kWaitMs));
  // the user turns to another runtime: it is listed and shown, its calls do not wait behind the hung one
  panel->setNamespace("/apex");
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel->link().connected() && panel->nodeTypeCount() > 0; }, kWaitMs))
      << "the calls to /apex wait behind the one to /hung";
  auto* status = panel->editor()->findChild<QLabel*>("connection");
  EXPECT_FALSE(status->text().contains("no answer")) << status->text().toStdString();
  // rviz closes with a call still unanswered: the panel goes at once
  panel->setNamespace("/hung");
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel->link().connected() && panel->editor()->scene()->node("n"); }, kWaitMs));
  emit panel->editor()->scene()->node("n")->editor("factor")->edited("factor", "3");
  ASSERT_TRUE(QTest::qWaitFor([&] { return hung.called() == 2; }, kWaitMs));
  QElapsedTimer clock;
  clock.start();
  panel.reset();
  EXPECT_LT(clock.elapsed(), 1000) << "closing the panel waited for the hung runtime";
  hung.release();  // the calls end; their answers go nowhere
}

}  // namespace

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
