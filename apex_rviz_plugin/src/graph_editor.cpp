#include "apex_rviz_plugin/graph_editor.hpp"

#include "apex_rviz_plugin/file_dialog.hpp"
#include "apex_rviz_plugin/help_view.hpp"
#include "apex_rviz_plugin/palette.hpp"
#include "apex_rviz_plugin/properties_view.hpp"
#include "apex_rviz_plugin/view_parts.hpp"

#include <QApplication>
#include <QCursor>
#include <QGraphicsView>
#include <QHBoxLayout>
#include <QInputDialog>
#include <QKeyEvent>
#include <QLabel>
#include <QLineEdit>
#include <QMenu>
#include <QMessageBox>
#include <QMouseEvent>
#include <QPainter>
#include <QScrollBar>
#include <QShortcut>
#include <QSplitter>
#include <QTabWidget>
#include <QTimer>
#include <QToolBar>
#include <QToolButton>
#include <QVBoxLayout>
#include <QWheelEvent>

#include <algorithm>
#include <cmath>

namespace apex_rviz_plugin {
namespace {

QToolButton* button(const QString& name, const QString& text, const QString& tip) {
  auto* b = new QToolButton;
  b->setObjectName(name);
  b->setText(text);
  b->setToolTip(tip);
  return b;
}

}  // namespace

void GraphEditor::placeMinimap() {
  if (minimap_) minimap_->place();
}

void GraphEditor::growCanvas(const QRectF& also) {
  // Room around the boxes, a bit more than a view each way: any box can be brought anywhere in
  // the view, and a zoom keeps what is under the cursor (QGraphicsView centres a scene smaller
  // than itself). Never smaller than what is seen: the view does not move.
  const double s = view_->transform().m11();
  const QRect port = view_->viewport()->rect();
  const double w = 1.2 * port.width() / s, h = 1.2 * port.height() / s;
  QRectF wanted = scene_->itemsBoundingRect().adjusted(-w, -h, w, h) | view_->mapToScene(port).boundingRect();
  if (!also.isNull()) wanted |= also;
  if (wanted != view_->sceneRect()) view_->setSceneRect(wanted);
}

GraphEditor::GraphEditor(QWidget* parent) : QWidget(parent), scene_(new GraphScene(this)), view_(new QGraphicsView) {
  view_->setObjectName("view");
  view_->setScene(scene_);
  view_->setRenderHint(QPainter::Antialiasing);
  view_->setDragMode(QGraphicsView::RubberBandDrag);
  view_->setMinimumSize(300, 180);  // with the tool bar, a ~300 px dock (rviz's default bottom one)
  view_->setTransformationAnchor(QGraphicsView::NoAnchor);  // the wheel keeps the point under it itself
  view_->viewport()->installEventFilter(this);
  view_->installEventFilter(this);  // Delete and Ctrl+D on the selected nodes
  minimap_ = new Minimap(scene_, view_);
  new EdgeScroller(view_);  // a box dragged to the view's edge scrolls it
  for (QScrollBar* bar : {view_->horizontalScrollBar(), view_->verticalScrollBar()}) {  // scrolled or zoomed
    connect(bar, &QScrollBar::valueChanged, this, [this] { placeMinimap(), minimap_->update(); });
    connect(bar, &QScrollBar::actionTriggered, this, [this] { keep_fitted_ = false; });  // by the person
  }
  connect(scene_, &QGraphicsScene::sceneRectChanged, this, [this] { growCanvas(), placeMinimap(); });
  auto* split = new QSplitter;
  split->addWidget(buildSideTabs());
  split->addWidget(view_);
  split->setStretchFactor(1, 1);
  message_ = new QLabel;
  message_->setObjectName("message");
  message_->setWordWrap(true);
  message_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  auto* column = new QVBoxLayout(this);
  column->setContentsMargins(2, 2, 2, 2);
  column->addWidget(buildToolBar());
  column->addWidget(buildLevelBar());
  column->addWidget(split, 1);
  column->addWidget(message_);

  connect(scene_, &GraphScene::refused, this, [this](const QString& why) { showMessage(why, true); });
  connect(scene_, &GraphScene::nodeMenuRequested, this, &GraphEditor::showNodeMenu);
  connect(scene_, &GraphScene::portMenuRequested, this, &GraphEditor::showPortMenu);
  connect(scene_, &GraphScene::paramMenuRequested, this, &GraphEditor::showParamMenu);
  connect(scene_, &GraphScene::linkMenuRequested, this, &GraphEditor::showLinkMenu);
  connect(scene_, &GraphScene::canvasMenuRequested, this, &GraphEditor::showCanvasMenu);
  connect(scene_, &GraphScene::canvasDoubleClicked, this, [this](QPointF at) { openQuickAdd(at); });
  connect(scene_, &GraphScene::linkDropped, this, &GraphEditor::openLinkAdd);
  connect(scene_, &QGraphicsScene::selectionChanged, this, [this] {  // an open help follows the node selected
    const QStringList selected = selectedNodes();
    if (help_ && help_->isVisible() && selected.size() == 1) showNodeHelp(selected.front());
  });
  connect(scene_, &GraphScene::inspectRequested, this, &GraphEditor::inspectRequested);
  auto shortcut = [this](const QKeySequence& keys, auto fn) {
    auto* s = new QShortcut(keys, this);
    s->setContext(Qt::WidgetWithChildrenShortcut);
    connect(s, &QShortcut::activated, this, fn);
  };
  shortcut(QKeySequence::Undo, [this] { emit undoRequested(); });
  shortcut(QKeySequence::Find, [this] { find_->setFocus(), find_->selectAll(); });
  shortcut(QKeySequence::Redo, [this] { emit redoRequested(); });
  shortcut(QKeySequence(Qt::CTRL | Qt::Key_M), [this] { whole_->toggle(); });
}

GraphEditor::~GraphEditor() {
  scene_->disconnect(this);
  model_ = nullptr;
}

QWidget* GraphEditor::buildToolBar() {
  // Two rows: the runtime and Find, then the buttons in a QToolBar, which puts what does not fit
  // behind its » button, so the panel stays usable in a narrow dock.
  auto* bar = new QWidget;
  auto* rows = new QVBoxLayout(bar);
  rows->setContentsMargins(0, 0, 0, 0);
  rows->setSpacing(2);
  auto* row = new QHBoxLayout;
  rows->addLayout(row);
  row->addWidget(new QLabel("Runtime:"));
  namespace_ = new QLineEdit("/apex");
  namespace_->setObjectName("namespace");
  namespace_->setToolTip("the namespace of the runtime to edit, e.g. /apex");
  namespace_->setMaximumWidth(160);
  namespace_->setMinimumWidth(60);
  connect(namespace_, &QLineEdit::editingFinished, this, [this] { emit namespaceChanged(namespace_->text()); });
  row->addWidget(namespace_);
  unsaved_ = new QLabel("● unsaved");
  unsaved_->setObjectName("unsaved");
  unsaved_->setStyleSheet("color: #d08020;");
  unsaved_->setToolTip(
      "the graph differs from the file it was loaded from or last saved to: Save... keeps it "
      "(the runtime also keeps a copy that survives a crash)");
  unsaved_->hide();
  row->addWidget(unsaved_);
  connection_ = new QLabel;
  connection_->setObjectName("connection");
  connection_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);  // long news must not widen the panel
  row->addWidget(connection_, 1);
  pause_ = button("pause", "Pause", "pause or resume every thread group");
  pause_->setCheckable(true);
  connect(pause_, &QToolButton::clicked, this, [this](bool on) { emit controlRequested(on ? "pause" : "resume"); });
  auto* step = button("step", "Step", "while paused: fire each enabled node once");
  connect(step, &QToolButton::clicked, this, [this] { emit controlRequested("step"); });
  undo_ = button("undo", "Undo", "undo the last edit (Ctrl+Z)");
  redo_ = button("redo", "Redo", "redo (Ctrl+Shift+Z)");
  undo_->setEnabled(false), redo_->setEnabled(false);
  connect(undo_, &QToolButton::clicked, this, [this] { emit undoRequested(); });
  connect(redo_, &QToolButton::clicked, this, [this] { emit redoRequested(); });
  find_ = new QLineEdit;
  find_->setObjectName("find");
  find_->setPlaceholderText("Find node (Ctrl+F)");
  find_->setToolTip("a node by name or type, also inside subgraphs; Enter shows the next");
  find_->setMaximumWidth(160);
  find_->setMinimumWidth(60);
  connect(find_, &QLineEdit::returnPressed, this, &GraphEditor::findNext);
  connect(find_, &QLineEdit::textChanged, this, [this] { found_ = -1; });
  row->addWidget(find_);
  auto* fit = button("fit", "Fit", "show the whole graph");
  connect(fit, &QToolButton::clicked, this, &GraphEditor::fitGraph);
  auto* tidy = button("tidy", "Tidy", "lay the nodes out in layers, sources left, sinks right (one undo step)");
  connect(tidy, &QToolButton::clicked, this, &GraphEditor::tidyRequested);
  auto* balance = button("balance", "Balance",
                         "thread groups that make the graph a pipeline over the cores, from each node's time "
                         "(one undo step; the status line says what to expect)");
  connect(balance, &QToolButton::clicked, this, &GraphEditor::balanceRequested);
  previews_ = button("previews", "Previews",
                     "thumbnails of images and sparklines of numbers on the nodes in view "
                     "(at most 5 a second; nodes out of view cost nothing)");
  previews_->setCheckable(true);
  connect(previews_, &QToolButton::toggled, this, &GraphEditor::previewsToggled);
  auto* presets = button("presets", "Presets", "named snapshots of parameter values: save, compare with now, restore");
  presets->setPopupMode(QToolButton::InstantPopup);
  auto* preset_menu = new QMenu(presets);
  connect(preset_menu, &QMenu::aboutToShow, this, [this, preset_menu] {
    preset_menu->clear();
    fillPresetMenu(*preset_menu);
  });
  presets->setMenu(preset_menu);
  trace_ =
      button("trace", "Trace", "the frame trace: every firing of every thread group, saved for Perfetto or chrome://tracing");
  trace_->setPopupMode(QToolButton::InstantPopup);
  auto* trace_menu = new QMenu(trace_);
  connect(trace_menu, &QMenu::aboutToShow, this, [this, trace_menu] {
    trace_menu->clear();
    fillTraceMenu(*trace_menu);
  });
  trace_->setMenu(trace_menu);
  auto* fresh = button("new", "New", "remove every node: start from an empty graph (asks first; starts a fresh history)");
  connect(fresh, &QToolButton::clicked, this, [this] {
    const auto answer = QMessageBox::question(this, "New graph",
                                              "Remove every node of the running graph?\n"
                                              "Save it first if you want to keep it.");
    if (answer == QMessageBox::Yes) emit newRequested();
  });
  auto* save = button("save", "Save...", "save the graph to a file (written by the runtime)");
  auto* load = button("load", "Load...", "load a graph file into the runtime (all or nothing)");
  connect(save, &QToolButton::clicked, this, [this] {  // a name typed without ".yaml" gets it
    const FileDialogSpec spec{"save_dialog",          "Save graph", last_path_, FileDialogSpec::Mode::Save,
                              "APEX graphs (*.yaml)", "yaml"};
    openFileDialog(file_dialog_, this, spec, [this](const QString& path) { emit saveRequested(last_path_ = path); });
  });
  connect(load, &QToolButton::clicked, this, [this] {
    const FileDialogSpec spec{"load_dialog", "Load graph", last_path_, FileDialogSpec::Mode::Open, "APEX graphs (*.yaml)", ""};
    openFileDialog(file_dialog_, this, spec, [this](const QString& path) { emit loadRequested(last_path_ = path); });
  });
  whole_ = button("whole_window", "Whole window",
                  "the graph editor over rviz's whole window, and back (Ctrl+M); the 3D view and other panels "
                  "come back as they were");
  whole_->setCheckable(true);
  connect(whole_, &QToolButton::toggled, this, &GraphEditor::wholeWindowToggled);
  connect(whole_, &QToolButton::toggled, this, [this] {  // the graph fitted to the view's new size
    QTimer::singleShot(100, this, [this] { fitGraph(); });
  });
  auto* buttons = new QToolBar;
  buttons->setObjectName("buttons");
  buttons->setToolButtonStyle(Qt::ToolButtonTextOnly);
  for (QToolButton* b : {pause_, step, undo_, redo_, fit, tidy, balance, previews_, presets, trace_, fresh, save, load, whole_})
    buttons->addWidget(b);
  rows->addWidget(buttons);
  return bar;
}

