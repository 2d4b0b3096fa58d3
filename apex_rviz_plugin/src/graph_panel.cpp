#include "apex_rviz_plugin/graph_panel.hpp"

#include <pluginlib/class_list_macros.hpp>
#include <ros/console.h>
#include <rviz/display.h>
#include <rviz/display_group.h>
#include <rviz/visualization_manager.h>

#include <QVBoxLayout>

#include "apex_rviz_plugin/panel_widget.hpp"

namespace apex_rviz_plugin {

GraphPanel::GraphPanel(QWidget* parent) : rviz::Panel(parent), widget_(new PanelWidget) {
  auto* column = new QVBoxLayout(this);
  column->setContentsMargins(0, 0, 0, 0);
  column->addWidget(widget_);
  connect(widget_, &PanelWidget::namespaceChanged, this, &rviz::Panel::configChanged);
  connect(widget_, &PanelWidget::displayRequested, this, &GraphPanel::addDisplay);
  connect(widget_, &PanelWidget::graphShown, this, [this](quint64 revision) {
    ROS_INFO_STREAM_ONCE_NAMED("apex_panel", "GraphPanel: showing the graph of "
                                                 << widget_->ns().toStdString() << " (revision " << revision << ", "
                                                 << widget_->model().graph().nodes.size() << " nodes)");
  });
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

void GraphPanel::addDisplay(const QString& rviz_class, const QString& name, const QString& topic) {
  if (!vis_manager_) return;
  rviz::DisplayGroup* root = vis_manager_->getRootDisplayGroup();
  for (int i = 0; i < root->numDisplays(); ++i)
    if (root->getDisplayAt(i)->getName() == name) return;  // already shown
  rviz::Display* d = vis_manager_->createDisplay(rviz_class, name, true);
  if (!d) return;
  const char* property = rviz_class == "rviz/Image" ? "Image Topic" : "Topic";
  if (rviz::Property* p = d->subProp(property)) p->setValue(topic);
}

}  // namespace apex_rviz_plugin

PLUGINLIB_EXPORT_CLASS(apex_rviz_plugin::GraphPanel, rviz::Panel)
