// Panel tests, continued (same runtime): what a new user found (issue #35, item 6). Save adds
// ".yaml"; Undo says what it undid; an edit made elsewhere drops Redo; a parameter's name has
// its menu; the minimap covers no box; a link asks before it goes, and takes a new node into it;
// Fit shows everything in a docked panel, new nodes land in view and a box dragged to the edge
// scrolls; a path's "..." is Qt's own dialog over the panel, one at a time.
#include "panel_test_support.hpp"

#include <QDir>
#include <QFileDialog>
#include <QPointer>
#include <QGraphicsProxyWidget>
#include <QListWidget>
#include <QPushButton>
#include <QScrollBar>

#include <algorithm>
#include <fstream>
#include <functional>
#include <iterator>

#include "apex_rviz_plugin/quick_add.hpp"

namespace panel_test {
namespace {

namespace fs = std::filesystem;

/** A popup menu as shown: its entries and where. */
struct Popup {
  QStringList actions;
  QPoint at;
};

/** The visible file dialogs (the old ones were embedded in the scene, still windows). */
std::vector<QFileDialog*> fileDialogs() {
  std::vector<QFileDialog*> out;
  for (QWidget* w : QApplication::topLevelWidgets())
    if (auto* d = qobject_cast<QFileDialog*>(w); d && d->isVisible()) out.push_back(d);
  return out;
}

class FirstUseTest : public PanelWidgetTest {
 protected:
  /** Runs `act`, then reads and closes the popup menu it showed (QMenu::exec waits for a person
   *  otherwise); nothing if none showed within a few seconds. */
  Popup popupOf(const std::function<void()>& act) {
    Popup seen;
    bool shown = false;
    QTimer poll;
    poll.setInterval(10);
    QObject::connect(&poll, &QTimer::timeout, [&] {
      auto* menu = qobject_cast<QMenu*>(QApplication::activePopupWidget());
      if (!menu || shown) return;
      for (QAction* a : menu->actions()) seen.actions << a->text();
      seen.at = menu->pos();
      shown = true;
      menu->close();
    });
    poll.start();
    act();
    (void)QTest::qWaitFor([&] { return shown; }, 3000);  // the caller checks what showed
    return seen;
  }
  /** Clicks tool button `name` and, in the menu it pops up, the entry whose text starts with `entry`
   *  (as a person does: the menu shows, the entry is picked, the menu closes). */
  bool pickFromButtonMenu(const char* name, const QString& entry) {
    QAction* picked = nullptr;
    QTimer poll;
    poll.setInterval(10);
    QObject::connect(&poll, &QTimer::timeout, [&] {
      auto* menu = qobject_cast<QMenu*>(QApplication::activePopupWidget());
      if (!menu) return;
      for (QAction* a : menu->actions())
        if (a->text().startsWith(entry)) picked = a;
      menu->close();
    });
    poll.start();
    QTest::mouseClick(panel.editor()->findChild<QToolButton*>(name), Qt::LeftButton);  // returns once the menu closed
    poll.stop();
    if (picked) picked->trigger();
    return picked != nullptr;
  }
  /** A right-click's menu event at scene point `at` (as the window system sends after the press). */
  void contextMenuAt(QPointF at) {
    const QPoint p = view->mapFromScene(at);
    QContextMenuEvent e(QContextMenuEvent::Mouse, p, view->viewport()->mapToGlobal(p));
    QApplication::sendEvent(view->viewport(), &e);
  }
  /** What the view shows, in scene units. */
  QRectF seen() const { return view->mapToScene(view->viewport()->rect()).boundingRect(); }
  /** A box's rectangle on the canvas. */
  static QRectF rect(const Box& b) { return QRectF(b.x, b.y, b.width, b.height); }
};

TEST_F(FirstUseTest, SaveAddsYamlToANameTypedWithoutIt) {
  emptyGraph();
  ASSERT_TRUE(addNode("apex_nodes/Clock", "saved_clock", ""));
  waitPlaced("saved_clock");
  const QString folder = QString::fromStdString(fs::path(g_bag).parent_path().string());  // in the runtime's file roots
  fs::remove(fs::path(g_bag).parent_path() / "blur_canny.yaml");
  fs::remove(fs::path(g_bag).parent_path() / "blur_canny");
  QString asked;
  QObject::connect(panel.editor(), &GraphEditor::saveRequested, &panel, [&](const QString& path) { asked = path; });
  QTest::mouseClick(panel.editor()->findChild<QToolButton*>("save"), Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return !fileDialogs().empty(); }, kWaitMs)) << "no Save dialog opened";
  QPointer<QFileDialog> dialog = fileDialogs().front();
  EXPECT_EQ(dialog->defaultSuffix().toStdString(), "yaml");
  dialog->setDirectory(folder);
  dialog->selectFile("blur_canny");  // typed without the suffix
  // as its Save button does (again while the folder is still being read: it may ignore the first)
  ASSERT_TRUE(QTest::qWaitFor(
      [&] {
        if (asked.isEmpty() && dialog && dialog->isVisible()) static_cast<QDialog*>(dialog.data())->accept();
        return !asked.isEmpty();
      },
      kWaitMs))
      << "the Save dialog gave no path"
      << (dialog ? "; it has " + dialog->selectedFiles().join(", ").toStdString() : std::string("; it closed"));
  EXPECT_TRUE(asked.endsWith("/blur_canny.yaml")) << asked.toStdString();
  ASSERT_TRUE(QTest::qWaitFor([&] { return fs::exists(fs::path(g_bag).parent_path() / "blur_canny.yaml"); }, kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_FALSE(fs::exists(fs::path(g_bag).parent_path() / "blur_canny"));
}

TEST_F(FirstUseTest, TheTraceButtonStartsTheTraceAndSavesItAsChromeTraceJson) {
  emptyGraph();
  ASSERT_TRUE(addNode("apex_nodes/Clock", "traced_clock", "{rate: 50.0}"));
  waitPlaced("traced_clock");
  auto* trace = panel.editor()->findChild<QToolButton*>("trace");
  ASSERT_TRUE(trace);
  ASSERT_TRUE(pickFromButtonMenu("trace", "Start tracing"));
  ASSERT_TRUE(QTest::qWaitFor([&] { return trace->text() == "Trace ●"; }, kWaitMs)) << panel.editor()->message().toStdString();
  const fs::path file = fs::path(g_bag).parent_path() / "clock_trace.json";
  fs::remove(file);
  QString asked;
  QObject::connect(panel.editor(), &GraphEditor::traceRequested, &panel,
                   [&](const QString& command, const QString& path, double) { asked = command == "save" ? path : asked; });
  ASSERT_TRUE(pickFromButtonMenu("trace", "Save all kept"));
  ASSERT_TRUE(QTest::qWaitFor([&] { return !fileDialogs().empty(); }, kWaitMs)) << "no Save trace dialog opened";
  QPointer<QFileDialog> dialog = fileDialogs().front();
  EXPECT_EQ(dialog->defaultSuffix().toStdString(), "json");
  dialog->setDirectory(QString::fromStdString(file.parent_path().string()));
  dialog->selectFile("clock_trace");
  ASSERT_TRUE(QTest::qWaitFor(
      [&] {
        if (asked.isEmpty() && dialog && dialog->isVisible()) static_cast<QDialog*>(dialog.data())->accept();
        return !asked.isEmpty();
      },
      kWaitMs));
  // the runtime's answer: the file written, and where to open it
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editor()->message().contains("open it in https://ui.perfetto.dev"); }, kWaitMs))
      << panel.editor()->message().toStdString();
  ASSERT_TRUE(fs::exists(file));
  std::ifstream in(file);
  const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(json.find("\"traceEvents\""), std::string::npos);
  EXPECT_NE(json.find("{\"ph\":\"X\",\"name\":\"traced_clock\",\"cat\":\"apex_nodes/Clock\""), std::string::npos);
  ASSERT_TRUE(pickFromButtonMenu("trace", "Stop tracing"));
  ASSERT_TRUE(QTest::qWaitFor([&] { return trace->text() == "Trace"; }, kWaitMs));
}