QWidget* GraphEditor::buildLevelBar() {  // where the view is inside subgraphs; hidden at the top
  auto* bar = new LevelBar(scene_);
  connect(scene_, &GraphScene::levelChanged, this, [this, bar](const QString& path) {
    bar->showPath(path);
    fitGraph();
  });
  return bar;
}

QWidget* GraphEditor::buildSideTabs() {
  // The palette and the selected node's properties share the column beside the canvas (as an
  // IDE's side bar): the canvas keeps its width in a dock across rviz's window.
  side_ = new QTabWidget;
  side_->setObjectName("side");
  side_->setDocumentMode(true);
  side_->addTab(buildPalette(), "Nodes");
  properties_ = new PropertiesView;
  side_->addTab(properties_, "Properties");
  connect(properties_, &PropertiesView::parameterEdited, scene_, &GraphScene::parameterEdited);
  connect(properties_, &PropertiesView::interactiveToggled, scene_, &GraphScene::interactiveToggled);
  connect(properties_, &PropertiesView::paramMenuRequested, this, &GraphEditor::showParamMenu);
  connect(scene_, &QGraphicsScene::selectionChanged, this, [this] {  // a node picked: its properties
    showProperties();
    const QWidget* typing = QApplication::focusWidget();  // not away from a search being typed
    if (!properties_->node().isEmpty() && !(typing && palette_->isAncestorOf(typing))) side_->setCurrentWidget(properties_);
  });
  return side_;
}

