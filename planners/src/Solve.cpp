#include "kautham/planners/Solve.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include <ompl/base/PlannerData.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/control/PathControl.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "kautham/planners/BeliefReporter.h"
#include "kautham/planners/BeliefVertex.h"
#include "kautham/planners/ControlReporter.h"
#include "kautham/planners/DeadlinePlanner.h"
#include "kautham/planners/ParallelPlanner.h"
#include "kautham/planners/PlannerEntry.h"
#include "kautham/planners/PlannerRegistry.h"

namespace kautham::planners {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::vector<physics::ControlStep> controlsOf(const ompl::control::PathControl& path,
                                             std::size_t controlCount, double stepSize) {
  std::vector<physics::ControlStep> steps;
  for (std::size_t i = 0; i < path.getControlCount(); ++i) {
    const auto* values =
        path.getControl(i)->as<ompl::control::RealVectorControlSpace::ControlType>()->values;
    const double duration = path.getControlDuration(i);
    steps.push_back({std::vector<double>(values, values + controlCount),
                     static_cast<unsigned>(std::lround(duration / stepSize))});
  }
  return steps;
}

/// Stops the planner when asked to, and reports progress on the way.
ompl::base::PlannerTerminationCondition watcher(const physics::PlanningContext& context,
                                                const SolveHooks& hooks, Clock::time_point start) {
  auto lastReport = std::make_shared<double>(0.0);
  return ompl::base::PlannerTerminationCondition([&context, hooks, start, lastReport] {
    if (hooks.progress) {
      const double elapsed = secondsSince(start);
      if (elapsed - *lastReport >= 0.5) {
        *lastReport = elapsed;
        const auto& counters = context.propagator().counters();
        hooks.progress(
            {elapsed, counters.propagations, counters.physicsSteps, context.goal().bestDistance()});
      }
    }
    return hooks.stop && hooks.stop();
  });
}

SearchTree treeOf(const ompl::base::PlannerData& data, const physics::PlanningContext& context) {
  SearchTree tree;
  const std::size_t count = data.numVertices();
  tree.parent.assign(count, -1);
  for (unsigned i = 0; i < count; ++i) {
    const double* state = physics::WorldStateSpace::values(data.getVertex(i).getState());
    tree.endEffector.push_back(context.layout().goalLinkPosition(state));
    tree.goalDistance.push_back(context.goal().distance(state));
    if (const auto* vertex = dynamic_cast<const BeliefVertex*>(&data.getVertex(i)))
      tree.belief.push_back(vertex->belief());
    std::vector<unsigned> children;
    data.getEdges(i, children);
    for (unsigned child : children) tree.parent[child] = static_cast<int>(i);
  }
  return tree;
}

}  // namespace

std::uint32_t seedRandomness(std::uint32_t seed) {
  if (seed == 0) return ompl::RNG::getSeed();
  // OMPL complains when it is reseeded after generators exist (tests plan several times in one
  // process); reseeding still fixes every generator made afterwards, which is all we need.
  const ompl::msg::LogLevel level = ompl::msg::getLogLevel();
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  ompl::RNG::setSeed(seed);
  ompl::msg::setLogLevel(level);
  return seed;
}

ompl::base::PlannerPtr makePlanner(physics::PlanningContext& context, const PlanRequest& request) {
  const PlannerRegistry::Entry& entry = plannerRegistry().at(request.planner);
  context.usePlanningRules(physics::ValidityRules::Full);  // a planner may narrow them
  ompl::base::PlannerPtr planner = entry.create(request.parameters, context);
  if (!planner) throw std::logic_error("planner " + request.planner + " made no planner");
  declareOmplParameters(*planner, request.parameters);
  declareOmplParameters(*planner, request.common);
  return planner;
}

PlanOutcome solve(physics::PlanningContext& context, const PlanRequest& request,
                  const SolveHooks& hooks) {
  ompl::base::PlannerPtr planner = makePlanner(context, request);
  context.problemDefinition()->clearSolutionPaths();
  context.goal().resetBestDistance();
  planner->setProblemDefinition(context.problemDefinition());
  planner->setup();
  if (auto* parallel = dynamic_cast<ParallelPlanner*>(planner.get()))
    parallel->setThreads(request.threads());  // other planners run in this thread alone

  const physics::PropagationCounters before = context.propagator().counters();
  const Clock::time_point start = Clock::now();
  if (auto* timed = dynamic_cast<DeadlinePlanner*>(planner.get()))
    timed->setDeadline(start + std::chrono::duration_cast<Clock::duration>(
                                   std::chrono::duration<double>(request.timeLimit())));
  const ompl::base::PlannerStatus status = planner->solve(ompl::base::plannerOrTerminationCondition(
      ompl::base::timedPlannerTerminationCondition(request.timeLimit()),
      watcher(context, hooks, start)));

  PlanOutcome outcome;
  outcome.statistics.planningTime = secondsSince(start);
  const physics::PropagationCounters after = context.propagator().counters();
  outcome.statistics.propagations = after.propagations - before.propagations;
  outcome.statistics.physicsSteps = after.physicsSteps - before.physicsSteps;
  ompl::base::PlannerData data(context.spaceInformation());
  planner->getPlannerData(data);
  outcome.statistics.treeStates = data.numVertices();
  outcome.tree = treeOf(data, context);
  planner->params().getParams(outcome.omplParameters);
  for (const auto& [name, value] : planner->getPlannerProgressProperties())
    if (name.rfind("iterations", 0) != 0)  // not all planners count them the same way
      outcome.statistics.plannerProperties.emplace_back(name.substr(0, name.find(' ')), value());

  if (const auto* reporter = dynamic_cast<const FailureReporter*>(planner.get())) {
    outcome.sampledFailures = reporter->sampledFailures();
    outcome.candidateFailures = reporter->candidateFailures();
    outcome.steeredFailures = reporter->steeredFailures();
  }

  const auto& pdef = context.problemDefinition();
  if (pdef->hasSolution()) {
    outcome.solved = status == ompl::base::PlannerStatus::EXACT_SOLUTION;
    outcome.approximate = !outcome.solved;
    outcome.goalDistance = pdef->getSolutionDifference();
    const auto& path = static_cast<const ompl::control::PathControl&>(*pdef->getSolutionPath());
    const auto& si = context.spaceInformation();
    outcome.controls =
        controlsOf(path, si->getControlSpace()->getDimension(), si->getPropagationStepSize());
    if (const auto* reporter = dynamic_cast<const ControlReporter*>(planner.get()))
      outcome.controls = reporter->solutionControls();
    if (const auto* reporter = dynamic_cast<const BeliefReporter*>(planner.get()))
      outcome.beliefs = reporter->solutionBeliefs();
  }
  return outcome;
}

}  // namespace kautham::planners