TEST_F(FirstUseTest, UndoSaysWhatItUndidAndAnEditMadeElsewhereDropsRedo) {
  emptyGraph();
  GraphScene* scene = panel.editor()->scene();
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  auto* redo = panel.editor()->findChild<QToolButton*>("redo");
  addByKeyboard("Clock", "clock_1");
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->isEnabled() && panel.editsPending() == 0; }, kWaitMs));
  QTest::mouseClick(undo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editor()->message().startsWith("undid"); }, kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_EQ(panel.editor()->message().toStdString(), "undid: Add clock_1");  // the edit's own name
  ASSERT_TRUE(QTest::qWaitFor([&] { return !scene->node("clock_1"); }, kWaitMs));
  EXPECT_TRUE(redo->isEnabled()) << "the undo's own graph is no edit made elsewhere";
  QTest::mouseClick(redo, Qt::LeftButton);
  ASSERT_TRUE(
      QTest::qWaitFor([&] { return panel.editor()->message() == "redid: Add clock_1" && scene->node("clock_1"); }, kWaitMs))
      << panel.editor()->message().toStdString();
  QTest::mouseClick(undo, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return !scene->node("clock_1") && panel.editor()->message().startsWith("undid"); }, kWaitMs));
  ASSERT_TRUE(redo->isEnabled());

  // a script (rosservice, another panel) edits the graph: the redo no longer applies
  ASSERT_TRUE(addNode("apex_nodes/Counter", "scripted_counter", ""));
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->node("scripted_counter") != nullptr; }, kWaitMs));
  EXPECT_TRUE(QTest::qWaitFor([&] { return !redo->isEnabled(); }, kWaitMs)) << "Redo is still enabled after an edit elsewhere";
}