void GraphEditor::showProperties() {
  const QStringList selected = selectedNodes();
  properties_->showNode(model_ && selected.size() == 1 ? model_->node(selected.front().toStdString()) : nullptr);
}

QWidget* GraphEditor::buildPalette() {
  palette_ = new Palette;
  connect(palette_, &Palette::addRequested, this, [this](const QString& type) { emit addRequested(type, newNodePosition()); });
  connect(palette_, &Palette::refused, this, [this](const QString& why) { showMessage(why, true); });
  connect(palette_, &Palette::reloadRequested, this, &GraphEditor::typesRequested);
  connect(palette_, &Palette::helpRequested, this, &GraphEditor::showTypeHelp);
  return palette_;
}

void GraphEditor::showTypes(const std::vector<apex::NodeTypeInfo>& types) {
  types_ = Palette::inOrder(types);
  palette_->showTypes(types);
}

QPointF GraphEditor::newNodePosition() {  // the middle of the view, a little further each time
  const QPointF c = view_->mapToScene(view_->viewport()->rect().center());
  const double step = 30.0 * (added_++ % 8);
  return c + QPointF(step - NodeItem::kMinWidth / 2, step - 40);
}

void GraphEditor::showGraph(const GraphModel& model) {
  model_ = &model;
  scene_->show(model);
  showProperties();
  const bool all_shown = std::all_of(select_when_shown_.begin(), select_when_shown_.end(),
                                     [this](const QString& n) { return scene_->node(n.toStdString()) != nullptr; });
  if (!select_when_shown_.isEmpty() && all_shown) {  // a paste may show up over several graphs: at its end
    scene_->clearSelection();
    for (const auto& n : select_when_shown_) scene_->node(n.toStdString())->setSelected(true);
    select_when_shown_.clear();
  }
  if (fit_pending_ && !model.graph().nodes.empty()) {
    fit_pending_ = false;
    fitGraph();
    keep_fitted_ = true;
  } else if (keep_fitted_ && !fitted_.contains(scene_->itemsBoundingRect())) {
    fitGraph();  // boxes grew (previews arrived) and the person has not touched the view since the fit
  }
  growCanvas();  // boxes moved or loaded where the canvas did not reach
  pause_->setChecked(model.graph().paused);
  pause_->setText(model.graph().paused ? "Resume" : "Pause");
}

