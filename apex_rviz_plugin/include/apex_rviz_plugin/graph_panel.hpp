// apex_rviz_plugin/GraphPanel: the graph editor docked in rviz. Thin: it holds
// a PanelWidget, keeps the runtime's namespace in the .rviz config, and turns
// an inspected image or cloud into an rviz display.
#pragma once

#include <rviz/panel.h>

namespace apex_rviz_plugin {

class PanelWidget;

class GraphPanel : public rviz::Panel {
  Q_OBJECT
 public:
  explicit GraphPanel(QWidget* parent = nullptr);
  void onInitialize() override;
  void load(const rviz::Config& config) override;
  void save(rviz::Config config) const override;

 private:
  void addDisplay(const QString& rviz_class, const QString& name, const QString& topic);

  PanelWidget* widget_;
};

}  // namespace apex_rviz_plugin