TEST_F(FirstUseTest, ARightClickOnAParametersNameShowsItsMenu) {
  emptyGraph();
  ASSERT_TRUE(addNode("apex_nodes/Clock", "menu_clock", ""));
  waitPlaced("menu_clock");
  GraphScene* scene = panel.editor()->scene();
  NodeItem* node = scene->node("menu_clock");
  view->resetTransform();  // 1:1, the box's widgets shown
  scene->setZoom(1);
  view->centerOn(node);
  ParamEditor* rate = node->editor("rate");
  ASSERT_TRUE(rate);
  auto* label = rate->findChild<QLabel*>();
  ASSERT_TRUE(label && label->text() == "rate");
  QGraphicsProxyWidget* proxy = label->window()->graphicsProxyWidget();
  ASSERT_TRUE(proxy);
  const QPointF on_name = proxy->mapToScene(QPointF(label->mapTo(label->window(), label->rect().center())));
  // The box does not have the keyboard focus (the person typed in another node, or the box was
  // drawn anew by the runtime's graph): the menu comes all the same.
  scene->setFocusItem(nullptr);
  const Popup menu = popupOf([&] { contextMenuAt(on_name); });
  QMenu expected;
  panel.editor()->fillParamMenu(expected, "menu_clock", "rate");
  QStringList texts;
  for (QAction* a : expected.actions()) texts << a->text();
  ASSERT_FALSE(texts.isEmpty());
  EXPECT_EQ(menu.actions, texts) << "no menu, or another one, on the parameter's name";
}

