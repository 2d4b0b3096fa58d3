// Optimizer: tunes other nodes' parameters against a fitness, as in the paper's §4.2. One output
// per tuned dimension feeds a parameter input; a run is an ask/tell loop through the graph:
// the node sends a candidate and fires `evaluate` (its events leave after its messages, so the
// values are in effect before the replay starts), the graph replays and scores the data, and the
// mean arrives at `fitness` (after the pass's last frame: the end-of-sequence token), which
// tells the search and sends the next candidate. No thread ever waits for an evaluation. With
// `workers` above 1, that many candidates are out at once, each in a copy of the evaluated part
// beside the graph (evaluation_copies.hpp) on threads of its own; the graph itself then rests.
// With `remote_workers`, other runtimes evaluate candidates too, each in its Optimizer of the same
// name (remote_workers.hpp); every Optimizer serves such requests while it runs no search itself
// (candidate_server.hpp). What it writes (values, front, state, study header): optimizer_texts.hpp.
#include <cmath>
#include <map>
#include <sstream>
#include <utility>

#include "apex/core/registry.hpp"
#include "apex_nodes/pareto.hpp"
#include "apex_nodes/remote_workers.hpp"
#include "apex_nodes/search.hpp"
#include "evaluation_copies.hpp"
#include "optimizer_ports.hpp"
#include "optimizer_texts.hpp"
#include "candidate_server.hpp"
#include "racing.hpp"
#include "reach.hpp"
#include "study_file.hpp"
#include "tuned_dimension.hpp"

