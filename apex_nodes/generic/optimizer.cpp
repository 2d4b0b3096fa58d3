// Optimizer: tunes other nodes' parameters against a fitness, as in the paper's §4.2. One output
// per tuned dimension feeds a parameter input; a run is an ask/tell loop through the graph:
// the node sends a candidate and fires `evaluate` (its events leave after its messages, so the
// values are in effect before the replay starts), the graph replays and scores the data, and the
// mean arrives at `fitness` (after the pass's last frame: the end-of-sequence token), which
// tells the search and sends the next candidate. No thread ever waits for an evaluation.
#include <cmath>
#include <sstream>

#include "apex/core/registry.hpp"
#include "apex_nodes/search.hpp"
#include "study_file.hpp"
#include "tuned_dimension.hpp"

namespace apex_nodes {
namespace param = apex::param;

namespace {

/** One output per dimension, of the type of the parameter it tunes. */
apex::Status shapeDimensions(const apex::ParamValues& p, apex::Manifest& m) {
  for (const auto& text : p.get<std::vector<std::string>>("dimensions")) {
    auto d = tuning::parseDimension(text);
    if (!d) return d.status();
    m.outputs.push_back({d->name, tuning::outputType(d->kind), false,
                         "the candidate's value of '" + d->name + "': connect it to the parameter it tunes"});
  }
  return apex::Status::ok();
}

}  // namespace

class Optimizer : public apex::Node {
 public:
  static inline const apex::InputPort<double> kFitness{
      "fitness", "the candidate's score, e.g. SequenceMean's mean; larger is better unless minimize"};
  static inline const apex::OutputPort<double> kBestFitness{"best_fitness", "after each evaluation: the best fitness so far"};
  static inline const apex::OutputPort<int> kEvaluations{"evaluations", "after each evaluation: how many are done"};
  static inline const apex::OutputPort<std::string> kBest{
      "best", "after each evaluation: the best values so far, as YAML ({c: 12.5, block_size: 31})"};
  static inline const apex::TriggerPort kEvaluate{
      "evaluate",
      "a candidate's values are in effect: replay the data (a player's restart) and start the "
      "score (SequenceMean's reset)"};
  static inline const apex::TriggerPort kFinished{"finished",
                                                  "the run ended (its budget is spent, or stop): the best values are known"};
  static inline const apex::ParamDecl<std::vector<std::string>> kDimensions =
      param::textList("dimensions")
          .describe(
              "one output each: 'name [min max] [int]', 'name interval [min max]' (both ends), 'name choice "
              "[option ...]' or 'name bool', e.g. 'c 0 60', 'block_size int', 'area interval 500 20000', 'method "
              "choice'; without min and max (options), the range (options) of the parameter it is connected to")
          .shapesInterface();
  static inline const apex::ParamDecl<std::string> kAlgorithm =
      param::choice("algorithm", {"differential_evolution", "random", "grid"});
  static inline const apex::ParamDecl<int> kBudget =
      param::integer("budget").range(1, 1000000).step(1).init(60).describe("evaluations in a run");
  static inline const apex::ParamDecl<int> kSeed =
      param::integer("seed").range(0, 1000000000).step(1).init(1).describe("the same seed gives the same candidates");
  static inline const apex::ParamDecl<int> kPopulation =
      param::integer("population")
          .range(0, 10000)
          .step(1)
          .describe("differential evolution: candidates per generation; 0: 15 per dimension, at least 5");
  static inline const apex::ParamDecl<double> kF =
      param::number("F").range(0.0, 2.0).step(0.05).init(0.8).describe("differential evolution: differential weight");
  static inline const apex::ParamDecl<double> kCR =
      param::number("CR").range(0.0, 1.0).step(0.05).init(0.9).describe("differential evolution: crossover probability");
  static inline const apex::ParamDecl<bool> kMinimize = param::flag("minimize").describe("smaller fitness is better");
  static inline const apex::ParamDecl<std::string> kState =
      param::text("state").init("idle").describe("what the optimiser is doing (it sets this; saved with the graph)");
  static inline const apex::ParamDecl<std::string> kBestValues =
      param::text("best_values")
          .describe(
              "the best values so far as YAML, {dimension: value} (it sets this; the panel's "
              "'Apply best values' sets them on the tuned parameters as one undoable edit)");
  static inline const apex::ParamDecl<std::string> kStudy =
      param::path("study")
          .mode(apex::PathMode::Write)
          .describe(
              "a file where each evaluation is written as it ends: a run started again with the same settings "
              "(after a stop, a crash or a kill) continues from it; empty: none");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Tunes other nodes' parameters: one output per dimension, connected to the parameter it tunes; "
               "each candidate is evaluated by the graph (evaluate: replay and score; the score comes back at fitness)")
        .inCategory("optimisation")
        .input(kFitness)
        .output(kBestFitness)
        .output(kEvaluations)
        .output(kBest)
        .slot("start", &Optimizer::start, "starts a run with the settings as they are now")
        .slot("stop", &Optimizer::stop, "ends the run; the tuned parameters get their values from before it back")
        .slot("apply_best", &Optimizer::applyBest, "sets the tuned parameters to the best values found")
        .trigger(kEvaluate)
        .trigger(kFinished)
        .param(kDimensions)
        .param(kAlgorithm)
        .param(kBudget)
        .param(kSeed)
        .param(kPopulation)
        .param(kF)
        .param(kCR)
        .param(kMinimize)
        .param(kState)
        .param(kBestValues)
        .param(kStudy)
        .shapedBy(shapeDimensions);
  }

  void setup() override {
    const std::string saved = state_.get();
    if (saved.rfind("running", 0) != 0) return;
    updateParam(kState.name(), "interrupted (" + saved + ")");
    fail("this graph was saved while a run was in progress (" + saved +
         "): the tuned parameters hold that candidate's values, not tuned ones; " +
         (study_path_.get().empty() ? std::string("start a new run")
                                    : "start it again: it continues from its study '" + study_path_.get() + "'"));
  }

  /** The end of a sequence stops here: the outputs are values, not frames. */
  void endOfSequence() override { again(); }

  void parameterChanged(const std::string& name) override {
    if (name != kDimensions.name() || !running_) return;
    running_ = waiting_ = false;  // its outputs are not the run's any more: nothing to give back through them
    setState("stopped: the dimensions changed during the run");
    fail("the dimensions changed during a run: it stopped after " + std::to_string(search_->evaluations()) +
         " evaluations; the tuned parameters keep the last candidate's values");
  }

  /** A fitness arrived: the evaluation asked for last is done. */
  void process() override {
    if (!running_ || !waiting_) return again();  // a score nobody asked for (e.g. a pass before the run): ignored
    waiting_ = false;
    if (const std::string lost = lostTarget(); !lost.empty()) {
      end("stopped");
      fail(lost + ": the run stopped after " + std::to_string(search_->evaluations()) +
           " evaluations (the other tuned parameters got their values back)");
      return;
    }
    const double f = *fitness_.get();
    search_->tell(minimize_ ? -f : f);
    if (study_) try {
        study_->append({asked_, f});
      } catch (const std::runtime_error& e) {
        end("stopped");
        fail(std::string(e.what()) + ": the run stopped after " + std::to_string(search_->evaluations()) + " evaluations");
        return;
      }
    best_fitness_.publish(minimize_ ? -search_->bestFitness() : search_->bestFitness());
    evaluations_.publish(search_->evaluations());
    best_.publish(bestText());
    updateParam(kBestValues.name(), bestText());
    if (search_->done()) return end("finished");
    propose();
  }

  void start() {
    if (running_) throw std::invalid_argument("a run is in progress (" + state_.get() + "): stop it first, or wait for it");
    error_.clear();
    auto dims = resolveDimensions();
    std::vector<search::Dimension> ranges;
    for (const auto& d : dims) ranges.insert(ranges.end(), d.coordinates.begin(), d.coordinates.end());
    search::Settings s;
    s.budget = budget_.get();
    s.seed = static_cast<unsigned>(seed_.get());
    s.population = population_.get();
    s.F = f_.get();
    s.CR = cr_.get();
    auto made = search::makeSearch(algorithm_.get(), ranges, s);
    if (!made) throw std::invalid_argument(made.message());
    auto search = std::move(made).value();
    auto study = openStudy(ranges);
    const int resumed = study ? replay(*study, *search) : 0;
    search_ = std::move(search);
    study_ = std::move(study);
    dims_ = std::move(dims);
    minimize_ = minimize_param_.get();
    running_ = true;
    if (resumed > 0)
      log(apex::LogLevel::Info, "resumed from the study '" + study_->path() + "': " + std::to_string(resumed) + " evaluations");
    if (search_->done()) return end("finished");
    propose();
  }

  void stop() {
    if (running_) end("stopped");
  }

  void applyBest() {
    if (running_) throw std::invalid_argument("a run is in progress (" + state_.get() + "): stop it first, or wait for it");
    if (!search_ || search_->best().empty()) throw std::invalid_argument("no best values yet: run the optimiser first");
    sendAll(search_->best());
    setState("applied the best values " + bestText());
  }

 private:
  /** Every dimension resolved against the parameter it tunes (the first, if it tunes several). */
  std::vector<tuning::TunedDimension> resolveDimensions() const {
    std::vector<tuning::TunedDimension> out;
    for (const auto& text : dimensions_.get()) {
      const tuning::DimensionText d = tuning::parseDimension(text).value();  // the interface function read it already
      const auto targets = parameterTargets(d.name);
      if (targets.empty())
        throw std::invalid_argument("dimension '" + d.name +
                                    "': its output feeds no parameter; connect it to the "
                                    "parameter it tunes");
      const apex::ParamSpec& spec = targets.front().spec;
      out.push_back(tuning::resolve(d, text, spec, targets.front().node + "/" + spec.name, targets.front().value));
    }
    if (out.empty()) throw std::invalid_argument("no dimensions: add one per parameter to tune, e.g. 'c 0 60'");
    return out;
  }

  /** The values at the search's point `x`, one per dimension. */
  std::vector<apex::ParamValue> valuesAt(const std::vector<double>& x) const {
    std::vector<apex::ParamValue> out;
    std::size_t at = 0;
    for (const auto& d : dims_) {
      out.push_back(d.value(x.data() + at));
      at += d.coordinates.size();
    }
    return out;
  }

  void sendAll(const std::vector<double>& x) {
    const auto values = valuesAt(x);
    for (std::size_t i = 0; i < dims_.size(); ++i) publishMessage(dims_[i].port, apex::toMessage(values[i]));
  }

  /** The run's settings as the study file's header states them. */
  std::string settingsText() const {
    std::string dims;
    for (const auto& d : dimensions_.get()) dims += (dims.empty() ? "" : ", ") + d;
    return "algorithm " + algorithm_.get() + ", budget " + std::to_string(budget_.get()) + ", seed " +
           std::to_string(seed_.get()) + ", population " + std::to_string(population_.get()) + ", F " + apex::toText(f_.get()) +
           ", CR " + apex::toText(cr_.get()) + ", minimize " + (minimize_param_.get() ? "true" : "false") + ", dimensions [" +
           dims + "]";
  }

  /** The study of this run, if `study` names one. */
  std::unique_ptr<tuning::StudyFile> openStudy(const std::vector<search::Dimension>& coordinates) const {
    if (study_path_.get().empty()) return nullptr;
    std::vector<std::string> columns;
    for (const auto& c : coordinates) columns.push_back(c.name);
    return std::make_unique<tuning::StudyFile>(study_path_.get(), settingsText(), columns);
  }

  /** The study's evaluations told to `search` again, each checked to be its candidate; how many. */
  int replay(tuning::StudyFile& study, search::Search& search) const {
    int n = 0;
    const bool minimize = minimize_param_.get();
    for (const auto& e : study.read()) {
      if (search.done()) break;
      if (!tuning::samePoint(search.ask(), e.point))
        throw std::invalid_argument("the study '" + study.path() + "': evaluation " + std::to_string(n + 1) +
                                    " is not this run's candidate (the search was changed?): name another file, or move it away");
      search.tell(minimize ? -e.fitness : e.fitness);
      ++n;
    }
    return n;
  }

  /** The next candidate out, then `evaluate` (events leave after the messages). */
  void propose() {
    asked_ = search_->ask();
    sendAll(asked_);
    waiting_ = true;
    setState("running: evaluation " + std::to_string(search_->evaluations() + 1) + " of " + std::to_string(search_->budget()));
    evaluate_.fire();
  }

  /** Gives the targets their values back and says how the run ended. */
  void end(const std::string& how) {
    running_ = waiting_ = false;
    for (const auto& d : dims_)
      if (!targetsOf(d.port).empty()) publishMessage(d.port, apex::toMessage(d.before));
    const int n = search_->evaluations();
    setState(how + " after " + std::to_string(n) + " evaluation" + (n == 1 ? "" : "s") +
             (search_->best().empty() ? ""
                                      : "; best " + apex::toText(minimize_ ? -search_->bestFitness() : search_->bestFitness()) +
                                            " at " + bestText()));
    finished_.fire();
  }

  /** "" if every dimension still feeds a parameter, else which one does not. */
  std::string lostTarget() const {
    for (const auto& d : dims_)
      if (targetsOf(d.port).empty())
        return "dimension '" + d.port + "' lost its parameter (its node was removed, or the link cut)";
    return "";
  }

  /** What a dimension's output feeds now; nothing if the output is gone. */
  std::vector<apex::ParamTarget> targetsOf(const std::string& port) const {
    if (!interface().findOutput(port)) return {};
    return parameterTargets(port);
  }

  std::string bestText() const {
    if (search_->best().empty()) return "{}";
    const auto values = valuesAt(search_->best());
    std::string out = "{";
    for (std::size_t i = 0; i < dims_.size(); ++i) out += (i ? ", " : "") + dims_[i].port + ": " + apex::toText(values[i]);
    return out + "}";
  }

  void setState(const std::string& text) { updateParam(kState.name(), text); }
  /** An error that stays until the next start, through the firings that ignore a score. */
  void fail(const std::string& text) {
    error_ = text;
    reportError(text);
  }
  void again() {
    if (!error_.empty()) reportError(error_);
  }

  apex::Input<double> fitness_{this, kFitness};
  apex::Output<double> best_fitness_{this, kBestFitness};
  apex::Output<int> evaluations_{this, kEvaluations};
  apex::Output<std::string> best_{this, kBest};
  apex::Trigger evaluate_{this, kEvaluate};
  apex::Trigger finished_{this, kFinished};
  apex::Param<std::vector<std::string>> dimensions_{this, kDimensions};
  apex::Param<std::string> algorithm_{this, kAlgorithm};
  apex::Param<int> budget_{this, kBudget};
  apex::Param<int> seed_{this, kSeed};
  apex::Param<int> population_{this, kPopulation};
  apex::Param<double> f_{this, kF};
  apex::Param<double> cr_{this, kCR};
  apex::Param<bool> minimize_param_{this, kMinimize};
  apex::Param<std::string> state_{this, kState};
  apex::Param<std::string> study_path_{this, kStudy};

  std::vector<tuning::TunedDimension> dims_;
  std::unique_ptr<search::Search> search_;
  std::unique_ptr<tuning::StudyFile> study_;  // the run's, if it has one
  std::vector<double> asked_;  // the candidate out: its point in the search
  bool running_ = false;
  bool waiting_ = false;  // a candidate is out; its fitness is not back yet
  bool minimize_ = false;
  std::string error_;  // why the last run stopped, or the graph was saved mid-run
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Optimizer, "apex_nodes/Optimizer");
