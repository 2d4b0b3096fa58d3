// Runs the Optimizer's differential evolution on standard functions for scipy's comparison
// (compare_scipy.py): one line per run, "function dims seed best", minimising.
//   apex_search_check BUDGET_PER_DIMENSION SEEDS
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "apex_nodes/search.hpp"

namespace {

double sphere(const std::vector<double>& x) {
  double s = 0;
  for (double v : x) s += v * v;
  return s;
}

double rosenbrock(const std::vector<double>& x) {
  double s = 0;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) s += 100 * std::pow(x[i + 1] - x[i] * x[i], 2) + std::pow(1 - x[i], 2);
  return s;
}

double rastrigin(const std::vector<double>& x) {
  double s = 10.0 * x.size();
  for (double v : x) s += v * v - 10 * std::cos(2 * M_PI * v);
  return s;
}

struct Function {
  std::function<double(const std::vector<double>&)> f;
  double low, high;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: apex_search_check BUDGET_PER_DIMENSION SEEDS\n");
    return 2;
  }
  const int per_dim = std::atoi(argv[1]), seeds = std::atoi(argv[2]);
  const std::map<std::string, Function> functions{
      {"sphere", {sphere, -5.12, 5.12}}, {"rosenbrock", {rosenbrock, -5, 10}}, {"rastrigin", {rastrigin, -5.12, 5.12}}};
  for (const auto& [name, fn] : functions) {
    for (int dims : {2, 5, 10}) {
      for (int seed = 1; seed <= seeds; ++seed) {
        std::vector<apex_nodes::search::Dimension> box(dims, {"x", fn.low, fn.high, false});
        apex_nodes::search::Settings s;
        s.budget = per_dim * dims, s.seed = static_cast<unsigned>(seed);
        auto made = apex_nodes::search::makeSearch(apex_nodes::search::Algorithm::kDifferentialEvolution, box, s);
        if (!made) {
          std::fprintf(stderr, "%s\n", made.message().c_str());
          return 1;
        }
        auto& search = *made.value();
        while (!search.done()) search.tell(-fn.f(search.ask()));  // larger is better: minimise f
        std::printf("%s %d %d %.17g\n", name.c_str(), dims, seed, -search.bestFitness());
      }
    }
  }
  return 0;
}
