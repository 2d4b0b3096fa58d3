#include "candidate_server.hpp"

#include <utility>

#include "apex/core/graph_file.hpp"

namespace apex_nodes {
namespace tuning {

void CandidateServer::ask(const std::string& optimizer, CandidateValues values, bool with_cost, RemoteWorkers::Done reply,
                          int workers) {
  optimizer_ = optimizer;
  waiting_.push_back({std::move(values), with_cost, std::move(reply)});
  workers_ = std::max(1, workers);
  if (describing_) return;
  describing_ = true;  // the part as it is now: copies of an older one are made again once idle
  hooks_.describe([this, epoch = epoch_](const apex::GraphSnapshot& graph) { made(graph, epoch); });
}

void CandidateServer::made(const apex::GraphSnapshot& graph, int epoch) {
  if (epoch != epoch_) return;
  describing_ = false;
  auto part = evaluatedPart(graph.description, optimizer_);
  if (!part) return fail(part.message());
  const std::string text = apex::formatGraphText(part->graph);
  const bool idle = std::none_of(busy_.begin(), busy_.end(), [](const auto& r) { return r.has_value(); });
  if (copies_ && (text == part_text_ || !idle)) return dispatch();
  copies_.reset();
  auto sent = [this, epoch](int copy, const std::string& input, double v) {
    if (input != "fitness") return;
    hooks_.later([this, epoch, copy, v] {
      if (epoch == epoch_) scored(copy, v);
    });
  };
  auto copies = EvaluationCopies::make(part.value(), graph.makeGraph, workers_, sent);
  if (!copies) return fail(copies.message());
  copies_ = std::move(copies).value();
  part_text_ = text;
  busy_.assign(copies_->size(), std::nullopt);
  dispatch();
}

void CandidateServer::dispatch() {
  if (!copies_) return;
  for (int i = 0; i < copies_->size() && !waiting_.empty(); ++i) {
    if (busy_[i]) continue;
    Request r = std::move(waiting_.front());
    waiting_.pop_front();
    if (auto st = copies_->evaluate(i, r.values); !st) {
      r.reply({"'" + optimizer_ + "': " + st.message(), 0, 0});
      continue;
    }
    busy_[i] = std::move(r);
  }
}

void CandidateServer::scored(int copy, double fitness) {
  if (!copies_ || copy >= static_cast<int>(busy_.size()) || !busy_[copy]) return;  // a pass nobody asked for
  Request r = std::move(*busy_[copy]);
  busy_[copy].reset();
  r.reply({"", fitness, r.with_cost ? copies_->msPerFrame(copy) : 0.0});
  ++served_;
  hooks_.said("served " + std::to_string(served_) + " candidate" + (served_ == 1 ? "" : "s") + " for other runtimes");
  dispatch();
}

void CandidateServer::fail(const std::string& why) { close("'" + optimizer_ + "' cannot evaluate: " + why); }

void CandidateServer::close(const std::string& why) {
  ++epoch_;
  describing_ = false;
  copies_.reset();  // first: its taps call in until they stop
  for (auto& r : busy_)
    if (r) r->reply({why, 0, 0});
  for (auto& r : waiting_) r.reply({why, 0, 0});
  busy_.clear();
  waiting_.clear();
}

}  // namespace tuning
}  // namespace apex_nodes
