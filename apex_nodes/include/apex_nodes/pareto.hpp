// The Optimizer's second objective: the candidates no other beats on both fitness and cost (the
// Pareto front), kept as evaluations end. ROS-free.
#pragma once

#include <algorithm>
#include <vector>

namespace apex_nodes {
namespace tuning {

/** @brief An evaluated candidate on two objectives: its fitness (larger is better unless
 *  minimize) and its cost (the tuned nodes' ms per frame; smaller is better). */
struct Scored {
  int evaluation = 0;  // 1, 2, ... in the order they were told
  double fitness = 0;
  double cost_ms = 0;
  std::vector<double> point;  // the search's coordinates
};

/** @brief `a` is at least as good as `b` on both objectives and better on one. */
inline bool dominates(const Scored& a, const Scored& b, bool minimize) {
  const bool fitter = minimize ? a.fitness < b.fitness : a.fitness > b.fitness;
  const bool as_fit = a.fitness == b.fitness || fitter;
  return as_fit && a.cost_ms <= b.cost_ms && (fitter || a.cost_ms < b.cost_ms);
}

/** @brief Adds `s` to `front` unless a point of it dominates `s` or equals it on both, and
 *  drops the points `s` dominates; the front stays ordered by cost (cheapest first). True if `s`
 *  joined it. */
inline bool addToFront(std::vector<Scored>& front, const Scored& s, bool minimize) {
  for (const Scored& f : front)
    if (dominates(f, s, minimize) || (f.fitness == s.fitness && f.cost_ms == s.cost_ms)) return false;
  front.erase(std::remove_if(front.begin(), front.end(), [&](const Scored& f) { return dominates(s, f, minimize); }),
              front.end());
  front.insert(
      std::upper_bound(front.begin(), front.end(), s, [](const Scored& a, const Scored& b) { return a.cost_ms < b.cost_ms; }), s);
  return true;
}

}  // namespace tuning
}  // namespace apex_nodes
