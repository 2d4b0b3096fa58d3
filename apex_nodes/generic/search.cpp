#include "apex_nodes/search.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace apex_nodes {
namespace search {

Search::Search(std::vector<Dimension> dims, const Settings& s) : dims_(std::move(dims)), rng_(s.seed), budget_(s.budget) {}

std::vector<double> Search::ask() {
  if (pending_) throw std::logic_error("ask() twice without tell()");
  asked_ = fit(next());
  pending_ = true;
  return asked_;
}

void Search::tell(double fitness) {
  if (!pending_) throw std::logic_error("tell() without ask()");
  pending_ = false;
  ++evaluations_;
  if (!std::isfinite(fitness)) fitness = -HUGE_VAL;  // a failed evaluation is the worst there is
  if (best_.empty() || fitness > best_fitness_) best_ = asked_, best_fitness_ = fitness;
  result(asked_, fitness);
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
  std::vector<double> next() override {
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
  std::vector<double> next() override {
    std::vector<double> x(dims_.size());
    long k = index_++;
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
  long index_ = 0;
};

/** Differential evolution, rand/1/bin, updating at once (as scipy's default): a population
 *  from a Latin hypercube; then for each member in turn a trial = a + F (b - c) of three
 *  others, crossed with the member (each value with probability CR, one for sure); the trial
 *  replaces the member if it is at least as fit. Out of range: a random value in range. */
class DifferentialEvolution : public Search {
 public:
  DifferentialEvolution(std::vector<Dimension> d, const Settings& s) : Search(std::move(d), s), F_(s.F), CR_(s.CR) {
    const int n = s.population > 0 ? s.population : std::max(5, 15 * static_cast<int>(dims_.size()));
    population_.resize(n, std::vector<double>(dims_.size()));
    fitness_.assign(n, -HUGE_VAL);
    for (std::size_t j = 0; j < dims_.size(); ++j) {  // Latin hypercube: one sample per stratum
      std::vector<int> strata(n);
      std::iota(strata.begin(), strata.end(), 0);
      std::shuffle(strata.begin(), strata.end(), rng_);
      for (int i = 0; i < n; ++i)
        population_[i][j] = dims_[j].min + (dims_[j].max - dims_[j].min) * (strata[i] + uniform(0, 1)) / n;
    }
  }

 private:
  std::vector<double> next() override {
    const int n = static_cast<int>(population_.size());
    if (initialised_ < n) return population_[initialised_];
    std::uniform_int_distribution<int> pick(0, n - 1);
    int a, b, c;
    do a = pick(rng_);
    while (a == target_);
    do b = pick(rng_);
    while (b == target_ || b == a);
    do c = pick(rng_);
    while (c == target_ || c == a || c == b);
    const std::size_t dims = dims_.size();
    const std::size_t forced = std::uniform_int_distribution<std::size_t>(0, dims - 1)(rng_);
    std::vector<double> trial = population_[target_];
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
    if (initialised_ < n) {
      population_[initialised_] = candidate;
      fitness_[initialised_++] = fitness;
      return;
    }
    if (fitness >= fitness_[target_]) population_[target_] = candidate, fitness_[target_] = fitness;
    target_ = (target_ + 1) % n;
  }
  double F_, CR_;
  std::vector<std::vector<double>> population_;
  std::vector<double> fitness_;
  int initialised_ = 0, target_ = 0;
};

}  // namespace

apex::Result<std::unique_ptr<Search>> makeSearch(const std::string& algorithm, std::vector<Dimension> dims, const Settings& s) {
  if (dims.empty()) return apex::Status::error("no dimensions to tune");
  for (const auto& d : dims) {
    if (!std::isfinite(d.min) || !std::isfinite(d.max) || d.min > d.max)
      return apex::Status::error("dimension '" + d.name + "': min " + std::to_string(d.min) + " and max " +
                                 std::to_string(d.max) + " do not make a range");
    if (d.integer && std::ceil(d.min) > std::floor(d.max))
      return apex::Status::error("dimension '" + d.name + "' is an integer but its range holds none");
  }
  if (s.budget < 1) return apex::Status::error("budget " + std::to_string(s.budget) + " is below 1");
  if (algorithm == "random") return std::unique_ptr<Search>(new RandomSearch(std::move(dims), s));
  if (algorithm == "grid") return std::unique_ptr<Search>(new GridSearch(std::move(dims), s));
  if (algorithm == "differential_evolution") {
    if (s.population != 0 && s.population < 4)
      return apex::Status::error("population " + std::to_string(s.population) + " is below 4 (rand/1 needs three others)");
    if (!(s.F > 0 && s.F <= 2)) return apex::Status::error("F " + std::to_string(s.F) + " is outside (0, 2]");
    if (!(s.CR >= 0 && s.CR <= 1)) return apex::Status::error("CR " + std::to_string(s.CR) + " is outside [0, 1]");
    return std::unique_ptr<Search>(new DifferentialEvolution(std::move(dims), s));
  }
  return apex::Status::error("unknown algorithm '" + algorithm + "' (differential_evolution, random, grid)");
}

}  // namespace search
}  // namespace apex_nodes
