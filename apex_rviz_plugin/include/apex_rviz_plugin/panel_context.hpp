// What every part of the panel's controller works on: the editor that shows the graph, the model
// of that graph, and the link to the runtime. PanelWidget owns all three and is the only one that
// changes the model (from the runtime's ~graph); its parts read it, show through the editor and
// call the runtime through the link.
#pragma once

#include <string>

#include <QString>

#include "apex_rviz_plugin/graph_editor.hpp"
#include "apex_rviz_plugin/graph_model.hpp"
#include "apex_rviz_plugin/runtime_link.hpp"

namespace apex_rviz_plugin {

struct PanelContext {
  GraphEditor& editor;
  const GraphModel& model;
  RuntimeLink& link;

  /** @brief The message line: `what` if `ok`, else "<what> refused: <message>" as an error. */
  void report(bool ok, const std::string& message, const QString& what) const {
    editor.showMessage(ok ? what : what + " refused: " + QString::fromStdString(message), !ok);
  }
};

}  // namespace apex_rviz_plugin
