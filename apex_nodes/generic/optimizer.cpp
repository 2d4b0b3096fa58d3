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

namespace apex_nodes {
namespace param = apex::param;

namespace {

/** One entry of `dimensions`: "name [min max] [int]". */
struct DimensionText {
  std::string name;
  bool has_range = false;
  double min = 0, max = 0;
  bool integer = false;
};

bool readNumber(const std::string& word, double& out) {
  std::istringstream in(word);
  return (in >> out) && in.peek() == EOF && std::isfinite(out);
}

apex::Result<DimensionText> parseDimension(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  const std::string how = "write 'name', 'name min max', 'name int' or 'name min max int', e.g. 'block_size 3 51 int'";
  if (words.empty()) return apex::Status::error("an empty dimension: " + how);
  DimensionText d;
  d.name = words[0];
  std::size_t i = 1;
  if (words.size() >= 3 && readNumber(words[1], d.min) && readNumber(words[2], d.max)) {
    d.has_range = true;
    i = 3;
    if (d.min > d.max) return apex::Status::error("dimension '" + text + "': min is above max");
  }
  if (i < words.size() && words[i] == "int") d.integer = true, ++i;
  if (i != words.size()) return apex::Status::error("dimension '" + text + "': cannot read '" + words[i] + "'; " + how);
  return d;
}

/** One output per dimension: int or double, as the parameter it feeds. */
apex::Status shapeDimensions(const apex::ParamValues& p, apex::Manifest& m) {
  for (const auto& text : p.get<std::vector<std::string>>("dimensions")) {
    auto d = parseDimension(text);
    if (!d) return d.status();
    m.outputs.push_back({d->name, d->integer ? apex::typeOf<int>() : apex::typeOf<double>(), false,
                         "the candidate's value of '" + d->name + "': connect it to the parameter it tunes"});
  }
  return apex::Status::ok();
}

std::string number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
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
              "one output each: 'name [min max] [int]', e.g. 'c 0 60' or 'block_size int'; without "
              "min and max, the range of the parameter its output is connected to")
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
        .shapedBy(shapeDimensions);
  }

  void setup() override {
    const std::string saved = state_.get();
    if (saved.rfind("running", 0) != 0) return;
    updateParam(kState.name(), "interrupted (" + saved + ")");
    fail("this graph was saved while a run was in progress (" + saved +
         "): the tuned parameters hold that candidate's values, not tuned ones; start a new run");
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
    for (const auto& d : dims) ranges.push_back(d.range);
    search::Settings s;
    s.budget = budget_.get();
    s.seed = static_cast<unsigned>(seed_.get());
    s.population = population_.get();
    s.F = f_.get();
    s.CR = cr_.get();
    auto made = search::makeSearch(algorithm_.get(), std::move(ranges), s);
    if (!made) throw std::invalid_argument(made.message());
    search_ = std::move(made).value();
    dims_ = std::move(dims);
    minimize_ = minimize_param_.get();
    running_ = true;
    propose();
  }

  void stop() {
    if (running_) end("stopped");
  }

  void applyBest() {
    if (running_) throw std::invalid_argument("a run is in progress (" + state_.get() + "): stop it first, or wait for it");
    if (!search_ || search_->best().empty()) throw std::invalid_argument("no best values yet: run the optimiser first");
    for (std::size_t i = 0; i < dims_.size(); ++i) send(dims_[i], snap(dims_[i], search_->best()[i]));
    setState("applied the best values " + bestText());
  }

 private:
  struct Dim {
    std::string port;
    search::Dimension range;
    double step = 0, origin = 0;  // integers on a grid (e.g. odd sizes: 3, 5, ...): the target's step
    apex::ParamValue before;  // what the (first) target held when the run started
  };

  /** Every dimension with its range (given, or the target's) and the value to give back. */
  std::vector<Dim> resolveDimensions() const {
    std::vector<Dim> out;
    for (const auto& text : dimensions_.get()) {
      const DimensionText d = parseDimension(text).value();  // the interface function read it already
      const auto targets = parameterTargets(d.name);
      if (targets.empty())
        throw std::invalid_argument("dimension '" + d.name +
                                    "': its output feeds no parameter; connect it to the "
                                    "parameter it tunes");
      const apex::ParamSpec& spec = targets.front().spec;
      const std::string where = targets.front().node + "/" + spec.name;
      Dim dim;
      dim.port = d.name;
      dim.range = {d.name, d.min, d.max, d.integer};
      dim.before = targets.front().value;
      if (spec.max > spec.min) {  // within the parameter's range, whatever the dimension says
        dim.range.min = d.has_range ? std::max(d.min, spec.min) : spec.min;
        dim.range.max = d.has_range ? std::min(d.max, spec.max) : spec.max;
        if (dim.range.min > dim.range.max)
          throw std::invalid_argument("dimension '" + text + "' lies outside the range of " + where + " [" + number(spec.min) +
                                      ", " + number(spec.max) + "]");
      } else if (!d.has_range) {
        throw std::invalid_argument("dimension '" + d.name + "': " + where + " has no range; give one, e.g. '" + d.name +
                                    " 0 10'");
      }
      if (d.integer && spec.step > 1) dim.step = spec.step, dim.origin = spec.min;
      out.push_back(dim);
    }
    if (out.empty()) throw std::invalid_argument("no dimensions: add one per parameter to tune, e.g. 'c 0 60'");
    return out;
  }

  /** On the target's grid and within the range. */
  static double snap(const Dim& d, double x) {
    if (d.range.integer) x = std::round(x);
    if (d.step <= 0) return x;
    double v = d.origin + std::round((x - d.origin) / d.step) * d.step;
    while (v > d.range.max && v - d.step >= d.origin) v -= d.step;
    while (v < d.range.min) v += d.step;
    return v;
  }

  void send(const Dim& d, double v) {
    if (d.range.integer) {
      publishMessage(d.port, apex::Message::make<int>(static_cast<int>(std::lround(v))));
    } else {
      publishMessage(d.port, apex::Message::make<double>(v));
    }
  }

  /** The next candidate out, then `evaluate` (events leave after the messages). */
  void propose() {
    const auto x = search_->ask();
    for (std::size_t i = 0; i < dims_.size(); ++i) send(dims_[i], snap(dims_[i], x[i]));
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
    std::string out = "{";
    for (std::size_t i = 0; i < dims_.size() && i < search_->best().size(); ++i) {
      const double v = snap(dims_[i], search_->best()[i]);
      out += (i ? ", " : "") + dims_[i].port + ": " +
             (dims_[i].range.integer ? apex::toText(static_cast<int>(std::lround(v))) : apex::toText(v));
    }
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

  std::vector<Dim> dims_;
  std::unique_ptr<search::Search> search_;
  bool running_ = false;
  bool waiting_ = false;  // a candidate is out; its fitness is not back yet
  bool minimize_ = false;
  std::string error_;  // why the last run stopped, or the graph was saved mid-run
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Optimizer, "apex_nodes/Optimizer");
