// The selected node's parameters in a column beside the canvas, as rviz's Displays panel lists a
// display's properties: every parameter at the panel's own size, whatever the canvas's zoom. The
// editors are the boxes' own (ParamEditor); what a person sets goes out as the boxes' signals do.
// A graph update shows the applied values and keeps the editors (and a slider being dragged);
// only another set of parameters rebuilds them. No ROS.
#pragma once

#include <QScrollArea>

#include <apex/NodeInfo.h>

#include <map>
#include <optional>
#include <string>

class QLabel;
class QVBoxLayout;

namespace apex_rviz_plugin {

class ParamEditor;

class PropertiesView : public QScrollArea {
  Q_OBJECT
 public:
  explicit PropertiesView(QWidget* parent = nullptr);
  /** @brief Shows `node`'s parameters, or says to select a node if null. The same parameters
   *  (names and kinds) as shown: their applied values, the editors kept. */
  void showNode(const apex::NodeInfo* node);
  /** @brief The node shown, "" if none. */
  QString node() const { return node_ ? QString::fromStdString(node_->name) : QString(); }
  /** @brief The editor of a parameter shown, nullptr if none. */
  ParamEditor* editor(const std::string& param) const;

 signals:
  /** `dragging`: a value of a slider drag going on (one undo step with the drag's last value). */
  void parameterEdited(const QString& node, const QString& param, const QString& yaml, bool dragging = false);
  void interactiveToggled(const QString& node, const QString& param, bool interactive);
  void paramMenuRequested(const QString& node, const QString& param, QPoint screen_pos);

 private:
  /** The parameters' names and kinds, and the node: what the editors are built for. */
  static std::string shapeOf(const apex::NodeInfo& node);
  void rebuild();

  std::optional<apex::NodeInfo> node_;
  std::string shape_;
  QLabel* title_;
  QLabel* kind_;
  QWidget* editors_box_ = nullptr;  ///< the editors, rebuilt with the shape
  QVBoxLayout* column_;
  std::map<std::string, ParamEditor*> editors_;
};

}  // namespace apex_rviz_plugin
