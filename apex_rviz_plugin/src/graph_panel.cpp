#include "apex_rviz_plugin/graph_panel.hpp"

#include <pluginlib/class_list_macros.hpp>
#include <ros/console.h>
#include <rviz/display.h>
#include <rviz/display_group.h>
#include <rviz/visualization_manager.h>

#include <QDockWidget>
#include <QMainWindow>
#include <QSignalBlocker>
#include <QToolButton>
#include <QVBoxLayout>
#include <cstdlib>
#include <memory>

#include "apex_rviz_plugin/panel_widget.hpp"

namespace apex_rviz_plugin {

GraphPanel::GraphPanel(QWidget* parent) : rviz::Panel(parent), widget_(new PanelWidget) {
  auto* column = new QVBoxLayout(this);
  column->setContentsMargins(0, 0, 0, 0);
  column->addWidget(widget_);
  connect(widget_, &PanelWidget::namespaceChanged, this, &rviz::Panel::configChanged);
  connect(widget_, &PanelWidget::displayRequested, this, &GraphPanel::showDisplay);
  connect(widget_, &PanelWidget::renameSent, this,
          [this](const QString& from, const QString& to) { followed_.expectRename(from.toStdString(), to.toStdString()); });
  connect(widget_, &PanelWidget::graphShown, this, &GraphPanel::followGraph);
  connect(widget_, &PanelWidget::graphShown, this, [this](quint64 revision) {
    ROS_INFO_STREAM_ONCE_NAMED("apex_panel", "GraphPanel: showing the graph of "
                                                 << widget_->ns().toStdString() << " (revision " << revision << ", "
                                                 << widget_->model().graph().nodes.size() << " nodes)");
  });
  // For test/panel/rviz_check.sh: "node/port ..." shown in rviz as "Show in rviz" does, once the
  // first graph is shown (a script cannot open the panel's menus).
  if (const char* show = std::getenv("APEX_PANEL_SHOW_IN_RVIZ")) {
    auto once = std::make_shared<QMetaObject::Connection>();
    *once = connect(widget_, &PanelWidget::graphShown, this,
                    [this, once, ports = QString(show).split(QChar(32), Qt::SkipEmptyParts)] {
                      disconnect(*once);
                      for (const QString& p : ports) widget_->inspect(p.section('/', 0, -2), p.section('/', -1));
                    });
  }
  // For test/panel/rviz_check.sh's screenshot: node N selected (its properties shown), once shown.
  if (const char* select = std::getenv("APEX_PANEL_SELECT")) {
    auto once = std::make_shared<QMetaObject::Connection>();
    *once = connect(widget_, &PanelWidget::graphShown, this, [this, once, node = std::string(select)] {
      if (NodeItem* item = widget_->editor()->scene()->node(node)) disconnect(*once), item->setSelected(true);
    });
  }
  connect(widget_->editor(), &GraphEditor::wholeWindowToggled, this, &GraphPanel::setWholeWindow);
  connect(widget_, &PanelWidget::statusShown, this,
          [] { ROS_INFO_STREAM_ONCE_NAMED("apex_panel", "GraphPanel: timing shown from ~status"); });
}

void GraphPanel::onInitialize() {
  if (widget_->ns().isEmpty()) widget_->setNamespace("/apex");
}

void GraphPanel::load(const rviz::Config& config) {
  rviz::Panel::load(config);
  QString ns;
  widget_->setNamespace(config.mapGetString("Namespace", &ns) && !ns.isEmpty() ? ns : "/apex");
  bool previews = false;
  if (config.mapGetBool("Previews", &previews)) widget_->setPreviews(previews);
}

void GraphPanel::save(rviz::Config config) const {
  rviz::Panel::save(config);
  config.mapSetValue("Namespace", widget_->ns());
  config.mapSetValue("Previews", widget_->previews());
}

void GraphPanel::showDisplay(const QString& node, const QString& port, const QString& topic, const QString& message_type) {
  const auto kind = rvizDisplayFor(message_type.toStdString());
  if (!vis_manager_ || !kind) return;
  const int id = followed_.follow(node.toStdString(), port.toStdString());
  const QString name = QString::fromStdString(FollowedDisplays::displayName(node.toStdString(), port.toStdString()));
  const QString rviz_class = QString::fromStdString(kind->rviz_class);
  QPointer<rviz::Display>& display = displays_[id];
  rviz::DisplayGroup* root = vis_manager_->getRootDisplayGroup();
  for (int i = 0; !display && i < root->numDisplays(); ++i)  // one a saved config brought back
    if (root->getDisplayAt(i)->getName() == name && root->getDisplayAt(i)->getClassId() == rviz_class)
      display = root->getDisplayAt(i);
  if (!display) display = vis_manager_->createDisplay(rviz_class, name, true);
  if (!display) {
    ROS_ERROR_STREAM_NAMED("apex_panel",
                           "GraphPanel: rviz could not make a " << kind->rviz_class << " display for " << name.toStdString());
    followed_.forget(id), displays_.erase(id);
    return;
  }
  if (rviz::Property* p = display->subProp(QString::fromStdString(kind->topic_property)); p && !kind->topic_property.empty())
    p->setValue(topic);
  display->setEnabled(followed_.enabled(id));
  ROS_INFO_STREAM_NAMED(
      "apex_panel", "GraphPanel: display '" << name.toStdString() << "' (" << kind->rviz_class << ") on " << topic.toStdString());
}

void GraphPanel::followGraph() {
  using Kind = DisplayChange::Kind;
  for (const DisplayChange& c : followed_.update(widget_->model().graph())) {
    const QPointer<rviz::Display> display = displays_[c.id];
    if (!display || c.kind == Kind::kRemove) {  // gone with its node or port, or deleted in rviz
      displays_.erase(c.id);
      if (c.kind != Kind::kRemove) followed_.forget(c.id);
      if (display) removeDisplay(display);
      continue;
    }
    if (c.kind == Kind::kRename) {  // disabled until the port, inspected under its new name, has a topic
      display->setName(QString::fromStdString(c.name));
      widget_->inspect(QString::fromStdString(c.node), QString::fromStdString(c.port));
    }
    display->setEnabled(followed_.enabled(c.id));
  }
}

void GraphPanel::setWholeWindow(bool on) {
  // The panel's dock (rviz's PanelDockWidget) in rviz's main window: every other dock and the 3D
  // view hidden, the dock areas then take the window; back, the window's layout as it was.
  QDockWidget* dock = nullptr;
  for (QWidget* w = parentWidget(); w && !dock; w = w->parentWidget()) dock = qobject_cast<QDockWidget*>(w);
  auto* window = dock ? qobject_cast<QMainWindow*>(dock->parentWidget()) : nullptr;
  if (!window || !window->centralWidget() || dock->isFloating()) {  // not docked in rviz's window: nothing to take
    const QSignalBlocker quiet(widget_->editor()->wholeWindowButton());
    widget_->editor()->wholeWindowButton()->setChecked(false);
    return;
  }
  if (on == !hidden_.isEmpty()) return;
  if (on) {
    layout_ = window->saveState();
    hidden_.append(window->centralWidget());
    for (QDockWidget* other : window->findChildren<QDockWidget*>())
      if (other != dock && other->isVisible()) hidden_.append(other);
    for (const auto& w : hidden_) w->hide();
    return;
  }
  for (const auto& w : hidden_)
    if (w) w->show();
  hidden_.clear();
  window->restoreState(layout_);
}

void GraphPanel::removeDisplay(rviz::Display* display) {
  ROS_INFO_STREAM_NAMED("apex_panel", "GraphPanel: removed display '" << display->getName().toStdString() << "'");
  display->disconnect();  // it may signal from other threads: nobody listens once it goes
  if (rviz::Property* parent = display->getParent()) parent->takeChild(display);
  display->deleteLater();  // signals may be queued to it
  vis_manager_->notifyConfigChanged();
}

}  // namespace apex_rviz_plugin

PLUGINLIB_EXPORT_CLASS(apex_rviz_plugin::GraphPanel, rviz::Panel)
