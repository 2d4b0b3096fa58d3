// PanelWidget, undo and redo as the runtime answers them, and redo after edits made elsewhere.
// The ~graph does not say who changed it. The panel knows when its own calls are on their way
// (pending_, replaying_) and, after an undo or redo, what the graph was right after it (read with
// get_graph behind its calls, in order): a later graph of another shape is someone else's edit.
#include "apex_rviz_plugin/panel_widget.hpp"

#include <algorithm>

namespace apex_rviz_plugin {
namespace {

/** What only edits change in a graph, as text: its nodes (name, type, thread group, subgraph,
 *  which parameters have ports) and its links. Not parameter values, enabled flags, errors or
 *  UI metadata: the runtime changes those by itself too (a player's frame, an Optimizer's state,
 *  enable and disable events, a panel placing boxes), and ~graph does not say who did. */
std::string editShape(const apex::GraphState& g) {
  std::vector<std::string> lines;
  for (const auto& n : g.nodes) {
    std::string line = "node " + n.name + " " + n.type + " " + n.thread_group + " " + n.subgraph;
    for (const auto& p : n.parameters)
      if (p.interactive) line += " " + p.name;
    lines.push_back(line);
  }
  for (const auto& c : g.connections)
    lines.push_back("link " + c.from_node + "/" + c.from_port + " " + c.to_node + "/" + c.to_port);
  std::sort(lines.begin(), lines.end());  // the same graph listed in another order is the same
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

}  // namespace

void PanelWidget::stepDone(bool undo, const std::string& label, bool ok, const std::string& message,
                           const apex::GraphState& after) {
  --replaying_;
  if (after.revision > 0) redo_base_ = std::make_pair(after.revision, editShape(after));
  const QString what = QString::fromStdString(label);
  if (ok) editor_->showMessage((undo ? "undid: " : "redid: ") + what, false);
  else editor_->showMessage((undo ? "undo of " : "redo of ") + what + " refused: " + QString::fromStdString(message), true);
  dropRedoIfEditedElsewhere();  // an edit elsewhere may be shown already
}

void PanelWidget::dropRedoIfEditedElsewhere() {
  // Graphs up to the step's revision may hold the step itself; one of the panel's own edits on
  // its way clears the redo list anyway once accepted.
  if (!history_.canRedo() || !redo_base_ || replaying_ > 0 || pending_ > 0) return;
  if (model_.graph().revision <= redo_base_->first || editShape(model_.graph()) == redo_base_->second) return;
  history_.dropRedo();
  redo_base_.reset();
  editor_->showHistory(QString::fromStdString(history_.undoLabel()), history_.canUndo(), history_.canRedo());
  editor_->showMessage("the graph was edited elsewhere: nothing to redo", false);
}

}  // namespace apex_rviz_plugin
