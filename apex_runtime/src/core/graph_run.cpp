// Running the graph: start, stop, pause, the two kinds of step, and waiting
// until nothing more can fire.
#include <chrono>

#include "graph_impl.hpp"
#include "node_state.hpp"

namespace apex {

using detail::ThreadGroup;

void Graph::start() {
  Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  impl.running_ = true;
  impl.ran_ = true;
  for (auto& [name, g] : impl.groups_) g->start();
}

void Graph::Impl::stop() {
  auto lock = lockEdits();
  running_ = false;
  for (auto& [name, g] : groups_) g->stop();
}

void Graph::pause() {
  Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  impl.paused_ = true;
  impl.revisions_->shown();  // not an edit: a save does not keep it
  for (auto& [name, g] : impl.groups_) g->hold(true);
}

void Graph::resume() {
  Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  impl.paused_ = false;
  impl.revisions_->shown();
  for (auto& [name, g] : impl.groups_) g->hold(false);
}

bool Graph::paused() const {
  const Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  return impl.paused_;
}

void Graph::step() {
  Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  if (!impl.paused_) return;
  // Every group's budget is the nodes ready at one instant: groups stay paused
  // while the budgets are taken, so no firing of this step joins it early.
  for (auto& [name, g] : impl.groups_) g->pause();
  for (auto& [name, g] : impl.groups_) g->beginStep();
  for (auto& [name, g] : impl.groups_) g->resume();
  for (auto& [name, g] : impl.groups_) g->waitStep();
}

Status Graph::stepFrame(double timeout_s) {
  Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  if (!impl.paused_) return Status::error("the graph is running; pause it first");
  std::vector<std::shared_ptr<ThreadGroup>> groups;
  for (auto& [name, g] : impl.groups_) groups.push_back(g);
  // Budgets set with every group paused: no source fires twice, whichever group frees it.
  for (auto& g : groups) g->pause();
  for (auto& g : groups) g->beginFrameStep();
  for (auto& g : groups) g->resume();
  const bool done = impl.allIdle(groups, timeout_s);
  for (auto& g : groups) g->endFrameStep();
  impl.revisions_->shown();
  if (!done) return Status::error("the frame did not finish within " + std::to_string(timeout_s) + " s");
  return Status::ok();
}

bool Graph::waitIdle(double timeout_s) const {
  const Impl& impl = *impl_;
  std::vector<std::shared_ptr<ThreadGroup>> groups;  // shared: a load may drop a group meanwhile
  {
    auto lock = impl.lockEdits();
    for (auto& [name, g] : impl.groups_) groups.push_back(g);
  }
  // The sources an edit told to re-send (off the edit) first, then what they sent.
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(timeout_s));
  for (;;) {
    if (!impl.waitWalked(deadline)) return false;
    const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    if (!impl.allIdle(groups, std::max(0.0, left))) return false;
    std::lock_guard<std::mutex> l(impl.changed_mutex_);
    if (impl.changed_.empty() && !impl.walking_) return true;  // (a node's own edit request may have made one)
  }
}

bool Graph::Impl::allIdle(const std::vector<std::shared_ptr<ThreadGroup>>& groups, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(timeout_s));
  // A group found idle may be given work by one checked later: idle means two
  // passes in a row found every group idle with no work pushed or posted between.
  std::vector<std::uint64_t> last;
  for (;;) {
    std::vector<std::uint64_t> seen;
    for (auto& g : groups) {
      if (!g->waitIdle(deadline)) return false;
      seen.push_back(g->activity());
    }
    if (seen == last) return true;
    last = std::move(seen);
  }
}

}  // namespace apex
