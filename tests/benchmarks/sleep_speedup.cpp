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

#include <CLI/CLI.hpp>

#include "kautham/core/ProblemLoader.h"
#include "physics/PhysicsTestSupport.h"

namespace {

using namespace kautham;
using Clock = std::chrono::steady_clock;

/// One setting's tree and what it cost.
struct Grower {
  test::ContextFixture scene;
  std::vector<std::vector<double>> kept;
  std::mt19937_64 rng;
  double seconds = 0.0;

  Grower(core::Problem problem, std::uint64_t seed)
      : scene(std::move(problem)), kept{scene.context.startState()}, rng(seed) {}

  unsigned long steps() const { return scene.context.propagator().counters().physicsSteps; }

  void expand() {
    const auto& si = scene.context.spaceInformation();
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::vector<double> control(si->getControlSpace()->getDimension());
    for (double& u : control) u = unit(rng);
    const unsigned hold = std::uniform_int_distribution<unsigned>(2, 20)(rng);
    scene.state = kept[std::uniform_int_distribution<std::size_t>(0, kept.size() - 1)(rng)];
    const Clock::time_point start = Clock::now();
    const bool valid = scene.driveControls(control, hold) == physics::Violation::None;
    seconds += std::chrono::duration<double>(Clock::now() - start).count();
    if (valid) kept.push_back(scene.state);
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
    const double awakeRate = withoutSleep.steps() / withoutSleep.seconds;
    const double sleepRate = withSleep.steps() / withSleep.seconds;
    std::printf("%-22s %12.0f %12.0f %8.2f %10zu %10zu\n", file.c_str(), awakeRate, sleepRate,
                sleepRate / awakeRate, withoutSleep.kept.size(), withSleep.kept.size());
    std::fflush(stdout);
  }
  return 0;
}
