// The Optimizer's study file: every evaluation of a run, written as it ends, so that a run that
// was stopped or killed continues where it was. The file is rewritten whole after each
// evaluation (never half-written): a header naming the run's settings, a line of column names,
// then one line per evaluation (its number, the fitness, its cost if the run has two objectives,
// the search's coordinates, all as exact
// as a double prints). A run resumes by asking its search again and telling it the recorded
// fitnesses: the same settings give the same candidates, which the file's lines must match.
// ROS-free.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "apex_nodes/pareto.hpp"
#include "apex_nodes/search.hpp"

namespace apex_nodes {
namespace tuning {

/** @brief One recorded evaluation: the search's point, the fitness the graph gave it and, in a
 *  study of two objectives, its cost (ms per frame). */
struct Evaluation {
  std::vector<double> point;
  double fitness = 0;
  double cost_ms = 0;
};

class StudyFile {
 public:
  /** @brief The study at `path` of a run whose settings read `settings` (one line of text) and
   *  whose points have the coordinates `columns`; `with_cost`: a column ms_per_frame after the
   *  fitness. Nothing is read or written yet. */
  StudyFile(std::string path, std::string settings, std::vector<std::string> columns, bool with_cost = false);

  /** @brief The evaluations recorded so far (none if the file does not exist). Throws
   *  std::invalid_argument naming the file if it was made with other settings, or a line of it
   *  cannot be read. */
  std::vector<Evaluation> read();
  /** @brief Records one more evaluation: the whole file written anew, atomically. Throws
   *  std::runtime_error naming the file if it cannot be written. */
  void append(const Evaluation& e);
  const std::string& path() const { return path_; }

 private:
  std::string header() const;
  std::string path_, settings_;
  std::vector<std::string> columns_;
  bool with_cost_;
  std::string lines_;  // the evaluations' lines, as written
};

/** @brief The study at `path` of a run whose settings read `settings` and whose search has the
 *  `coordinates` (their names are its columns); `with_cost` as for StudyFile. nullptr if `path`
 *  is "": the run keeps no study. */
std::unique_ptr<StudyFile> openStudy(const std::string& path, const std::string& settings,
                                     const std::vector<search::Dimension>& coordinates, bool with_cost);

/** @brief Whether two points are the same candidate (as printed and read back: exactly). */
bool samePoint(const std::vector<double>& a, const std::vector<double>& b);

/** @brief The study's evaluations told to `search` again (`minimize`: their fitnesses negated), each
 *  checked to be its candidate, until its budget is spent; those told, numbered from 1. Throws
 *  std::invalid_argument, naming the file, at the first that is not its candidate. */
std::vector<Scored> replay(StudyFile& study, search::Search& search, bool minimize);

}  // namespace tuning
}  // namespace apex_nodes
