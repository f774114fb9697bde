// Sleeping objects: how much faster the planner's inner loop (propagate, then check) runs on
// the dense suite when objects at rest sleep (<Physics sleep="true">, the default) than when
// every object is stepped (sleep="false"). See docs/performance.md, "Sleeping objects".
//
// The workload is a tree grown as a planner grows one, without a planner's choices: from a
// state drawn from the states kept so far, a random control held for 2 to 20 propagation
// steps, one propagate + check per step; a valid end is kept. Both settings grow their own
// tree from the same seed, interleaved in rounds so a busy moment of the machine slows both.
// Trees differ (the physics differs by what sleeps), so the numbers are per physics step.

#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <ompl/control/spaces/RealVectorControlSpace.h>
#include <CLI/CLI.hpp>

#include "kautham/core/ProblemLoader.h"
#include "kautham/physics/PlanningContext.h"
#include "kautham/physics/WorldStateSpace.h"

namespace {

using namespace kautham;
using Clock = std::chrono::steady_clock;

/// One setting's tree and what it cost.
struct Grower {
  core::Problem problem;
  physics::PlanningContext context;
  std::vector<std::vector<double>> kept;
  std::mt19937_64 rng;
  double seconds = 0.0;
  unsigned long steps = 0;
  unsigned long propagations = 0;
  unsigned long touchedStarts = 0;  ///< expansions whose end moved an object

  Grower(core::Problem p, std::uint64_t seed)
      : problem(std::move(p)),
        context(problem, 0, physics::PropagationSettings{}),
        kept{context.startState()},
        rng(seed) {}

  void expand() {
    const auto& si = context.spaceInformation();
    ompl::base::State* from = si->allocState();
    ompl::base::State* to = si->allocState();
    ompl::control::Control* control = si->allocControl();
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const std::size_t dimension = si->getControlSpace()->getDimension();
    double* u = control->as<ompl::control::RealVectorControlSpace::ControlType>()->values;
    for (std::size_t i = 0; i < dimension; ++i) u[i] = unit(rng);
    const unsigned hold = std::uniform_int_distribution<unsigned>(2, 20)(rng);
    std::vector<double> state =
        kept[std::uniform_int_distribution<std::size_t>(0, kept.size() - 1)(rng)];
    const unsigned long before = context.propagator().counters().physicsSteps;
    const Clock::time_point start = Clock::now();
    bool valid = true;
    for (unsigned k = 0; k < hold && valid; ++k) {
      std::copy(state.begin(), state.end(), physics::WorldStateSpace::values(from));
      context.propagator().propagate(from, control, si->getPropagationStepSize(), to);
      const double* values = physics::WorldStateSpace::values(to);
      state.assign(values, values + state.size());
      valid = context.validityChecker().check(state.data()) == physics::Violation::None;
      ++propagations;
    }
    seconds += std::chrono::duration<double>(Clock::now() - start).count();
    steps += context.propagator().counters().physicsSteps - before;
    if (valid) kept.push_back(state);
    si->freeControl(control);
    si->freeState(from);
    si->freeState(to);
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Physics steps per second with and without sleeping objects, dense suite"};
  std::vector<std::string> problems;
  for (int n : {5, 10, 20, 30, 40})
    problems.push_back("problems/kuka_clutter_" + std::to_string(n) + ".xml");
  unsigned rounds = 10;
  unsigned expansionsPerRound = 40;
  app.add_option("--problem", problems, "problem files (relative to the source tree)");
  app.add_option("--rounds", rounds, "rounds; each grows both trees by --expansions");
  app.add_option("--expansions", expansionsPerRound, "expansions per round and setting");
  CLI11_PARSE(app, argc, argv);

  std::printf("%-22s %12s %12s %8s %10s %10s\n", "problem", "awake st/s", "sleep st/s", "ratio",
              "awake kept", "sleep kept");
  for (const std::string& file : problems) {
    core::Problem problem = core::loadProblem(std::string(KAUTHAM_SOURCE_DIR) + "/" + file);
    core::Problem awake = problem;
    awake.physics.sleep = false;
    problem.physics.sleep = true;
    Grower withoutSleep(awake, 1);
    Grower withSleep(problem, 1);
    for (unsigned r = 0; r < rounds; ++r)
      for (Grower* g : {&withoutSleep, &withSleep})
        for (unsigned e = 0; e < expansionsPerRound; ++e) g->expand();
    const double awakeRate = withoutSleep.steps / withoutSleep.seconds;
    const double sleepRate = withSleep.steps / withSleep.seconds;
    std::printf("%-22s %12.0f %12.0f %8.2f %10zu %10zu\n", file.c_str(), awakeRate, sleepRate,
                sleepRate / awakeRate, withoutSleep.kept.size(), withSleep.kept.size());
    std::fflush(stdout);
  }
  return 0;
}