void GraphEditor::fitGraph() {
  QRectF r = scene_->itemsBoundingRect().adjusted(-20, -20, 20, 20);
  if (r.isEmpty()) return;
  const QRect port = view_->viewport()->rect();
  double s = 1.0;
  for (int i = 0; i < 4; ++i) {  // boxes draw larger when zoomed out (names alone): fit what they become
    const double next = std::clamp(std::min(port.width() / r.width(), port.height() / r.height()), kMinZoom, 1.0);
    if (i > 0 && next >= s) break;
    s = next;
    scene_->setZoom(s);
    r = scene_->itemsBoundingRect().adjusted(-20, -20, 20, 20);
  }
  view_->resetTransform();
  view_->scale(s, s);
  growCanvas();
  view_->ensureVisible(QRectF(r.topLeft(), QSizeF(1, 1)), 0, 0);  // a graph too big to fit: its start
  if (s * r.width() <= port.width() && s * r.height() <= port.height()) view_->centerOn(r.center());
  fitted_ = scene_->itemsBoundingRect();
  placeMinimap();
}

void GraphEditor::reveal(const QRectF& area) {
  const double s = view_->transform().m11();
  const QSizeF seen = QSizeF(view_->viewport()->size()) / s;  // a box taller than the view: its title
  const QRectF shown(area.topLeft(),
                     QSizeF(std::min(area.width(), seen.width() - 20 / s), std::min(area.height(), seen.height() - 20 / s)));
  growCanvas(shown);
  view_->ensureVisible(shown, 10, 10);
}

