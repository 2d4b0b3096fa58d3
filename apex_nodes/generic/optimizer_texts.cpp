// What the Optimizer writes (optimizer_texts.hpp).
#include "optimizer_texts.hpp"

#include <map>

namespace apex_nodes {
namespace tuning {

namespace {

/** The algorithm's name, as its choice lists it (search::algorithms()). */
std::string nameOf(search::Algorithm algorithm) {
  for (const auto& o : search::algorithms())
    if (o.value == algorithm) return o.name;
  return "";
}

}  // namespace

CandidateValues valueTexts(const std::vector<TunedDimension>& dims, const std::vector<double>& x) {
  const auto values = valuesAt(dims, x);
  CandidateValues out;
  for (std::size_t i = 0; i < dims.size(); ++i) out.emplace_back(dims[i].port, apex::toText(values[i]));
  return out;
}

std::string valuesText(const std::vector<TunedDimension>& dims, const std::vector<double>& x) {
  const auto values = valuesAt(dims, x);
  std::string out = "{";
  for (std::size_t i = 0; i < dims.size(); ++i) out += (i ? ", " : "") + dims[i].port + ": " + apex::toText(values[i]);
  return out + "}";
}

std::string frontText(const std::vector<TunedDimension>& dims, const std::vector<Scored>& front) {
  std::string out;
  for (const auto& p : front)
    out += (out.empty() ? "" : ", ") + std::string("{evaluation: ") + std::to_string(p.evaluation) +
           ", fitness: " + apex::toText(p.fitness) + ", ms_per_frame: " + apex::toText(p.cost_ms) +
           ", values: " + valuesText(dims, p.point) + "}";
  return "[" + out + "]";
}

std::string remoteText(const std::vector<std::string>& runtimes, const std::vector<int>& evaluated) {
  std::map<std::string, int> by;
  for (std::size_t i = 0; i < runtimes.size(); ++i) by[runtimes[i]] += evaluated[i];
  std::string out;
  for (const auto& [runtime, n] : by) out += "; " + std::to_string(n) + " evaluated by " + runtime;
  return out;
}

std::string spaceText(const std::vector<TunedDimension>& dims) {
  std::string text;
  for (const auto& d : dims) text += (text.empty() ? "" : ", ") + d.spaceText();
  return "[" + text + "]";
}

std::string interruptedText(const std::string& saved, const std::string& study) {
  return "this graph was saved while a run was in progress (" + saved +
         "): the tuned parameters hold that candidate's values, not tuned ones; " +
         (study.empty() ? std::string("start a new run") : "start it again: it continues from its study '" + study + "'");
}

std::string runningText(int evaluation, int budget, std::size_t workers, std::size_t remote_workers) {
  const std::string at_once = workers > 1 ? ", " + std::to_string(workers) + " workers" +
                                                (remote_workers == 0 ? "" : " (" + std::to_string(remote_workers) + " remote)")
                                          : "";
  return "running: evaluation " + std::to_string(evaluation) + " of " + std::to_string(budget) + at_once;
}

std::string endText(const RunEnd& end) {
  const int n = end.evaluations;
  return end.how + " after " + std::to_string(n) + " evaluation" + (n == 1 ? "" : "s") +
         (end.racing.empty() ? "" : " (" + end.racing + ")") +
         (end.best.empty() ? "" : "; best " + apex::toText(end.best_fitness) + " at " + end.best) +
         (end.front ? "; a front of " + std::to_string(*end.front) + " point" + (*end.front == 1 ? "" : "s") : "") + end.remote;
}

std::string studySettingsText(search::Algorithm algorithm, const search::Settings& settings, bool minimize,
                              const std::vector<std::string>& dimensions, bool two_objectives) {
  std::string dims;
  for (const auto& d : dimensions) dims += (dims.empty() ? "" : ", ") + d;
  return "algorithm " + nameOf(algorithm) + ", budget " + std::to_string(settings.budget) + ", seed " +
         std::to_string(settings.seed) + ", population " + std::to_string(settings.population) + ", F " +
         apex::toText(settings.F) + ", CR " + apex::toText(settings.CR) + ", minimize " + (minimize ? "true" : "false") +
         ", dimensions [" + dims + "]" +
         (settings.deferred && algorithm == search::Algorithm::kDifferentialEvolution ? ", updating deferred" : "") +
         (two_objectives ? ", objectives fitness_and_cost" : "");
}

}  // namespace tuning
}  // namespace apex_nodes
