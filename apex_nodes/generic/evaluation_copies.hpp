// Copies of the part of a graph an Optimizer evaluates, so that several candidates are scored at
// once (its `workers`). The part is read from the graph's description: every node its fitness
// comes from, up to the Optimizer (a player, the tuned filters, the score, the mean), with the
// connections among them. Each copy is a graph of its own beside the user's, with the same node
// types, host and thread groups (so threads of its own), never shown or saved. A candidate is
// evaluated in a copy as the Optimizer's ports do it in the graph: the values set on the
// parameters its dimensions feed, then the slots its `evaluate` fires; what the senders of its
// inputs (`fitness`, `running`) send comes back by a callback. ROS-free.
#pragma once

#include <functional>
#include <map>
#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "apex/core/graph.hpp"

namespace apex_nodes {
namespace tuning {

/** @brief Where an Optimizer's evaluation acts in its graph (at the top level, subgraphs whole). */
struct EvaluatedPart {
  apex::GraphDescription graph;  ///< the nodes the fitness comes from, and the connections among them
  std::map<std::string, std::vector<std::pair<std::string, std::string>>> targets;  ///< per output: node, parameter
  std::map<std::string, std::vector<std::pair<std::string, std::string>>> slots;  ///< per trigger: node, slot
  std::map<std::string, std::pair<std::string, std::string>> senders;  ///< per input: node, output
};

/** @brief The part of `graph` that optimizer `name` evaluates (its input `fitness`, its trigger
 *  `evaluate`); an error saying what is missing (e.g. nothing feeds the fitness). */
apex::Result<EvaluatedPart> evaluatedPart(const apex::GraphDescription& graph, const std::string& name);

/** @brief Running copies of an evaluated part. */
class EvaluationCopies {
 public:
  /** Called with a copy's index, the Optimizer's input and the number its sender sent there, on
   *  that copy's thread. */
  using Scored = std::function<void(int copy, const std::string& input, double value)>;

  /** @brief `count` copies of `part`, each made by `make` and loaded (not started). */
  static apex::Result<std::unique_ptr<EvaluationCopies>> make(const EvaluatedPart& part,
                                                              const std::function<std::unique_ptr<apex::Graph>()>& make,
                                                              int count, Scored scored);
  ~EvaluationCopies();
  int size() const { return static_cast<int>(copies_.size()); }
  /** @brief Copy `i` evaluates the values (YAML text per Optimizer output): they are set on the
   *  parameters the outputs feed, then the `evaluate` slots fire; the fitness comes to `scored`. */
  apex::Status evaluate(int i, const std::vector<std::pair<std::string, std::string>>& values);
  /** @brief Fires in copy `i` the slots the Optimizer's trigger `trigger` feeds (e.g. `cut`). */
  apex::Status fire(int i, const std::string& trigger);
  /** @brief What copy `i`'s pass since its last evaluate() cost: the milliseconds the tuned nodes
   *  and the nodes they feed fired for (as the runtime times firings, NodeStats), per frame (a
   *  tuned node's firings); 0 before any frame. For the Optimizer's second objective. */
  double msPerFrame(int i) const;

 private:
  /** Per node of the tuned nodes and what they feed: NodeStats' firings, timed firings and their time. */
  using Work = std::map<std::string, apex::NodeStats>;
  Work workOf(int i) const;
  EvaluationCopies() = default;
  EvaluatedPart part_;
  std::set<std::string> costly_;  // the tuned nodes and those downstream of them in the part
  std::set<std::string> tuned_;
  std::vector<std::unique_ptr<apex::Graph>> copies_;
  std::vector<bool> started_;
  std::vector<Work> at_start_;  // per copy: at its pass's start
};

}  // namespace tuning
}  // namespace apex_nodes
