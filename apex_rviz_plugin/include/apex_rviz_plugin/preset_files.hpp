// Presets (preset_files.cpp): named snapshots of parameter values, one YAML file per name in
// $ROS_HOME/apex/presets. The editor's Presets menu lists them; saving writes one, restoring asks
// for the values that differ as one edit, comparing shows what differs. No state but the files.
#pragma once

#include <optional>
#include <string>

#include <QObject>
#include <QStringList>

#include "apex_rviz_plugin/panel_context.hpp"

namespace apex_rviz_plugin {

class PresetFiles : public QObject {
  Q_OBJECT
 public:
  explicit PresetFiles(const PanelContext& context) : ctx_(context) {}

  /** @brief Where presets are saved, one YAML file per name: $ROS_HOME/apex/presets. */
  static QString folder();
  /** @brief The presets saved, shown in the editor's menu. */
  void list();
  /** @brief The parameters of `nodes` (all if empty) saved as preset `name`; the message line says where. */
  void save(const QString& name, const QStringList& nodes);
  /** @brief The preset's values set where they differ, as one edit (editRequested). */
  void restore(const QString& name);
  /** @brief What differs between the preset and the graph, in the editor's window for it. */
  void compare(const QString& name);

 signals:
  void editRequested(const std::optional<Edit>& edit);

 private:
  /** The preset's text, or "" with the reason shown. */
  std::string read(const QString& name);

  PanelContext ctx_;
};

}  // namespace apex_rviz_plugin
