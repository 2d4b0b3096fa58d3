// A node type's documentation in the panel: what docs/nodes.md says of it (apex_nodes/tools/
// node_docs.hpp writes that file from the manifests), from what the runtime lists of the type
// (NodeTypeInfo): its description and category, its inputs and outputs with their types, its
// slots and triggers, its parameters with kind, range or options, default and description.
// One window beside the editor, not modal: it stays open while the person works and, while
// open, follows the node selected (the editor tells it).
#pragma once

#include <QDialog>
#include <QString>

#include <apex/NodeTypeInfo.h>

class QTextBrowser;

namespace apex_rviz_plugin {

class HelpView : public QDialog {
  Q_OBJECT
 public:
  explicit HelpView(QWidget* parent = nullptr);
  /** @brief Shows `type`'s documentation, for `node` of the graph ("" for a type of the palette). */
  void showType(const apex::NodeTypeInfo& type, const QString& node = QString());
  /** @brief The id of the type shown; "" before one is. */
  const QString& typeId() const { return type_; }
  /** @brief The text shown, without its markup (for tests). */
  QString text() const;
  /** @brief A type's documentation as rich text: the content of its section of docs/nodes.md. */
  static QString html(const apex::NodeTypeInfo& type);
  /** @brief A parameter's range (`[min, max]`, a step if not 1, "(radians)" for angles), options
   *  or path mode, written as docs/nodes.md writes it; "" for kinds without any. */
  static QString limits(const apex::ParamInfo& param);

 private:
  QTextBrowser* text_;
  QString type_;
};

}  // namespace apex_rviz_plugin
