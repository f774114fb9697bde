#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <ompl/base/Planner.h>

#include "kautham/physics/Replay.h"
#include "kautham/planners/FailureReporter.h"
#include "kautham/planners/PlanRequest.h"

namespace kautham::planners {

/// A snapshot of a running planner, for progress displays.
struct Progress {
  double elapsed = 0.0;  ///< seconds
  std::uint64_t propagations = 0;
  std::uint64_t physicsSteps = 0;
  double bestGoalDistance = 0.0;  ///< metres: how close the search has come to the goal
};

struct SolveHooks {
  std::function<void(const Progress&)> progress;  ///< called about twice a second
  std::function<bool()> stop;                     ///< true: stop planning now (Ctrl-C)
};

struct PlanStatistics {
  double planningTime = 0.0;  ///< seconds of wall-clock time in the planner
  std::size_t treeStates = 0;
  std::uint64_t propagations = 0;
  std::uint64_t physicsSteps = 0;
  /// The planner's own counters (OMPL progress properties: p-KPIECE's cells, candidates,
  /// particles, mean solution belief), as name and text.
  std::vector<std::pair<std::string, std::string>> plannerProperties;
};

/// The planner's tree as the end effector saw it: where each state put the goal link.
struct SearchTree {
  std::vector<Eigen::Vector3d> endEffector;  ///< one per tree state
  std::vector<int> parent;                   ///< index of the parent state, -1 for roots
  std::vector<double> goalDistance;          ///< metres from the goal region's centre
  std::vector<double> belief;  ///< per tree state, when the planner judges robustness (p-KPIECE)
};

struct PlanOutcome {
  bool solved = false;  ///< an exact solution: the goal region was reached
  bool approximate = false;
  double goalDistance = 0.0;
  std::vector<physics::ControlStep> controls;
  std::vector<double> beliefs;  ///< per control, when the planner judges robustness (p-KPIECE)
  /// Why the motions the planner ran in sampled worlds failed (p-KPIECE's particles), most
  /// frequent first; empty for planners that run none.
  std::vector<FailureCount> sampledFailures;
  /// Why candidate motions, run once as planned, stopped at a broken rule (FailureReporter),
  /// and of those the ones the planner aimed at the goal; empty for planners that do not say.
  std::vector<FailureCount> candidateFailures;
  std::vector<FailureCount> steeredFailures;
  PlanStatistics statistics;
  SearchTree tree;
  /// The planner's OMPL parameter set after setup, name -> value: every parameter of the
  /// request (see makePlanner), as OMPL's benchmark tools record planner settings.
  std::map<std::string, std::string> omplParameters;
};

/// Seeds every random number generator the planners use (OMPL's), before anything samples.
/// Seed 0 means "pick one": the seed in use is returned either way.
std::uint32_t seedRandomness(std::uint32_t seed);

/// The requested planner from the registry, made over the context (full validity rules unless
/// the planner narrows them) with the request's values. Every parameter, the planner's own and
/// the common ones, is on its OMPL parameter set (declareParam), with its value.
ompl::base::PlannerPtr makePlanner(physics::PlanningContext& context, const PlanRequest& request);

/// Runs the requested planner on a context until it solves, the time limit passes or
/// `hooks.stop` says so. Deterministic for a seed when it solves before the limit.
PlanOutcome solve(physics::PlanningContext& context, const PlanRequest& request,
                  const SolveHooks& hooks = {});

}  // namespace kautham::planners
