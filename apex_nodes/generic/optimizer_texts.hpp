// What the Optimizer writes (optimizer.cpp): its candidates' values as YAML (the best values, the
// Pareto front, what a copy or another runtime is sent), its space for a search outside the
// runtime, its state while a run goes and when it ends, why a run saved half-way cannot go on,
// and the settings its study file's header names. These functions only write the texts; the
// Optimizer decides when each is written. ROS-free.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "apex_nodes/pareto.hpp"
#include "apex_nodes/remote_workers.hpp"
#include "apex_nodes/search.hpp"
#include "tuned_dimension.hpp"

namespace apex_nodes {
namespace tuning {

/** @brief The values at the search's point `x` as YAML text, by output of `dims`: a candidate as
 *  a copy or another runtime evaluates it. */
CandidateValues valueTexts(const std::vector<TunedDimension>& dims, const std::vector<double>& x);

/** @brief The values at `x` as a YAML map, {dimension: value}, e.g. "{c: 12.5, block_size: 31}". */
std::string valuesText(const std::vector<TunedDimension>& dims, const std::vector<double>& x);

/** @brief The Pareto front as a YAML list, cheapest first, e.g. "[{evaluation: 3, fitness: 0.9,
 *  ms_per_frame: 1.5, values: {c: 12.5}}]"; "[]" while it is empty. */
std::string frontText(const std::vector<TunedDimension>& dims, const std::vector<Scored>& front);

/** @brief How many candidates each other runtime evaluated, for the state: e.g. "; 12 evaluated
 *  by /robot2/apex" per runtime, by name (one listed twice is counted once, in all); "" without
 *  remote workers. `evaluated[i]`: how many `runtimes[i]` evaluated. */
std::string remoteText(const std::vector<std::string>& runtimes, const std::vector<int>& evaluated);

/** @brief The dimensions as a search outside the runtime samples them: a YAML list of their
 *  TunedDimension::spaceText(). */
std::string spaceText(const std::vector<TunedDimension>& dims);

/** @brief Why a run cannot go on in a graph saved in the middle of it (its state then `saved`),
 *  and how to start again: from its study at `study`, if it has one (not ""). */
std::string interruptedText(const std::string& saved, const std::string& study);

/** @brief The state while a run goes: e.g. "running: evaluation 7 of 60, 4 workers (2 remote)",
 *  `evaluation` being the next one's number; the workers only if there are more than one, the
 *  remote ones only if there are any. */
std::string runningText(int evaluation, int budget, std::size_t workers, std::size_t remote_workers);

/** @brief How a run ended, as its last state says it. */
struct RunEnd {
  std::string how;  ///< e.g. "finished", "stopped"
  int evaluations = 0;
  std::string racing;  ///< what racing did (Racing::summary()); "" if the run was not asked to race
  std::string best;  ///< the best values (valuesText()); "" if there are none
  double best_fitness = 0;  ///< their fitness, as the graph scored it
  std::optional<std::size_t> front;  ///< with two objectives: the points on the front
  std::string remote;  ///< what the remote workers evaluated (remoteText())
};

/** @brief The state a run ends with: e.g. "finished after 60 evaluations (racing bound: 12 cut
 *  short, 71% of the frames scored); best 0.93 at {c: 12.5}; a front of 4 points; 20 evaluated by
 *  /robot2/apex", each part after the first only if `end` has it. */
std::string endText(const RunEnd& end);

/** @brief A run's settings as its study file's header names them (study_file.hpp): e.g.
 *  "algorithm random, budget 60, seed 1, population 0, F 0.8, CR 0.9, minimize false, dimensions
 *  [c 0 60]", then ", updating deferred" for differential evolution with `settings.deferred`,
 *  and ", objectives fitness_and_cost" with `two_objectives`. `dimensions`: as written. */
std::string studySettingsText(search::Algorithm algorithm, const search::Settings& settings, bool minimize,
                              const std::vector<std::string>& dimensions, bool two_objectives);

}  // namespace tuning
}  // namespace apex_nodes