bool GraphEditor::eventFilter(QObject* watched, QEvent* event) {
  if (watched == view_->viewport() && (event->type() == QEvent::MouseButtonPress || event->type() == QEvent::Wheel))
    keep_fitted_ = false;  // the view is the person's now (see showGraph)
  if (watched == view_ && event->type() == QEvent::KeyPress && !scene_->focusItem()) {  // not while typing in a widget
    auto* key = static_cast<QKeyEvent*>(event);
    if (key->key() == Qt::Key_Delete || key->key() == Qt::Key_Backspace) return removeSelected(), true;
    const bool ctrl = key->modifiers() & Qt::ControlModifier;
    const bool plain = key->modifiers() == Qt::NoModifier;  // Shift+Tab still moves the focus back
    if (plain && (key->key() == Qt::Key_Tab || key->key() == Qt::Key_Space)) return openQuickAdd(cursorPosition()), true;
    if (plain && key->key() == Qt::Key_F1 && selectedNodes().size() == 1) return showNodeHelp(selectedNodes().front()), true;
    if (ctrl && key->key() == Qt::Key_D) return emit duplicateRequested(selectedNodes()), true;
    if (ctrl && key->key() == Qt::Key_C) return emit copyRequested(selectedNodes()), true;
    if (ctrl && key->key() == Qt::Key_V) {
      const QPoint cursor = view_->viewport()->mapFromGlobal(QCursor::pos());
      const bool inside = view_->viewport()->rect().contains(cursor);
      return emit pasteRequested(inside ? view_->mapToScene(cursor) : newNodePosition()), true;
    }
  }
  if (watched == view_->viewport() && event->type() == QEvent::Wheel) {  // zooms around the cursor
    auto* wheel = static_cast<QWheelEvent*>(event);
    const double now = view_->transform().m11();
    const double f = std::clamp(std::pow(1.15, wheel->angleDelta().y() / 120.0), kMinZoom / now, 3.0 / now);
    const QPoint at = wheel->position().toPoint();  // the event's own place, not the cursor's (none offscreen)
    const QPointF under = view_->mapToScene(at);
    view_->scale(f, f);
    const double s = view_->transform().m11();  // where the view must go, on the canvas too
    growCanvas(QRectF(under - QPointF(at) / s, QSizeF(view_->viewport()->size()) / s));
    const QPointF off = view_->transform().map(under) - view_->transform().map(view_->mapToScene(at));  // pixels
    for (auto [bar, by] : {std::pair{view_->horizontalScrollBar(), off.x()}, std::pair{view_->verticalScrollBar(), off.y()}})
      bar->setValue(bar->value() + static_cast<int>(std::lround(by)));  // what was under the cursor stays there
    scene_->setZoom(view_->transform().m11());
    placeMinimap();
    return true;
  }
  if (watched == view_->viewport() && event->type() == QEvent::MouseMove)  // where quick add opens without a cursor
    last_mouse_ = static_cast<QMouseEvent*>(event)->pos();
  if (watched == view_->viewport() && event->type() == QEvent::Resize) growCanvas(), placeMinimap();  // its new size
  return QWidget::eventFilter(watched, event);
}

