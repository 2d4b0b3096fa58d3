// Ask/tell searches for the Optimizer node: ask() gives the next candidate, tell() its fitness
// (larger is better). Nothing blocks: the node asks, the graph evaluates, the node tells.
// ROS-free; checked against scipy (test/optimizer/).
#pragma once

#include <memory>
#include <random>
#include <string>
#include <vector>

#include "apex/core/result.hpp"

namespace apex_nodes {
namespace search {

/** @brief One tuned value: its range, and whether it is an integer. */
struct Dimension {
  std::string name;
  double min = 0, max = 1;
  bool integer = false;
};

struct Settings {
  int budget = 100;  ///< evaluations in all
  unsigned seed = 1;  ///< the same seed gives the same candidates
  int population = 0;  ///< differential evolution; 0: 15 per dimension (at least 5)
  double F = 0.8;  ///< differential weight
  double CR = 0.9;  ///< crossover probability
};

/** @brief A search in ask/tell form. */
class Search {
 public:
  virtual ~Search() = default;
  /** @brief The next candidate; call tell() with its fitness before asking again. */
  std::vector<double> ask();
  /** @brief The fitness of the last candidate asked for (larger is better). */
  void tell(double fitness);
  /** @brief The budget is spent. */
  bool done() const { return evaluations_ >= budget_; }
  int evaluations() const { return evaluations_; }
  int budget() const { return budget_; }
  /** @brief The best candidate so far and its fitness (empty before the first tell). */
  const std::vector<double>& best() const { return best_; }
  double bestFitness() const { return best_fitness_; }

 protected:
  Search(std::vector<Dimension> dims, const Settings& s);
  virtual std::vector<double> next() = 0;
  virtual void result(const std::vector<double>& candidate, double fitness) = 0;
  /** Within the bounds; integers rounded. */
  std::vector<double> fit(std::vector<double> x) const;
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }
  std::vector<Dimension> dims_;
  std::mt19937_64 rng_;

 private:
  int budget_, evaluations_ = 0;
  std::vector<double> asked_, best_;
  double best_fitness_ = 0;
  bool pending_ = false;
};

/** @brief "differential_evolution" (rand/1/bin), "random" or "grid"; refused with a message
 *  for an unknown algorithm, no dimensions, a range with min > max, or settings out of range. */
apex::Result<std::unique_ptr<Search>> makeSearch(const std::string& algorithm, std::vector<Dimension> dims,
                                                 const Settings& settings);

}  // namespace search
}  // namespace apex_nodes