TEST_F(FirstUseTest, TheMinimapIsHiddenWhenNothingIsOutOfViewAndNeverCoversABox) {
  emptyGraph();
  auto* minimap = panel.editor()->findChild<QWidget*>("minimap");
  ASSERT_TRUE(minimap);
  panel.editor()->fitGraph();
  QApplication::processEvents();
  EXPECT_FALSE(minimap->isVisible()) << "shown on an empty graph";
  ASSERT_TRUE(addNode("apex_nodes/Clock", "map_a", ""));
  waitPlaced("map_a");
  ASSERT_TRUE(addNode("apex_nodes/Counter", "map_b", ""));
  waitPlaced("map_b");
  GraphScene* scene = panel.editor()->scene();
  panel.editor()->fitGraph();
  QApplication::processEvents();
  EXPECT_FALSE(minimap->isVisible()) << "shown while the whole graph is in view";

  // 1:1, one box in the view's bottom-right corner (where the minimap went), the other out of view
  view->resetTransform();
  scene->setZoom(1);
  const QRectF a = rect(scene->boxes().at("map_a"));
  const QSizeF half = QSizeF(view->viewport()->size()) / 2;
  view->centerOn(a.bottomRight() - QPointF(half.width() - 12, half.height() - 12));
  QApplication::processEvents();
  ASSERT_TRUE(seen().intersects(a));
  ASSERT_FALSE(seen().contains(rect(scene->boxes().at("map_b"))) && seen().contains(a)) << "the whole graph is in view";
  ASSERT_TRUE(minimap->isVisible()) << "part of the graph is out of view: the minimap helps";
  const QRect there(view->viewport()->mapFrom(view, minimap->pos()), minimap->size());
  const QRectF covered = view->mapToScene(there).boundingRect();
  for (const auto& [name, box] : scene->boxes()) EXPECT_FALSE(covered.intersects(rect(box))) << "the minimap covers " << name;
}

TEST_F(FirstUseTest, ARightClickOnALinkAsksAndDeleteRemovesItAtOnce) {
  emptyGraph();
  ASSERT_TRUE(addNode("apex_nodes/Clock", "link_clock", ""));
  waitPlaced("link_clock");
  ASSERT_TRUE(addNode("apex_nodes/Counter", "link_counter", ""));
  waitPlaced("link_counter");
  ASSERT_TRUE(link("link_clock", "count", "link_counter", "in"));
  GraphScene* scene = panel.editor()->scene();
  ASSERT_TRUE(QTest::qWaitFor([&] { return scene->connections().size() == 1; }, kWaitMs));
  panel.editor()->fitGraph();
  const apex::Connection c = scene->connections().front()->connection();
  const QPointF on_link = scene->connections().front()->path().pointAtPercent(0.5);
  const Popup menu = popupOf([&] { contextMenuAt(on_link); });
  EXPECT_TRUE(menu.actions.contains("Delete link")) << "no menu on the link: " << menu.actions.join(", ").toStdString();
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editsPending() == 0; }, kWaitMs));
  EXPECT_TRUE(connected(runtimeGraph(), "link_clock", "count", "link_counter", "in")) << "a right-click alone disconnected";

  QMenu link_menu;
  panel.editor()->fillLinkMenu(link_menu, c);
  ASSERT_TRUE(action(link_menu, "Delete link"));
  action(link_menu, "Delete link")->trigger();
  EXPECT_TRUE(scene->connections().empty()) << "still drawn until the next graph";
  ASSERT_TRUE(QTest::qWaitFor([&] { return !connected(runtimeGraph(), "link_clock", "count", "link_counter", "in"); }, kWaitMs));
  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->isEnabled() && panel.editsPending() == 0; }, kWaitMs));
  QTest::mouseClick(undo, Qt::LeftButton);  // one step brings it back
  ASSERT_TRUE(QTest::qWaitFor([&] { return connected(runtimeGraph(), "link_clock", "count", "link_counter", "in"); }, kWaitMs));
}

