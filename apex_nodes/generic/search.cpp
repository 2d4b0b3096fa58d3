#include "apex_nodes/search.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace apex_nodes {
namespace search {

Search::Search(std::vector<Dimension> dims, const Settings& s) : dims_(std::move(dims)), rng_(s.seed), budget_(s.budget) {}

bool Search::canAsk() const { return asked_count_ < budget_ && evaluations_ >= waitsFor(asked_count_); }

double Search::threshold(int) const { return best_.empty() ? -HUGE_VAL : best_fitness_; }

int Search::rival(int) const { return best_id_; }

std::vector<double> Search::ask() {
  if (!canAsk())
    throw std::logic_error(asked_count_ >= budget_ ? "ask() with the whole budget asked for"
                                                   : "ask() while the search waits for fitnesses");
  auto x = fit(next(asked_count_));
  out_[asked_count_++] = x;
  return x;
}

void Search::tell(double fitness) {
  if (out_.size() != 1) throw std::logic_error("tell(fitness) needs exactly one candidate out; say which");
  tell(out_.begin()->first, fitness);
}

void Search::tell(int id, double fitness) {
  if (!out_.count(id) || told_.count(id)) throw std::logic_error("tell() of candidate " + std::to_string(id) + ", not out");
  if (!std::isfinite(fitness)) fitness = -HUGE_VAL;  // a failed evaluation is the worst there is
  told_[id] = fitness;
  for (auto it = told_.begin(); it != told_.end() && it->first == evaluations_; it = told_.erase(it)) {
    const std::vector<double> x = std::move(out_.at(it->first));
    out_.erase(it->first);
    ++evaluations_;
    if (best_.empty() || it->second > best_fitness_) best_ = x, best_fitness_ = it->second, best_id_ = it->first;
    result(x, it->second);
  }
}

std::vector<double> Search::fit(std::vector<double> x) const {
  for (std::size_t j = 0; j < x.size(); ++j) {
    x[j] = std::clamp(x[j], dims_[j].min, dims_[j].max);
    if (dims_[j].integer) x[j] = std::clamp(std::round(x[j]), std::ceil(dims_[j].min), std::floor(dims_[j].max));
  }
  return x;
}

namespace {

/** Uniform samples in the box. */
class RandomSearch : public Search {
 public:
  RandomSearch(std::vector<Dimension> d, const Settings& s) : Search(std::move(d), s) {}

 private:
  std::vector<double> next(int) override {
    std::vector<double> x(dims_.size());
    for (std::size_t j = 0; j < x.size(); ++j) x[j] = uniform(dims_[j].min, dims_[j].max);
    return x;
  }
  void result(const std::vector<double>&, double) override {}
};

/** A full grid with as many points per dimension as the budget allows (integers: at most
 *  one point per value), walked in order; the last points repeat if the budget is larger. */
class GridSearch : public Search {
 public:
  GridSearch(std::vector<Dimension> d, const Settings& s) : Search(std::move(d), s) {
    const int per = std::max(1, static_cast<int>(std::floor(std::pow(std::max(1, s.budget), 1.0 / dims_.size()) + 1e-9)));
    for (const auto& dim : dims_) {
      int n = per;
      if (dim.integer) n = std::min<int>(n, static_cast<int>(std::floor(dim.max) - std::ceil(dim.min)) + 1);
      points_.push_back(std::max(1, n));
    }
  }

 private:
  std::vector<double> next(int index) override {
    std::vector<double> x(dims_.size());
    long k = index;
    for (std::size_t j = 0; j < x.size(); ++j) {
      const int n = points_[j];
      const int i = static_cast<int>(k % n);
      k /= n;
      x[j] = n == 1 ? (dims_[j].min + dims_[j].max) / 2 : dims_[j].min + (dims_[j].max - dims_[j].min) * i / (n - 1);
    }
    return x;
  }
  void result(const std::vector<double>&, double) override {}
  std::vector<int> points_;
};

/** Differential evolution, rand/1/bin: a population from a Latin hypercube; then for each
 *  member in turn a trial = a + F (b - c) of three others, crossed with the member (each value
 *  with probability CR, one for sure); the trial replaces the member if it is at least as fit,
 *  at once (scipy's default), or deferred: at the end of the generation, so that all of its
 *  trials can be out at once. Out of range: a random value in range. */
class DifferentialEvolution : public Search {
 public:
  DifferentialEvolution(std::vector<Dimension> d, const Settings& s)
      : Search(std::move(d), s), F_(s.F), CR_(s.CR), deferred_(s.deferred) {
    const int n = s.population > 0 ? s.population : std::max(5, 15 * static_cast<int>(dims_.size()));
    population_.resize(n, std::vector<double>(dims_.size()));
    fitness_.assign(n, -HUGE_VAL);
    member_id_.assign(n, -1);
    for (std::size_t j = 0; j < dims_.size(); ++j) {  // Latin hypercube: one sample per stratum
      std::vector<int> strata(n);
      std::iota(strata.begin(), strata.end(), 0);
      std::shuffle(strata.begin(), strata.end(), rng_);
      for (int i = 0; i < n; ++i)
        population_[i][j] = dims_[j].min + (dims_[j].max - dims_[j].min) * (strata[i] + uniform(0, 1)) / n;
    }
  }

