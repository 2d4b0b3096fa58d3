// Ask/tell searches for the Optimizer node: ask() gives the next candidate, tell() its fitness
// (larger is better). Nothing blocks: the node asks, the graph evaluates, the node tells. Several
// candidates may be out at once (canAsk()): their fitnesses may come back in any order and are
// taken in the order asked, so the candidates depend on the seed alone, never on timing.
// ROS-free; checked against scipy (test/optimizer/).
#pragma once

#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "apex/core/declare.hpp"
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
  /** Differential evolution: a generation's trials replace their members only once all are
   *  scored (scipy's updating='deferred'), so a whole generation can be evaluated at once;
   *  false: each trial at once (scipy's 'immediate'), one candidate out at a time. */
  bool deferred = false;
};

/** @brief A search in ask/tell form. */
class Search {
 public:
  virtual ~Search() = default;
  /** @brief Whether a candidate can be asked for now: budget is left that no candidate out
   *  holds, and the search needs no fitness it waits for (e.g. the end of a generation's). */
  bool canAsk() const;
  /** @brief The next candidate, number asked() - 1; throws std::logic_error unless canAsk(). */
  std::vector<double> ask();
  /** @brief The fitness of candidate `id` (larger is better), in any order: the search takes
   *  them in the order asked. Throws std::logic_error for a candidate not out. */
  void tell(int id, double fitness);
  /** @brief The fitness of the one candidate out. */
  void tell(double fitness);
  /** @brief Candidates asked for so far, told or not. */
  int asked() const { return asked_count_; }
  /** @brief For racing: a fitness such that any value below it, told for candidate `id` (out now),
   *  changes nothing the search does (the candidate is not the best and loses where it competes);
   *  -infinity when its exact value matters (e.g. a first population's member). By default the
   *  best so far. */
  virtual double threshold(int id) const;
  /** @brief For racing: the evaluation whose fitness threshold(id) is (the best so far, or the
   *  member a trial competes with), so that a pass can be compared with it frame by frame; -1
   *  when there is none. */
  virtual int rival(int id) const;
  /** @brief The budget is spent. */
  bool done() const { return evaluations_ >= budget_; }
  int evaluations() const { return evaluations_; }
  int budget() const { return budget_; }
  /** @brief The best candidate so far and its fitness (empty before the first tell). */
  const std::vector<double>& best() const { return best_; }
  double bestFitness() const { return best_fitness_; }

 protected:
  Search(std::vector<Dimension> dims, const Settings& s);
  /** The candidate number `index` (asked in order; every one before it is told if the search
   *  said so through waitsFor()). */
  virtual std::vector<double> next(int index) = 0;
  /** How many fitnesses in all must be taken before candidate `index` can be asked: by default
   *  none (any number out at once). */
  virtual int waitsFor(int /*index*/) const { return 0; }
  virtual void result(const std::vector<double>& candidate, double fitness) = 0;
  /** Within the bounds; integers rounded. */
  std::vector<double> fit(std::vector<double> x) const;
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }
  std::vector<Dimension> dims_;
  std::mt19937_64 rng_;

 private:
  int budget_, evaluations_ = 0, asked_count_ = 0;
  std::map<int, std::vector<double>> out_;  // asked, not yet taken: by number
  std::map<int, double> told_;  // told out of order, waiting for those before them
  std::vector<double> best_;
  double best_fitness_ = 0;
  int best_id_ = -1;
};

/** @brief How a search picks its candidates; by name: algorithms(). */
enum class Algorithm { kDifferentialEvolution, kRandom, kGrid };

/** @brief The algorithms by name (differential_evolution, random, grid): the Optimizer's
 *  `algorithm` choice reads this one table. */
const std::vector<apex::Option<Algorithm>>& algorithms();

/** @brief A search by `algorithm` (differential evolution: rand/1/bin); refused with a message
 *  for no dimensions, a range with min > max, or settings out of range. */
apex::Result<std::unique_ptr<Search>> makeSearch(Algorithm algorithm, std::vector<Dimension> dims, const Settings& settings);

}  // namespace search
}  // namespace apex_nodes
