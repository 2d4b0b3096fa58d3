// A node's parameters: the values asked for (any thread, under NodeState::shared_'s lock) and
// the ones its group thread applies before a firing (Node::parameterChanged), whether set by an
// edit, by the node itself, or through a parameter input. Publishing them is the firing's
// (node_state.cpp).
#include "node_state.hpp"

#include "apex/core/node_names.hpp"

namespace apex {
namespace detail {

ParamValue NodeState::requestedParam(int index) const {
  auto lock = shared_.lock();
  return params_[index].requested;
}

ParamValues NodeState::requestedParams() const {
  ParamValues values;
  auto lock = shared_.lock();
  for (std::size_t i = 0; i < params_.size(); ++i) values.set(manifest().params[i].name, params_[i].requested);
  return values;
}

void NodeState::presetParam(int index, ParamValue v) {
  auto lock = shared_.lock();
  params_[index].requested = std::move(v);
  params_[index].resend = manifest().params[index].every_set;  // as requestParam: a command, applied even if equal
}

void NodeState::requestParam(int index, ParamValue v) {
  bool post_now = false;
  {
    auto shared = shared_.lock();
    params_[index].requested = std::move(v);
    params_[index].resend = manifest().params[index].every_set;
    params_dirty_.store(true, std::memory_order_release);
    post_now = !shared->apply_posted;
    shared->apply_posted = true;
  }
  if (post_now) post([](NodeState& n) { n.applyParams(); });
}

void NodeState::applyParams() {
  std::vector<int> changed;
  {
    auto shared = shared_.lock();
    shared->apply_posted = false;
    params_dirty_.store(false, std::memory_order_relaxed);
    for (std::size_t i = 0; i < params_.size(); ++i) {
      if (params_[i].requested == params_[i].active && !params_[i].resend) continue;
      params_[i].resend = false;
      params_[i].active = params_[i].requested;
      changed.push_back(static_cast<int>(i));
    }
  }
  for (int i : changed) {
    try {
      node_->parameterChanged(manifest().params[i].name);
    } catch (const std::exception& ex) {
      setError(nodeLabel(name_, type_->id) + " failed to apply parameter '" + manifest().params[i].name + "': " + ex.what());
    }
    publishParam(i);  // a parameter output carries every change
  }
  if (!changed.empty()) revisions_->edit();
}

void NodeState::updateParam(int index, ParamValue v) {
  {
    auto lock = shared_.lock();
    ParamState& p = params_[index];
    if (p.active == v) return;
    if (p.requested == p.active) p.requested = v;  // else an edit asked for another value: it applies next
    p.active = std::move(v);
  }
  revisions_->shown();  // its output sends it with the firing's outputs
}

void NodeState::receiveParam(Edge& edge, const Message& m, bool counted) {
  if (edge.dead) return;
  if (!m.isNothing()) {
    auto value = fromMessage(manifest().params[edge.to_index], m);
    if (value) {
      requestParam(edge.to_index, value.value());
      applyParams();
    } else {
      setError(nodeLabel(name_) + ": parameter input refused a value: " + value.message());
    }
  }
  // A flush (an edit) may have cleared the mark already: release the sender once.
  if (counted && edge.counted() && edge.unread.exchange(false, std::memory_order_acq_rel)) edge.from->unblock(1);
}

}  // namespace detail
}  // namespace apex