 private:
  /** Immediate: each candidate waits for the one before; deferred: for the generation before. */
  int waitsFor(int index) const override {
    const int n = static_cast<int>(population_.size());
    return deferred_ ? index / n * n : index;
  }
  /** A trial competes with its member only (whose fitness is at most the best). */
  double threshold(int id) const override {
    const int n = static_cast<int>(population_.size());
    return id < n ? -HUGE_VAL : fitness_[(id - n) % n];
  }
  int rival(int id) const override {
    const int n = static_cast<int>(population_.size());
    return id < n ? -1 : member_id_[(id - n) % n];
  }
  std::vector<double> next(int index) override {
    const int n = static_cast<int>(population_.size());
    if (index < n) return population_[index];
    const int target = (index - n) % n;
    std::uniform_int_distribution<int> pick(0, n - 1);
    int a, b, c;
    do a = pick(rng_);
    while (a == target);
    do b = pick(rng_);
    while (b == target || b == a);
    do c = pick(rng_);
    while (c == target || c == a || c == b);
    const std::size_t dims = dims_.size();
    const std::size_t forced = std::uniform_int_distribution<std::size_t>(0, dims - 1)(rng_);
    std::vector<double> trial = population_[target];
    for (std::size_t j = 0; j < dims; ++j) {
      if (j != forced && uniform(0, 1) >= CR_) continue;
      double v = population_[a][j] + F_ * (population_[b][j] - population_[c][j]);
      if (v < dims_[j].min || v > dims_[j].max) v = uniform(dims_[j].min, dims_[j].max);
      trial[j] = v;
    }
    return trial;
  }
  void result(const std::vector<double>& candidate, double fitness) override {
    const int n = static_cast<int>(population_.size());
    const int id = evaluations() - 1;  // results come in the order asked
    if (initialised_ < n) {
      population_[initialised_] = candidate;
      member_id_[initialised_] = id;
      fitness_[initialised_++] = fitness;
      return;
    }
    trials_.push_back({id, candidate, fitness});
    if (deferred_ && static_cast<int>(trials_.size()) < n) return;
    for (auto& t : trials_) {
      if (t.fitness >= fitness_[target_])
        population_[target_] = std::move(t.values), fitness_[target_] = t.fitness, member_id_[target_] = t.id;
      target_ = (target_ + 1) % n;
    }
    trials_.clear();
  }
  double F_, CR_;
  bool deferred_;
  std::vector<std::vector<double>> population_;
  std::vector<double> fitness_;
  std::vector<int> member_id_;  // per member: the evaluation it came from
  struct Trial {
    int id;
    std::vector<double> values;
    double fitness;
  };
  std::vector<Trial> trials_;  // scored, not yet selected (deferred)
  int initialised_ = 0, target_ = 0;  // members scored; the member the next selection is for
};

}  // namespace

// In a function: the Optimizer's parameter declaration reads it during static initialisation.
const std::vector<apex::Option<Algorithm>>& algorithms() {
  static const std::vector<apex::Option<Algorithm>> table{
      {"differential_evolution", Algorithm::kDifferentialEvolution}, {"random", Algorithm::kRandom}, {"grid", Algorithm::kGrid}};
  return table;
}

apex::Result<std::unique_ptr<Search>> makeSearch(Algorithm algorithm, std::vector<Dimension> dims, const Settings& s) {
  if (dims.empty()) return apex::Status::error("no dimensions to tune");
  for (const auto& d : dims) {
    if (!std::isfinite(d.min) || !std::isfinite(d.max) || d.min > d.max)
      return apex::Status::error("dimension '" + d.name + "': min " + std::to_string(d.min) + " and max " +
                                 std::to_string(d.max) + " do not make a range");
    if (d.integer && std::ceil(d.min) > std::floor(d.max))
      return apex::Status::error("dimension '" + d.name + "' is an integer but its range holds none");
  }
  if (s.budget < 1) return apex::Status::error("budget " + std::to_string(s.budget) + " is below 1");
  if (algorithm == Algorithm::kRandom) return std::unique_ptr<Search>(new RandomSearch(std::move(dims), s));
  if (algorithm == Algorithm::kGrid) return std::unique_ptr<Search>(new GridSearch(std::move(dims), s));
  if (s.population != 0 && s.population < 4)
    return apex::Status::error("population " + std::to_string(s.population) + " is below 4 (rand/1 needs three others)");
  if (!(s.F > 0 && s.F <= 2)) return apex::Status::error("F " + std::to_string(s.F) + " is outside (0, 2]");
  if (!(s.CR >= 0 && s.CR <= 1)) return apex::Status::error("CR " + std::to_string(s.CR) + " is outside [0, 1]");
  return std::unique_ptr<Search>(new DifferentialEvolution(std::move(dims), s));
}

}  // namespace search
}  // namespace apex_nodes