namespace apex_nodes {
namespace param = apex::param;

namespace {
using Done = tuning::RemoteWorkers::Done;
}  // namespace

class Optimizer : public apex::Node, private OptimizerPorts {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Tunes other nodes' parameters: one output per dimension, connected to the parameter it tunes; "
               "each candidate is evaluated by the graph (evaluate: replay and score; the score comes back at fitness)")
        .inCategory("optimisation")
        .input(kFitness)
        .input(kRunning)
        .output(kBestFitness)
        .output(kEvaluations)
        .output(kBest)
        .slot("start", &Optimizer::start, "starts a run with the settings as they are now")
        .slot("stop", &Optimizer::stop, "ends the run; the tuned parameters get their values from before it back")
        .slot("apply_best", &Optimizer::applyBest, "sets the tuned parameters to the best values found")
        .slot("describe_space", &Optimizer::describeSpace,
              "sets space: the dimensions resolved against the parameters they tune, for a search outside the runtime")
        .trigger(kEvaluate)
        .trigger(kCut)
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
        .param(kSpace)
        .param(kStudy)
        .param(kWorkers)
        .param(kRemoteWorkers)
        .param(kRacing)
        .param(kRacingRule)
        .param(kRacingConfidence)
        .param(kFrameBound)
        .param(kObjectives)
        .param(kFront)
        .shapedBy([](const apex::ParamValues& p, apex::Manifest& m) {
          return tuning::addOutputs(p.get<std::vector<std::string>>(kDimensions.name()), m);  // one per dimension
        });
  }

  ~Optimizer() override {
    reach_->set(nullptr);  // first: nothing from other threads reaches it any more
    serving_.reset();  // waits for the requests under way to be handed over
    copies_.reset();  // the copies' taps call in until they stop
  }

  void setup() override {
    reach_->set(this);
    if (auto transport = tuning::remoteWorkers())
      serving_ = transport->serve(*this, [this](tuning::CandidateValues values, bool with_cost, Done reply) {
        auto shared = std::make_shared<Done>(std::move(reply));
        if (!reach_->later([this, values = std::move(values), with_cost, shared] { serve(values, with_cost, *shared); }))
          (*shared)({"the optimizer '" + name() + "' was removed", 0, 0});
      });
    const std::string saved = state_.get();
    if (saved.rfind("running", 0) != 0 && saved.rfind("starting", 0) != 0) return;
    updateParam(kState.name(), "interrupted (" + saved + ")");
    fail(tuning::interruptedText(saved, study_path_.get()));
  }

  /** The end of a sequence stops here: the outputs are values, not frames. */
  void endOfSequence() override { again(); }

  void parameterChanged(const std::string& name) override {
    if (name != kDimensions.name() || !running_) return;
    drop();  // its outputs are not the run's any more: nothing to give back through them
    setState("stopped: the dimensions changed during the run");
    fail("the dimensions changed during a run: it stopped after " + std::to_string(search_->evaluations()) +
         " evaluations; the tuned parameters keep the last candidate's values");
  }

  /** A fitness arrived (the evaluation asked for last is done), or a frame's mean so far. */
  void process() override {
    if (!running_ || copies_ || out_[0] < 0) return again();  // a score nobody asked for (e.g. a pass before the run)
    if (!hasInput(kFitness.name)) {
      if (hasInput(kRunning.name)) frameScored(0, *running_in_.get());
      return;
    }
    if (const std::string lost = lostTarget(); !lost.empty()) {
      out_[0] = -1;
      return stopFailing(lost + ": the run stopped after " + std::to_string(search_->evaluations()) +
                         " evaluations (the other tuned parameters got their values back)");
    }
    scored(0, *fitness_.get());
  }

  void start() {
    if (running_) throw std::invalid_argument("a run is in progress (" + state_.get() + "): stop it first, or wait for it");
    error_.clear();
    remotes_ = remote_workers_.get();
    remote_ = tuning::remoteWorkers();
    if (!remotes_.empty() && !remote_)
      throw std::invalid_argument("remote_workers: this host cannot reach other runtimes (the ROS runtime can)");
    server_.close("the optimizer '" + name() + "' there started a run of its own");
    auto dims = resolveDimensions();
    std::vector<search::Dimension> ranges;
    for (const auto& d : dims) ranges.insert(ranges.end(), d.coordinates.begin(), d.coordinates.end());
    search::Settings s;
    s.budget = budget_.get();
    s.seed = static_cast<unsigned>(seed_.get());
    s.population = population_.get();
    s.F = f_.get();
    s.CR = cr_.get();
    s.deferred = workersInAll() > 1;
    auto made = search::makeSearch(algorithm_.get(), ranges, s);
    if (!made) throw std::invalid_argument(made.message());
    auto search = std::move(made).value();
    const bool two = objectives_.get() == Objectives::kFitnessAndCost;
    auto study = tuning::openStudy(study_path_.get(),
                                   tuning::studySettingsText(algorithm_.get(), s, minimize_param_.get(), dimensions_.get(), two),
                                   ranges, two);
    const auto resumed = study ? tuning::replay(*study, *search, minimize_param_.get()) : std::vector<tuning::Scored>{};
    search_ = std::move(search);
    study_ = std::move(study);
    dims_ = std::move(dims);
    minimize_ = minimize_param_.get();
    two_ = two;
    front_.clear(), costs_.clear();
    if (two_) {
      for (const auto& e : resumed) tuning::addToFront(front_, e, minimize_);
      updateParam(kFront.name(), tuning::frontText(dims_, front_));
    }
    running_ = true;
    local_ = workers_.get();
    out_.assign(local_ + remotes_.size(), -1);
    remote_done_.assign(remotes_.size(), 0);
    racing_.start(racing_param_.get(), racing_rule_.get(), racing_confidence_.get(), frame_bound_param_.get(), minimize_,
                  out_.size());
    points_.clear(), scores_.clear();
    if (!resumed.empty())
      log(apex::LogLevel::Info,
          "resumed from the study '" + study_->path() + "': " + std::to_string(resumed.size()) + " evaluations");
    if (search_->done()) return end("finished");
    if (!inCopies()) return propose();
    setState("starting: copying the evaluated part for " +
             (local_ > 1 || !remotes_.empty() ? std::to_string(local_) + " workers" : std::string("its cost")));
    describeGraph([this, run = run_](const apex::GraphSnapshot& graph) { makeCopies(graph, run); });
  }

  void stop() {
    if (running_) end("stopped");
  }

  void describeSpace() { updateParam(kSpace.name(), tuning::spaceText(resolveDimensions())); }

  void applyBest() {
    if (running_) throw std::invalid_argument("a run is in progress (" + state_.get() + "): stop it first, or wait for it");
    if (!search_ || search_->best().empty()) throw std::invalid_argument("no best values yet: run the optimiser first");
    sendAll(search_->best());
    setState("applied the best values " + bestText());
  }

 private:
  /** Every dimension resolved against the parameter it tunes (the first, if it tunes several). */
  std::vector<tuning::TunedDimension> resolveDimensions() const {
    return tuning::resolveAll(dimensions_.get(), [this](const std::string& output) { return parameterTargets(output); });
  }

  void sendAll(const std::vector<double>& x) {
    const auto values = tuning::valuesAt(dims_, x);
    for (std::size_t i = 0; i < dims_.size(); ++i) publishMessage(dims_[i].port, apex::toMessage(values[i]));
  }

  /** The copies for workers beyond the graph, then the first candidates out. */
  void makeCopies(const apex::GraphSnapshot& graph, int run) {
    if (!running_ || run != run_) return;  // stopped meanwhile
    auto part = tuning::evaluatedPart(graph.description, name());
    auto sent = [this, run](int copy, const std::string& input, double v) {
      runLater([this, run, copy, fitness = input == kFitness.name, v] {
        if (!running_ || run != run_ || out_[copy] < 0) return;  // a run that ended, or a pass nobody asked for
        fitness ? scored(copy, v) : frameScored(copy, v);
      });
    };
    auto copies = part ? tuning::EvaluationCopies::make(part.value(), graph.makeGraph, static_cast<int>(local_), sent)
                       : apex::Result<std::unique_ptr<tuning::EvaluationCopies>>(part.status());
    if (!copies) return stopFailing("workers " + std::to_string(local_) + ": " + copies.message());
    copies_ = std::move(copies).value();
    propose();
  }

  /** Racing: one more frame of worker `w`'s pass scored, its mean so far `mean`; cut it once it
   *  cannot reach what the search needs of it. */
  void frameScored(std::size_t w, double mean) {
    const bool cut = racing_.frame(w, mean, search_->threshold(out_[w]), search_->rival(out_[w]));
    sayIfRacingOff();
    if (!cut) return;
    if (!copies_) return cut_.fire();
    if (auto st = copies_->fire(static_cast<int>(w), kCut.name); !st)
      stopFailing("worker " + std::to_string(w + 1) + ": " + st.message());
  }

  /** Worker `w`'s pass ended with `f`: a whole pass's mean, or a cut one's, which counts as the
   *  bound it was cut at (the most it could have scored, below what it needed). */
  void scored(std::size_t w, double f) {
    const int id = std::exchange(out_[w], -1);
    if (two_ && copies_ && w < local_) costs_[id] = copies_->msPerFrame(static_cast<int>(w));
    const double counted = w < local_ ? racing_.ended(w, id, f) : f;  // a remote pass is never cut
    sayIfRacingOff();
    told(id, counted);
  }

  /** Racing turned itself off for the rest of the run: why, logged once. */
  void sayIfRacingOff() {
    if (const std::string why = racing_.takeWhyOff(); !why.empty())
      log(apex::LogLevel::Warn, "racing is off for this run: " + why);
  }

  /** Candidate `id` scored `f`: the search told, each evaluation it takes written to the study. */
  void told(int id, double f) {
    const int before = search_->evaluations();
    search_->tell(id, minimize_ ? -f : f);
    scores_[id] = f;
    for (int k = before; k < search_->evaluations(); ++k) {
      const tuning::Evaluation e{points_.at(k), scores_.at(k), costs_[k]};
      points_.erase(k), scores_.erase(k), costs_.erase(k);
      if (two_ && tuning::addToFront(front_, {k + 1, e.fitness, e.cost_ms, e.point}, minimize_))
        updateParam(kFront.name(), tuning::frontText(dims_, front_));
      if (study_) try {
          study_->append(e);
        } catch (const std::runtime_error& err) {
          return stopFailing(std::string(err.what()) + ": the run stopped after " + std::to_string(k) + " evaluations");
        }
    }
    best_fitness_.publish(bestFitness());
    evaluations_.publish(search_->evaluations());
    best_.publish(bestText());
    updateParam(kBestValues.name(), bestText());
    if (search_->done()) return end("finished");
    propose();
  }

  /** A candidate to each idle worker the search has one for: into the graph through the outputs,
   *  then `evaluate` (events leave after the messages); into a copy through its parameters. */
  void propose() {
    for (std::size_t w = 0; w < out_.size() && search_->canAsk(); ++w) {
      if (out_[w] >= 0) continue;
      const int id = search_->asked();
      const auto x = search_->ask();
      points_[id] = x;
      out_[w] = id;
      if (w >= local_) {
        askRemote(w, x);
      } else if (!copies_) {
        sendAll(x);
        evaluate_.fire();
      } else if (auto st = copies_->evaluate(static_cast<int>(w), tuning::valueTexts(dims_, x)); !st) {
        return stopFailing("worker " + std::to_string(w + 1) + ": " + st.message());
      }
    }
    setState(tuning::runningText(search_->evaluations() + 1, search_->budget(), out_.size(), remotes_.size()));
  }

  /** The run is over: nothing out counts any more, the copies go. */
  void drop() {
    running_ = false;
    ++run_;
    out_.assign(out_.size(), -1);
    racing_.reset(out_.size());
    copies_.reset();
  }

  /** Gives the targets their values back and says how the run ended. */
  void end(const std::string& how) {
    const bool in_copies = inCopies();
    drop();
    if (!in_copies)  // with copies the graph rested: nothing to give back
      for (const auto& d : dims_)
        if (!targetsOf(d.port).empty()) publishMessage(d.port, apex::toMessage(d.before));
    setState(tuning::endText({how, search_->evaluations(), racing_.asked() ? racing_.summary() : "",
                              search_->best().empty() ? "" : bestText(), bestFitness(),
                              two_ ? std::optional<std::size_t>(front_.size()) : std::nullopt,
                              tuning::remoteText(remotes_, remote_done_)}));
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

  /** The best values so far as a YAML map; "{}" before the first evaluation. */
  std::string bestText() const { return search_->best().empty() ? "{}" : tuning::valuesText(dims_, search_->best()); }
  /** The best fitness so far, as the graph scored it. */
  double bestFitness() const { return minimize_ ? -search_->bestFitness() : search_->bestFitness(); }

  /** Candidates are evaluated in copies of the evaluated part, not in the graph (with remote
   *  workers too: an answer comes between firings, when the graph's receivers may not have read
   *  the last firing's messages, so a candidate could not go out into the graph then). */
  bool inCopies() const { return local_ > 1 || two_ || !remotes_.empty(); }
  /** The workers here and in other runtimes. */
  std::size_t workersInAll() const { return workers_.get() + remote_workers_.get().size(); }

  /** Worker `w`, in another runtime, evaluates `x`; its answer comes to answered(). */
  void askRemote(std::size_t w, const std::vector<double>& x) {
    const std::string runtime = remotes_[w - local_];
    remote_->evaluate(runtime, name(), tuning::valueTexts(dims_, x), two_,
                      [this, reach = reach_, run = run_, w, runtime](tuning::RemoteOutcome o) {
                        reach->later([this, run, w, runtime, o] { answered(run, w, runtime, o); });
                      });
  }

  void answered(int run, std::size_t w, const std::string& runtime, const tuning::RemoteOutcome& o) {
    if (!running_ || run != run_ || out_[w] < 0) return;  // a run that ended meanwhile
    if (!o.error.empty())
      return stopFailing("remote worker " + runtime + ": " + o.error + ": the run stopped after " +
                         std::to_string(search_->evaluations()) + " evaluations" +
                         (study_path_.get().empty() ? "" : " (start it again: it continues from its study)"));
    if (two_) costs_[out_[w]] = o.ms_per_frame;
    ++remote_done_[w - local_];
    scored(w, o.fitness);
  }

  /** A request from another runtime's Optimizer: evaluated here unless a run of its own goes on. */
  void serve(tuning::CandidateValues values, bool with_cost, const Done& reply) {
    if (running_) return reply({"the optimizer '" + name() + "' there runs a search of its own (" + state_.get() + ")", 0, 0});
    server_.ask(name(), std::move(values), with_cost, reply, workers_.get());
  }

  void setState(const std::string& text) { updateParam(kState.name(), text); }
  /** An error that stays until the next start, through the firings that ignore a score. */
  void fail(const std::string& text) {
    error_ = text;
    reportError(text);
  }
  /** The run stops, `why` its error (worded before it stops: stopping changes nothing it names). */
  void stopFailing(const std::string& why) {
    end("stopped");
    fail(why);
  }
  void again() {
    if (!error_.empty()) reportError(error_);
  }

  apex::Input<double> fitness_{this, kFitness};
  apex::Input<double> running_in_{this, kRunning};
  apex::Trigger cut_{this, kCut};
  apex::Param<bool> racing_param_{this, kRacing};
  apex::Choice<tuning::RacingRule> racing_rule_{this, kRacingRule};
  apex::Param<double> racing_confidence_{this, kRacingConfidence};
  apex::Param<double> frame_bound_param_{this, kFrameBound};
  apex::Output<double> best_fitness_{this, kBestFitness};
  apex::Output<int> evaluations_{this, kEvaluations};
  apex::Output<std::string> best_{this, kBest};
  apex::Trigger evaluate_{this, kEvaluate};
  apex::Trigger finished_{this, kFinished};
  apex::Param<std::vector<std::string>> dimensions_{this, kDimensions};
  apex::Choice<search::Algorithm> algorithm_{this, kAlgorithm};
  apex::Param<int> budget_{this, kBudget};
  apex::Param<int> seed_{this, kSeed};
  apex::Param<int> population_{this, kPopulation};
  apex::Param<double> f_{this, kF};
  apex::Param<double> cr_{this, kCR};
  apex::Param<bool> minimize_param_{this, kMinimize};
  apex::Param<std::string> state_{this, kState};
  apex::Param<std::string> study_path_{this, kStudy};
  apex::Param<int> workers_{this, kWorkers};
  apex::Param<std::vector<std::string>> remote_workers_{this, kRemoteWorkers};
  apex::Choice<Objectives> objectives_{this, kObjectives};

  std::vector<tuning::TunedDimension> dims_;
  std::unique_ptr<search::Search> search_;
  std::unique_ptr<tuning::StudyFile> study_;  // the run's, if it has one
  std::unique_ptr<tuning::EvaluationCopies> copies_;  // the workers, if more than one (else the graph evaluates)
  std::vector<int> out_{-1};  // per worker (here, then remote): the candidate it evaluates, -1: idle
  std::size_t local_ = 1;  // workers here, the first of out_
  std::vector<std::string> remotes_;  // the run's remote workers, after those here
  std::vector<int> remote_done_;  // per remote worker: candidates it evaluated
  std::shared_ptr<tuning::RemoteWorkers> remote_;  // the run's transport
  std::shared_ptr<tuning::Reach> reach_ = std::make_shared<tuning::Reach>();
  std::shared_ptr<void> serving_;  // while set, other runtimes' Optimizers can send candidates here
  tuning::CandidateServer server_{{[this](auto done) { describeGraph(std::move(done)); },
                                   [this](std::function<void()> fn) { reach_->later(std::move(fn)); },
                                   [this](const std::string& text) { setState(text); }}};
  std::map<int, std::vector<double>> points_;  // candidates asked for and not yet written to the study
  std::map<int, double> scores_;  // their fitnesses, as they come (in any order)
  std::map<int, double> costs_;  // with two objectives: their costs, as they come
  bool two_ = false;  // the run has two objectives
  std::vector<tuning::Scored> front_;  // with two objectives: the Pareto front so far
  int run_ = 0;  // grows as a run ends: a copy's score of an earlier run is ignored
  tuning::Racing racing_;
  bool running_ = false;
  bool minimize_ = false;
  std::string error_;  // why the last run stopped, or the graph was saved mid-run
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Optimizer, "apex_nodes/Optimizer");
