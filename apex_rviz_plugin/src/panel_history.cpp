// Undo and redo as the runtime answers them, and redo after edits made elsewhere.
// The ~graph does not say who changed it. The panel knows when its own calls are on their way
// (pending_, replaying_) and, after an undo or redo, what the graph was right after it (read with
// get_graph behind its calls, in order): a later graph of another shape is someone else's edit.
#include "apex_rviz_plugin/panel_history.hpp"

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

void PanelHistory::answered(const Edit& edit, bool ok, int epoch) {
  --pending_;
  if (ok && epoch == epoch_) history_.done(edit);  // not into a history started since: another graph
  show();
}

bool PanelHistory::deferred(bool undo) {
  if (pending_ <= 0) return false;
  waiting_.push_back(undo);  // the edit it would undo is not in the history yet
  return true;
}

std::optional<bool> PanelHistory::nextWaiting() {
  if (pending_ != 0 || waiting_.empty()) return std::nullopt;
  const bool undo = waiting_.front();
  waiting_.pop_front();
  return undo;
}

PanelHistory::Step PanelHistory::take(bool undo) {
  Step step;
  step.label = undo ? history_.undoLabel() : history_.redoLabel();
  step.calls = undo ? history_.undo() : history_.redo();
  show();
  if (step.calls.empty()) return step;
  ++replaying_;
  redo_base_.reset();
  return step;
}

void PanelHistory::stepDone(bool undo, const std::string& label, bool ok, const std::string& message,
                            const apex::GraphState& after) {
  --replaying_;
  if (after.revision > 0) redo_base_ = std::make_pair(after.revision, editShape(after));
  const QString what = QString::fromStdString(label);
  if (ok) ctx_.editor.showMessage((undo ? "undid: " : "redid: ") + what, false);
  else ctx_.editor.showMessage((undo ? "undo of " : "redo of ") + what + " refused: " + QString::fromStdString(message), true);
  dropRedoIfEditedElsewhere();  // an edit elsewhere may be shown already
}

void PanelHistory::dropRedoIfEditedElsewhere() {
  // Graphs up to the step's revision may hold the step itself; one of the panel's own edits on
  // its way clears the redo list anyway once accepted.
  if (!history_.canRedo() || !redo_base_ || replaying_ > 0 || pending_ > 0) return;
  const apex::GraphState& now = ctx_.model.graph();
  if (now.revision <= redo_base_->first || editShape(now) == redo_base_->second) return;
  history_.dropRedo();
  redo_base_.reset();
  show();
  ctx_.editor.showMessage("the graph was edited elsewhere: nothing to redo", false);
}

void PanelHistory::restoreIfUntouched(const EditHistory& before) {
  if (history_.canUndo() || history_.canRedo()) return;  // something done since: the new history stands
  history_ = before;
  show();
}

void PanelHistory::reset() {
  history_.clear();
  waiting_.clear();
  ++epoch_;
  show();
}

void PanelHistory::show() const {
  ctx_.editor.showHistory(QString::fromStdString(history_.undoLabel()), history_.canUndo(), history_.canRedo());
}

}  // namespace apex_rviz_plugin
