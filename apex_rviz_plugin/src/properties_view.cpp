#include "apex_rviz_plugin/properties_view.hpp"

#include "apex_rviz_plugin/box_view.hpp"
#include "apex_rviz_plugin/param_editor.hpp"

#include <QLabel>
#include <QVBoxLayout>

#include <algorithm>

namespace apex_rviz_plugin {

PropertiesView::PropertiesView(QWidget* parent) : QScrollArea(parent) {
  setObjectName("properties");
  setWidgetResizable(true);
  setFrameShape(QFrame::NoFrame);
  auto* page = new QWidget;
  column_ = new QVBoxLayout(page);
  column_->setContentsMargins(4, 4, 4, 4);
  column_->setSpacing(3);
  title_ = new QLabel;
  title_->setObjectName("properties_title");
  title_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  QFont bold = title_->font();
  bold.setBold(true);
  title_->setFont(bold);
  kind_ = new QLabel;
  kind_->setObjectName("properties_kind");
  kind_->setWordWrap(true);
  column_->addWidget(title_);
  column_->addWidget(kind_);
  column_->addStretch(1);
  setWidget(page);
  showNode(nullptr);
}

std::string PropertiesView::shapeOf(const apex::NodeInfo& node) {
  BoxView all;
  all.expanded = true;
  std::string shape = node.name + "|" + node.type;
  for (const auto& name : all.shown(node)) {
    const auto p = std::find_if(node.parameters.begin(), node.parameters.end(),
                                [&name](const apex::ParamInfo& q) { return q.name == name; });
    shape +=
        "|" + name + ":" + p->kind + ":" + std::to_string(p->min) + ":" + std::to_string(p->max) + ":" + std::to_string(p->step);
    for (const auto& option : p->options) shape += ":" + option;
  }
  return shape;
}

void PropertiesView::showNode(const apex::NodeInfo* node) {
  if (!node) {
    node_.reset(), shape_.clear();
    title_->setText("No node selected");
    kind_->setText("Click a node to see and set its parameters here.");
    rebuild();
    return;
  }
  node_ = *node;
  title_->setText(QString::fromStdString(node->name) + (node->enabled ? "" : "  (disabled)"));
  kind_->setText(QString::fromStdString(kindLine(node->type, node->thread_group) +
                                        (node->keeps.empty() ? "" : "\nKeeps from frame to frame: " + node->keeps)));
  const std::string shape = shapeOf(*node);
  if (shape != shape_) {
    shape_ = shape;
    rebuild();
    return;
  }
  for (const auto& p : node->parameters) {  // the applied values; an editor in use keeps its own
    auto it = editors_.find(p.name);
    if (it != editors_.end()) it->second->showApplied(p);
  }
}

void PropertiesView::rebuild() {
  delete editors_box_;  // deletes the editors in it
  editors_box_ = nullptr;
  editors_.clear();
  if (!node_) return;
  editors_box_ = new QWidget;
  auto* column = new QVBoxLayout(editors_box_);
  column->setContentsMargins(0, 4, 0, 0);
  column->setSpacing(2);
  BoxView all;
  all.expanded = true;
  const std::vector<std::string> shown = all.shown(*node_);
  const QString node = QString::fromStdString(node_->name);
  for (const auto& p : node_->parameters) {
    if (std::find(shown.begin(), shown.end(), p.name) == shown.end()) continue;
    auto* e = editorFor(p, node, this);
    editors_[p.name] = e;
    column->addWidget(e);
  }
  if (editors_.empty()) column->addWidget(new QLabel("no parameters"));
  column_->insertWidget(2, editors_box_);
}

ParamEditor* PropertiesView::editor(const std::string& param) const {
  auto it = editors_.find(param);
  return it == editors_.end() ? nullptr : it->second;
}

}  // namespace apex_rviz_plugin