void GraphEditor::showMessage(const QString& text, bool error) {
  message_->setText(text);
  message_->setStyleSheet(error ? "color: #e04040;" : "");
}

QString GraphEditor::message() const { return message_->text(); }

void GraphEditor::showConnection(bool up, const QString& text) {
  connection_->setText(text);
  connection_->setToolTip(text);
  connection_->setStyleSheet(up ? "color: #40a040;" : "color: #d08020;");
}

void GraphEditor::showHistory(const QString& undo_label, bool can_undo, bool can_redo) {
  undo_->setEnabled(can_undo);
  redo_->setEnabled(can_redo);
  undo_->setToolTip(can_undo ? "Undo: " + undo_label + " (Ctrl+Z)" : "nothing to undo");
}

void GraphEditor::setNamespace(const QString& ns) { namespace_->setText(ns); }

void GraphEditor::showUnsaved(bool unsaved) { unsaved_->setVisible(unsaved); }

bool GraphEditor::unsavedShown() const { return !unsaved_->isHidden(); }

void GraphEditor::removeSelected() {
  for (QGraphicsItem* i : scene_->selectedItems())
    if (auto* n = dynamic_cast<NodeItem*>(i)) emit removeRequested(QString::fromStdString(n->info().name));
}

void GraphEditor::findNext() {
  const QString text = find_->text().trimmed();
  if (!model_ || text.isEmpty()) return;
  std::vector<std::string> matches;
  for (const auto& n : model_->graph().nodes)
    if (QString::fromStdString(n.name).contains(text, Qt::CaseInsensitive) ||
        QString::fromStdString(n.type).contains(text, Qt::CaseInsensitive))
      matches.push_back(n.name);
  if (matches.empty()) return showMessage("no node's name or type contains '" + text + "'", true);
  found_ = (found_ + 1) % static_cast<int>(matches.size());
  const std::string& name = matches[found_];
  const auto slash = name.rfind('/');
  scene_->setLevel(slash == std::string::npos ? "" : name.substr(0, slash));  // its subgraph, opened
  NodeItem* item = scene_->node(name);
  if (!item) return;
  scene_->clearSelection();
  item->setSelected(true);
  view_->centerOn(item);
  showMessage(QString("'%1': %2 (%3 of %4)").arg(text, QString::fromStdString(name)).arg(found_ + 1).arg(matches.size()), false);
}

QStringList GraphEditor::selectedNodes() const {
  QStringList out;
  for (QGraphicsItem* i : scene_->selectedItems())
    if (auto* n = dynamic_cast<NodeItem*>(i)) out << QString::fromStdString(n->info().name);
  return out;
}

void GraphEditor::selectWhenShown(const QStringList& nodes) { select_when_shown_ = nodes; }

QString GraphEditor::defaultGraphFolder() { return apexFolder(); }

}  // namespace apex_rviz_plugin
