// The Optimizer's ports, events and parameters (optimizer.cpp), declared once: its manifest lists
// them and its handles read them.
#pragma once

#include <string>
#include <vector>

#include "apex/core/declare.hpp"
#include "apex/core/ports.hpp"
#include "apex_nodes/search.hpp"
#include "racing.hpp"

namespace apex_nodes {

struct OptimizerPorts {
  static inline const apex::InputPort<double> kFitness{
      "fitness", "the candidate's score, e.g. SequenceMean's mean; larger is better unless minimize", true};
  static inline const apex::InputPort<double> kRunning{
      "running", "for racing: each frame, the candidate's mean so far (SequenceMean's running)", true};
  static inline const apex::OutputPort<double> kBestFitness{"best_fitness", "after each evaluation: the best fitness so far"};
  static inline const apex::OutputPort<int> kEvaluations{"evaluations", "after each evaluation: how many are done"};
  static inline const apex::OutputPort<std::string> kBest{
      "best", "after each evaluation: the best values so far, as YAML ({c: 12.5, block_size: 31})"};
  static inline const apex::TriggerPort kEvaluate{
      "evaluate",
      "a candidate's values are in effect: replay the data (a player's restart) and start the "
      "score (SequenceMean's reset)"};
  static inline const apex::TriggerPort kCut{
      "cut",
      "racing: the candidate cannot reach what it needs to (the best so far, or the member it competes with): end its "
      "pass now (a player's end_pass)"};
  static inline const apex::TriggerPort kFinished{"finished",
                                                  "the run ended (its budget is spent, or stop): the best values are known"};
  static inline const apex::ParamDecl<std::vector<std::string>> kDimensions =
      apex::param::textList("dimensions")
          .describe(
              "one output each: 'name [min max] [int]', 'name interval [min max]' (both ends), 'name choice "
              "[option ...]' or 'name bool', e.g. 'c 0 60', 'block_size int', 'area interval 500 20000', 'method "
              "choice'; without min and max (options), the range (options) of the parameter it is connected to")
          .shapesInterface();
  static inline const apex::ChoiceDecl<search::Algorithm> kAlgorithm =
      apex::param::choice<search::Algorithm>("algorithm", search::algorithms());
  static inline const apex::ParamDecl<int> kBudget =
      apex::param::integer("budget").range(1, 1000000).step(1).init(60).describe("evaluations in a run");
  static inline const apex::ParamDecl<int> kSeed =
      apex::param::integer("seed").range(0, 1000000000).step(1).init(1).describe("the same seed gives the same candidates");
  static inline const apex::ParamDecl<int> kPopulation =
      apex::param::integer("population")
          .range(0, 10000)
          .step(1)
          .describe("differential evolution: candidates per generation; 0: 15 per dimension, at least 5");
  static inline const apex::ParamDecl<double> kF =
      apex::param::number("F").range(0.0, 2.0).step(0.05).init(0.8).describe("differential evolution: differential weight");
  static inline const apex::ParamDecl<double> kCR =
      apex::param::number("CR").range(0.0, 1.0).step(0.05).init(0.9).describe("differential evolution: crossover probability");
  static inline const apex::ParamDecl<bool> kMinimize = apex::param::flag("minimize").describe("smaller fitness is better");
  static inline const apex::ParamDecl<std::string> kState =
      apex::param::text("state").init("idle").describe("what the optimiser is doing (it sets this; saved with the graph)");
  static inline const apex::ParamDecl<std::string> kBestValues =
      apex::param::text("best_values")
          .describe(
              "the best values so far as YAML, {dimension: value} (it sets this; the panel's "
              "'Apply best values' sets them on the tuned parameters as one undoable edit)");
  static inline const apex::ParamDecl<std::string> kSpace = apex::param::text("space").describe(
      "what describe_space found: each dimension as resolved against the parameter it tunes, as YAML (it sets "
      "this; python/apex/tuning.py samples it with Optuna)");
  static inline const apex::ParamDecl<std::string> kStudy =
      apex::param::path("study")
          .mode(apex::PathMode::Write)
          .describe(
              "a file where each evaluation is written as it ends: a run started again with the same settings "
              "(after a stop, a crash or a kill) continues from it; empty: none");
  static inline const apex::ParamDecl<int> kWorkers = apex::param::integer("workers").range(1, 64).step(1).init(1).describe(
      "candidates evaluated at once (e.g. one per core); above 1, each in a copy of the part the fitness comes "
      "from, made when a run starts, on threads of its own, while the graph rests; differential evolution then "
      "replaces members once a generation is scored (scipy's deferred updating)");
  static inline const apex::ParamDecl<bool> kRacing = apex::param::flag("racing").describe(
      "stop scoring a candidate once it cannot count, by racing_rule (cut fires): the same course (bound) or nearly "
      "(paired) on fewer frames; needs running and cut connected");
  static inline const apex::ChoiceDecl<tuning::RacingRule> kRacingRule =
      apex::param::choice<tuning::RacingRule>(
          "racing_rule", {{"paired", tuning::RacingRule::kPaired,
                           "also once it is clearly worse, frame by frame, than the evaluation it must beat (a paired t-test at "
                           "racing_confidence, after 5 frames): far fewer frames, nearly the same course"},
                          {"bound", tuning::RacingRule::kBound,
                           "only once even the best frame scores for the rest of its pass could not make it count: exactly the "
                           "course of whole passes"}})
          .describe("racing: when a candidate's pass is cut");
  static inline const apex::ParamDecl<double> kRacingConfidence =
      apex::param::number("racing_confidence")
          .range(0.5, 0.999)
          .step(0.01)
          .init(0.95)
          .describe("racing_rule paired: how sure it must be that a candidate loses before its pass is cut");
  static inline const apex::ParamDecl<std::vector<std::string>> kRemoteWorkers =
      apex::param::textList("remote_workers")
          .describe(
              "other runtimes (e.g. /robot2/apex, on this machine or another) whose Optimizer of the same name evaluates "
              "candidates too, one at a time each, beside the workers here: they load the same graph and reach the same "
              "files; a runtime named twice evaluates two at once if its Optimizer has two workers");
  enum class Objectives { kFitness, kFitnessAndCost };
  static inline const apex::ChoiceDecl<Objectives> kObjectives =
      apex::param::choice<Objectives>(
          "objectives",
          {{"fitness", Objectives::kFitness},
           {"fitness_and_cost", Objectives::kFitnessAndCost,
            "also the cost, the ms per frame the tuned nodes and those they feed fire for, measured in a copy of the "
            "evaluated part (as with workers): the run keeps the candidates no other beats on both in 'front'"}})
          .describe("what a candidate is judged by");
  static inline const apex::ParamDecl<std::string> kFront = apex::param::text("front").describe(
      "with two objectives, the Pareto front so far, cheapest first, as YAML ([{evaluation: 7, fitness: 0.9, "
      "ms_per_frame: 3.1, values: {c: 12}}, ...]; it sets this; the panel's menu applies a point of it)");
  static inline const apex::ParamDecl<double> kFrameBound =
      apex::param::number("frame_score_bound")
          .range(-1e9, 1e9)
          .step(0.1)
          .init(1.0)
          .describe("racing: the best score a single frame can have (1 for F1 or accuracy; with minimize, the least)");
};

}  // namespace apex_nodes