/** The graph's nodes (name and type) and connections, as sorted text: what an undo gives back. */
std::vector<std::string> shape(const apex::GraphState& g) {
  std::vector<std::string> out;
  for (const auto& n : g.nodes) out.push_back("node " + n.name + " " + n.type);
  for (const auto& c : g.connections)
    out.push_back("link " + c.from_node + "/" + c.from_port + " -> " + c.to_node + "/" + c.to_port);
  std::sort(out.begin(), out.end());
  return out;
}

TEST_F(FirstUseTest, InsertNodeOnALinkPutsANewNodeBetweenLinkedOnBothSidesAsOneUndoStep) {
  emptyGraph();
  emit panel.editor()->loadRequested(QString::fromStdString(g_graphs + "/demo.yaml"));
  GraphScene* scene = panel.editor()->scene();
  const auto shown = [&]() -> const ConnectionItem* {
    for (const ConnectionItem* c : scene->connections())
      if (c->connection().from_node == "camera_detector" && c->connection().to_node == "overlay_out") return c;
    return nullptr;
  };
  ASSERT_TRUE(QTest::qWaitFor([&] { return shown() && panel.editsPending() == 0; }, kWaitMs))
      << panel.editor()->message().toStdString();
  emit panel.editor()->tidyRequested();  // the file's positions put boxes over this link
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel.editsPending() == 0 && overlapping(*scene).empty(); }, kWaitMs))
      << overlapping(*scene);
  panel.editor()->fitGraph();
  const apex::GraphState before = runtimeGraph();
  ASSERT_TRUE(connected(before, "camera_detector", "overlay", "overlay_out", "image"));
  const apex::Connection c = shown()->connection();
  QPointF clear;  // a point of the link with no box over it
  for (int i = 1; i < 40 && clear.isNull(); ++i) {
    const QPointF at = shown()->path().pointAtPercent(i / 40.0);
    const auto under = scene->items(at);
    if (std::all_of(under.begin(), under.end(), [](QGraphicsItem* it) { return dynamic_cast<ConnectionItem*>(it); })) clear = at;
  }
  ASSERT_FALSE(clear.isNull()) << "boxes cover the whole link";
  const Popup menu = popupOf([&] { contextMenuAt(clear); });
  EXPECT_TRUE(menu.actions.contains("Insert node...")) << "link menu: " << menu.actions.join(", ").toStdString();

  QMenu link_menu;
  panel.editor()->fillLinkMenu(link_menu, c);
  ASSERT_TRUE(action(link_menu, "Insert node"));
  action(link_menu, "Insert node")->trigger();
  QuickAdd* quick = panel.editor()->quickAdd();
  ASSERT_TRUE(quick && quick->isVisible()) << panel.editor()->message().toStdString();
  EXPECT_TRUE(quick->shown().contains("apex_nodes/GaussianBlur"));
  EXPECT_FALSE(quick->shown().contains("apex_nodes/Clock")) << "it takes no image";
  EXPECT_FALSE(quick->shown().contains("apex_nodes/ImagePublisher")) << "it sends no image on";
  QTest::keyClicks(quick->search(), "apex_nodes/GaussianBlur");
  ASSERT_TRUE(quick->list()->currentItem());
  EXPECT_EQ(quick->list()->currentItem()->text(), QString::fromUtf8("GaussianBlur \u00b7 image \u2192 image"));
  const std::string name = panel.model().freshName("apex_nodes/GaussianBlur");
  QTest::keyClick(quick->search(), Qt::Key_Return);
  ASSERT_TRUE(QTest::qWaitFor(
      [&] {
        const auto g = runtimeGraph();
        return connected(g, "camera_detector", "overlay", name, "image") && connected(g, name, "image", "overlay_out", "image");
      },
      kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_FALSE(connected(runtimeGraph(), "camera_detector", "overlay", "overlay_out", "image")) << "the old link is still there";
  waitPlaced(name);
  const auto boxes = scene->boxes();
  const double middle = rect(boxes.at(name)).center().x();
  EXPECT_GT(middle, rect(boxes.at("camera_detector")).center().x()) << "not between the two boxes";
  EXPECT_LT(middle, rect(boxes.at("overlay_out")).center().x()) << "not between the two boxes";

  auto* undo = panel.editor()->findChild<QToolButton*>("undo");
  ASSERT_TRUE(QTest::qWaitFor([&] { return undo->toolTip().contains(QString::fromStdString("Insert " + name)); }, kWaitMs))
      << undo->toolTip().toStdString();
  QTest::mouseClick(undo, Qt::LeftButton);  // one step: the node and both links go, the old link comes back
  ASSERT_TRUE(QTest::qWaitFor([&] { return !find(runtimeGraph(), name) && panel.editsPending() == 0; }, kWaitMs))
      << panel.editor()->message().toStdString();
  EXPECT_EQ(shape(runtimeGraph()), shape(before));
  emptyGraph();  // the tests after start from nothing
}

/** A clock and a chain of 29 relays after it, no positions: 30 layers side by side. */
std::string writeChain() {
  const std::string path = fs::path(g_bag).parent_path() / "panel_chain.yaml";
  std::ofstream out(path);
  out << "apex_graph: 2\nnodes:\n  - {name: clock, type: apex_nodes/Clock, parameters: {rate: 1.0}}\n";
  for (int i = 1; i < 30; ++i) out << "  - {name: r" << i << ", type: apex_nodes/Relay}\n";
  out << "connections:\n";
  for (int i = 1; i < 30; ++i)
    out << "  - {from: " << (i == 1 ? std::string("clock/count") : "r" + std::to_string(i - 1) + "/out") << ", to: r" << i
        << "/in}\n";
  return path;
}

TEST_F(FirstUseTest, InADockedPanelFitShowsEveryNodeNewNodesLandInViewAndABoxDraggedToTheEdgeScrolls) {
  emptyGraph();
  panel.resize(900, 330);  // rviz's bottom dock
  QApplication::processEvents();
  GraphScene* scene = panel.editor()->scene();
  for (const char* name : {"clock_1", "clock_2", "clock_3"}) {  // from the palette, one after the other
    addByKeyboard("Clock", name);
    waitPlaced(name);
    const QPointF corner = scene->node(name)->pos();
    EXPECT_TRUE(seen().contains(QRectF(corner, QSizeF(80, 20)))) << name << "'s title is out of view";
  }

  emit panel.editor()->loadRequested(QString::fromStdString(writeChain()));
  ASSERT_TRUE(QTest::qWaitFor(
      [&] {
        const auto boxes = scene->boxes();
        if (boxes.size() != 30 || panel.editsPending() > 0) return false;
        for (const auto& [name, box] : boxes)
          if (!panel.model().hasPosition(name)) return false;
        return overlapping(*scene).empty();
      },
      kWaitMs))
      << scene->boxes().size() << " boxes; " << panel.editor()->message().toStdString();
  QTest::mouseClick(panel.editor()->findChild<QToolButton*>("fit"), Qt::LeftButton);
  for (const auto& [name, box] : scene->boxes()) EXPECT_TRUE(seen().contains(rect(box))) << name << " is out of view after Fit";
  EXPECT_FALSE(panel.editor()->findChild<QWidget*>("minimap")->isVisible());

  // 1:1 on the clock; its title dragged to the view's right edge and held there: the view scrolls
  view->resetTransform();
  scene->setZoom(1);
  NodeItem* clock = scene->node("clock");
  view->centerOn(clock);
  const QPointF grab = clock->scenePos() + QPointF(60, 10);
  const double start_x = clock->x();
  const int before = view->horizontalScrollBar()->value();
  const QPoint edge(view->viewport()->width() - 3, view->mapFromScene(grab).y());
  mouse(view, QEvent::MouseButtonPress, grab, Qt::LeftButton);
  for (int i = 1; i <= 10; ++i) {
    const QPoint p = view->mapFromScene(grab) + (edge - view->mapFromScene(grab)) * i / 10;
    mouse(view, QEvent::MouseMove, view->mapToScene(p), Qt::LeftButton);
  }
  const bool scrolled = QTest::qWaitFor([&] { return view->horizontalScrollBar()->value() > before + 150; }, kWaitMs);
  mouse(view, QEvent::MouseButtonRelease, view->mapToScene(edge), Qt::NoButton);
  EXPECT_TRUE(scrolled) << "the view did not scroll: " << before << " -> " << view->horizontalScrollBar()->value();
  EXPECT_GT(clock->x(), start_x + view->viewport()->width() / 2 + 100) << "the box did not go along";
}

TEST_F(FirstUseTest, APathsChooserIsQtsOwnDialogOverThePanelOneAtATime) {
  emptyGraph();
  ASSERT_TRUE(addNode("apex_nodes/BagReader", "chooser_bag", "{file: '" + g_bag + "'}"));
  NodeItem* node = nullptr;
  ASSERT_TRUE(
      QTest::qWaitFor([&] { return (node = panel.editor()->scene()->node("chooser_bag")) && node->editor("file"); }, kWaitMs));
  QPushButton* browse = nullptr;
  for (auto* b : node->editor("file")->findChildren<QPushButton*>())
    if (b->text() == "...") browse = b;
  ASSERT_TRUE(browse);
  struct Seen {
    int dialogs = 0;
    bool qt_own = false, in_scene = true, modal = false;
    QString folder;
    QStringList filters;
  } seen;
  bool recorded = false, clicking = false;
  auto record = [&] {
    const auto dialogs = fileDialogs();
    seen.dialogs = static_cast<int>(dialogs.size());
    if (dialogs.empty()) return;
    QFileDialog* d = dialogs.front();
    seen.qt_own = d->testOption(QFileDialog::DontUseNativeDialog);
    seen.in_scene = d->graphicsProxyWidget() || !d->parentWidget() || d->parentWidget()->window()->graphicsProxyWidget();
    seen.modal = d->isModal() || d->windowModality() != Qt::NonModal;
    seen.folder = d->directory().absolutePath();
    seen.filters = d->nameFilters();
    recorded = true;
  };
  QTimer unblock;  // the old dialog ran its own event loop in the click: read it there, and close it
  unblock.setInterval(10);
  QObject::connect(&unblock, &QTimer::timeout, [&] {
    if (!clicking || fileDialogs().empty() || recorded) return;
    record();
    for (QFileDialog* d : fileDialogs()) d->reject();
  });
  unblock.start();
  clicking = true;
  QTest::mouseClick(browse, Qt::LeftButton);
  clicking = false;
  if (!recorded) {  // opened without blocking: there now
    ASSERT_TRUE(QTest::qWaitFor([&] { return !fileDialogs().empty(); }, kWaitMs)) << "no dialog opened";
    record();
  }
  EXPECT_EQ(seen.dialogs, 1);
  EXPECT_TRUE(seen.qt_own) << "the desktop's dialog (it drew black in rviz)";
  EXPECT_FALSE(seen.in_scene) << "parented inside the node's box: embedded in the canvas";
  EXPECT_TRUE(seen.modal);
  EXPECT_EQ(QDir(seen.folder).canonicalPath(),
            QDir(QString::fromStdString(fs::path(g_bag).parent_path().string())).canonicalPath());
  EXPECT_TRUE(!seen.filters.isEmpty() && seen.filters.front().contains("*.bag")) << seen.filters.join(";;").toStdString();
  ASSERT_TRUE(recorded && seen.qt_own) << "the old dialog: stop before a second click would wait in its event loop";
  QTest::mouseClick(browse, Qt::LeftButton);  // a second click while it is open: the same one, raised
  EXPECT_EQ(fileDialogs().size(), 1u);
  for (QFileDialog* d : fileDialogs()) d->reject();
  unblock.stop();
}

}  // namespace
}  // namespace panel_test
