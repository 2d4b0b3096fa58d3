// The panel's undo and redo as the runtime answers them (panel_history.cpp). It owns the history
// of accepted edits, the count of edits and steps on their way, the undos and redos asked for
// while an edit was unanswered, and what the graph was right after the last undo or redo (to tell
// an edit made elsewhere). PanelWidget sends the calls; this says what to send and records answers.
#pragma once

#include <deque>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "apex_rviz_plugin/panel_context.hpp"

namespace apex_rviz_plugin {

class PanelHistory {
 public:
  explicit PanelHistory(const PanelContext& context) : ctx_(context) {}

  /** @brief Edits sent whose answer has not come back yet. */
  int pending() const { return pending_; }
  /** @brief Counts fresh histories: an edit answered after another one began is not recorded. */
  int epoch() const { return epoch_; }
  /** @brief An edit is sent, in the history of epoch(). */
  void sent() { ++pending_; }
  /** @brief Its answer: recorded if accepted and no fresh history began since (`epoch`, as sent);
   *  the editor's undo and redo buttons show the history. */
  void answered(const Edit& edit, bool ok, int epoch);

  /** @brief Undo (true) or redo asked for: true if it waits (an edit is unanswered, not in the
   *  history yet: the runtime's new graph can show before its answer); nextWaiting() gives it. */
  bool deferred(bool undo);
  /** @brief The first waiting undo (true) or redo, taken, once no edit is unanswered; else nothing. */
  std::optional<bool> nextWaiting();

  struct Step {
    std::vector<Call> calls;  ///< none: nothing to undo or redo
    std::string label;  ///< the edit's own name
  };
  /** @brief Takes the last edit off the undo (or redo) list and shows the history; calls to send
   *  are counted as a step on its way until stepDone. */
  Step take(bool undo);
  /** @brief A step answered; `after`, the runtime's graph right after it: the message says "undid:
   *  <label>" or "redid: <label>" (or the refusal); what could be redone is dropped if the graph
   *  shown was edited elsewhere since. */
  void stepDone(bool undo, const std::string& label, bool ok, const std::string& message, const apex::GraphState& after);
  /** @brief Someone else (a script, another panel) edited the graph since the last undo or redo:
   *  what could be redone no longer applies and is dropped. */
  void dropRedoIfEditedElsewhere();

  /** @brief The history as it is (kept by a Load to bring back if the runtime refuses it). */
  const EditHistory& edits() const { return history_; }
  /** @brief `before` brought back if nothing was done since the fresh history began. */
  void restoreIfUntouched(const EditHistory& before);
  /** @brief A fresh history (a Load, a New, another runtime): nothing to undo, redo or wait for;
   *  edits answered from now on that were sent before are not recorded. */
  void reset();
  /** @brief The link dropped every answer (another namespace): nothing is on its way. */
  void dropAnswers() { pending_ = 0, replaying_ = 0; }

 private:
  void show() const;

  PanelContext ctx_;
  EditHistory history_;
  int pending_ = 0;
  int replaying_ = 0;  // undo and redo steps sent, not answered yet
  int epoch_ = 0;
  std::deque<bool> waiting_;  // undo (true) or redo asked for while an edit was unanswered
  /** The graph a redo applies to: its revision and shape right after the last undo or redo; unset
   *  while unknown. */
  std::optional<std::pair<std::uint64_t, std::string>> redo_base_;
};

}  // namespace apex_rviz_plugin
