// What the panel tests share: calls to the runtime as a script makes them, checks
// of the boxes, simulated mouse input, and the fixture (a panel on /apex). The
// tests run in one binary against one runtime, in the order of the files
// (test_panel_widget, test_panel_tuning_and_layout, test_panel_runtimes).
#pragma once

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <QApplication>
#include <QElapsedTimer>
#include <QContextMenuEvent>
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
#include <QPointer>
#include <QSlider>
#include <QStyle>
#include <QStyleOptionSlider>
#include <QTabWidget>

#include <filesystem>
#include <fstream>

#include <apex/AddNode.h>
#include <apex/Connect.h>
#include <apex/FireSlot.h>
#include <apex/SetInteractive.h>
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
#include "apex_rviz_plugin/properties_view.hpp"
#include "apex_rviz_plugin/transport_bar.hpp"

namespace panel_test {

using namespace apex_rviz_plugin;

inline std::string g_shot, g_bag, g_graphs;  // from the command line (main)

/** Sets a parameter through the runtime's service, as a script would. */
inline bool setParameter(const std::string& node, const std::string& param, const std::string& value) {
  apex::SetParameter srv;
  srv.request.node = node, srv.request.parameter = param, srv.request.value = value;
  return ros::service::call("/apex/set_parameter", srv) && srv.response.success;
}
inline constexpr int kWaitMs = 20000;

inline bool addNode(const std::string& type, const std::string& name, const std::string& params) {
  apex::AddNode srv;
  srv.request.type = type, srv.request.name = name, srv.request.parameters = params;
  return ros::service::call("/apex/add_node", srv) && srv.response.success;
}

inline bool link(const std::string& a, const std::string& ap, const std::string& b, const std::string& bp) {
  apex::Connect srv;
  srv.request.from_node = a, srv.request.from_port = ap, srv.request.to_node = b, srv.request.to_port = bp;
  return ros::service::call("/apex/connect", srv) && srv.response.success;
}

inline bool fireSlot(const std::string& node, const std::string& slot) {
  apex::FireSlot srv;
  srv.request.node = node, srv.request.slot = slot;
  return ros::service::call("/apex/fire_slot", srv) && srv.response.success;
}

inline bool setInteractive(const std::string& node, const std::string& param, bool interactive = true) {
  apex::SetInteractive srv;
  srv.request.node = node, srv.request.parameter = param, srv.request.interactive = interactive;
  return ros::service::call("/apex/set_interactive", srv) && srv.response.success;
}

/** The runtime's graph, as a script reads it. A call that fails at once (on a loaded machine a
 *  connection to the service can be dropped: seen once in CI, with no error on the runtime's side)
 *  is made again, at most twice, and said in the log; a runtime that does not answer still fails. */
inline apex::GraphState runtimeGraph(const std::string& ns = "/apex") {
  apex::GetGraph srv;
  bool answered = false;
  for (int attempt = 0; attempt < 3 && !answered; ++attempt) {
    answered = ros::service::call(ns + "/get_graph", srv);
    if (!answered) std::fprintf(stderr, "runtimeGraph: %s/get_graph failed (attempt %d of 3)\n", ns.c_str(), attempt + 1);
  }
  EXPECT_TRUE(answered) << ns << "/get_graph did not answer";
  return srv.response.graph;
}

inline const apex::NodeInfo* find(const apex::GraphState& g, const std::string& name) {
  for (const auto& n : g.nodes)
    if (n.name == name) return &n;
  return nullptr;
}

inline std::string param(const apex::GraphState& g, const std::string& node, const std::string& name) {
  if (const auto* n = find(g, node))
    for (const auto& p : n->parameters)
      if (p.name == name) return p.value;
  return "";
}

inline double number(const apex::GraphState& g, const std::string& node, const std::string& name) {
  const std::string v = param(g, node, name);
  return v.empty() ? -1 : std::stod(v);
}

inline bool connected(const apex::GraphState& g, const std::string& a, const std::string& ap, const std::string& b,
                      const std::string& bp) {
  for (const auto& c : g.connections)
    if (c.from_node == a && c.from_port == ap && c.to_node == b && c.to_port == bp) return true;
  return false;
}

/** The boxes shown that lie on each other, as text; "" if none. */
inline std::string boxText(const Box& b) {
  return "(" + std::to_string(int(b.x)) + ", " + std::to_string(int(b.y)) + ", " + std::to_string(int(b.width)) + " x " +
         std::to_string(int(b.height)) + ")";
}

inline std::string overlapping(const GraphScene& scene) {
  const auto boxes = scene.boxes();
  std::string out;
  for (auto a = boxes.begin(); a != boxes.end(); ++a)
    for (auto b = std::next(a); b != boxes.end(); ++b)
      if (a->second.overlaps(b->second))
        out += a->first + " on " + b->first + " " + boxText(a->second) + " " + boxText(b->second) + "; ";
  return out;
}

/** The boxes shown that do not lie whole in the view's visible part, as text; "" if none. */
inline std::string outOfView(QGraphicsView* view, const GraphScene& scene) {
  const QRectF seen = view->mapToScene(view->viewport()->rect()).boundingRect();
  std::string out;
  for (const auto& [name, b] : scene.boxes())
    if (!seen.contains(QRectF(b.x, b.y, b.width, b.height))) out += name + " " + boxText(b) + "; ";
  return out;
}

/** A mouse event as the window system would deliver it to the view. */
inline void mouse(QGraphicsView* view, QEvent::Type type, QPointF scene_pos, Qt::MouseButtons held) {
  const QPoint at = view->mapFromScene(scene_pos);
  QMouseEvent e(type, at, view->viewport()->mapToGlobal(at), type == QEvent::MouseMove ? Qt::NoButton : Qt::LeftButton, held,
                Qt::NoModifier);
  QApplication::sendEvent(view->viewport(), &e);
}

/** Presses at `from`, moves in steps, releases at `to`: a drag. */
inline void drag(QGraphicsView* view, QPointF from, QPointF to) {
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

  /** New: an empty graph and a fresh history. */
  void emptyGraph() {
    const auto before = runtimeGraph().revision;
    emit panel.editor()->newRequested();
    // the New applied (a later revision), not only an empty graph: an empty graph before it would
    // let a node added next be cleared by the New still on its way
    ASSERT_TRUE(QTest::qWaitFor(
        [&] {
          const apex::GraphState g = runtimeGraph();
          return g.revision > before && g.nodes.empty() && panel.editor()->scene()->boxes().empty() && panel.editsPending() == 0;
        },
        kWaitMs))
        << panel.editor()->message().toStdString();
  }
  /** A BagReader `player` playing the demo bag at its full rate, looping: returns once it has
   *  changed the graph a few times (its frame and time, ten times a second). */
  void startPlaying(const std::string& player) {
    ASSERT_TRUE(
        addNode("apex_nodes/BagReader", player, "{file: '" + g_bag + "', topics: [/camera/image_raw], rate: 0.0, loop: true}"));
    waitPlaced(player);
    const auto before = panel.model().graph().revision;
    ASSERT_TRUE(QTest::qWaitFor([&] { return panel.model().graph().revision > before + 5; }, kWaitMs))
        << "the player does not change the graph as it plays";
  }
  /** Waits until the node is shown where the panel put it, with no edit on its way. */
  void waitPlaced(const std::string& node) {
    ASSERT_TRUE(QTest::qWaitFor(
        [&] { return panel.editor()->scene()->node(node) && panel.model().hasPosition(node) && panel.editsPending() == 0; },
        kWaitMs))
        << node << "; " << panel.editor()->message().toStdString();
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

/** The action of a menu whose text starts with `text`, or nullptr. */
inline QAction* action(const QMenu& menu, const QString& text) {
  for (QAction* a : menu.actions())
    if (a->text().startsWith(text)) return a;
  return nullptr;
}

/** A right-click on `node`'s title, its menu held open until `graphs` graphs came, then the item
 *  `text` chosen in it (with `submenu`: the first item of that submenu whose text starts with
 *  `text`). Returns the graphs shown while it was open; negated if nothing was chosen (the menu
 *  closed before, or has no such item). */
inline int chooseInNodeMenu(PanelWidget& panel, QGraphicsView* view, const std::string& node, const QString& text,
                            const QString& submenu = {}, int graphs = 3) {
  int shown = 0;
  const auto counting = QObject::connect(&panel, &PanelWidget::graphShown, [&] { ++shown; });
  bool chose = false;
  QTimer chooser;  // inside the menu's own event loop
  chooser.setInterval(20);
  QObject::connect(&chooser, &QTimer::timeout, [&] {
    auto* menu = qobject_cast<QMenu*>(QApplication::activePopupWidget());
    if (!menu || shown < graphs || chose) return;
    QAction* choice = nullptr;
    for (QAction* a : menu->actions()) {
      if (submenu.isEmpty() && a->text() == text) choice = a;
      if (!submenu.isEmpty() && a->text() == submenu && a->menu()) choice = action(*a->menu(), text);
    }
    menu->hide();
    if (choice) chose = true, choice->trigger();
  });
  chooser.start();
  NodeItem* item = panel.editor()->scene()->node(node);
  const QPoint at = view->mapFromScene(item->scenePos() + QPointF(40, 8));
  QContextMenuEvent right(QContextMenuEvent::Mouse, at, view->viewport()->mapToGlobal(at));
  QApplication::sendEvent(view->viewport(), &right);  // returns once the menu is closed
  chooser.stop();
  QObject::disconnect(counting);
  return chose ? shown : -shown;
}

}  // namespace panel_test
