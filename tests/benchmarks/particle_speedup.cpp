// Parallel particles: how much faster p-KPIECE's particle jobs run in 2 processes than in 1
// (planners::ParticleWorkers), and what share of p-KPIECE's planning time is spent stepping
// the physics (time inside World::step over the planning time, in one single-process run).
// Scene: problems/kuka_cans_10.xml. See docs/performance.md, "Parallel particles".
//
// World::step is timed by interposing it: this program defines the symbol (and exports it,
// see tests/CMakeLists.txt), so the physics library's calls reach the definition here, which
// forwards to the library's own (dlsym RTLD_NEXT). The physics library is not instrumented.

#include <dlfcn.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <ompl/util/Console.h>
#include <CLI/CLI.hpp>

#include "kautham/core/ProblemLoader.h"
#include "kautham/planners/PlanRequest.h"
#include "kautham/planners/Solve.h"
#include "kautham/planners/pkpiece/MotionEvaluator.h"
#include "kautham/planners/pkpiece/ParticleWorkers.h"

namespace {

using Clock = std::chrono::steady_clock;

// Time spent inside World::step, in this process.
std::uint64_t stepNanoseconds = 0;
std::uint64_t stepCalls = 0;

}  // namespace

extern "C" {
// kautham::physics::World::step(), as the linker names it; `this` is the first argument.
void _ZN7kautham7physics5World4stepEv(kautham::physics::World* world) {
  using Step = void (*)(kautham::physics::World*);
  static const Step real =
      reinterpret_cast<Step>(::dlsym(RTLD_NEXT, "_ZN7kautham7physics5World4stepEv"));
  const Clock::time_point start = Clock::now();
  real(world);
  stepNanoseconds += static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start).count());
  ++stepCalls;
}
}

namespace {

using namespace kautham;

struct Options {
  std::string problem = "problems/kuka_cans_10.xml";
  unsigned candidates = 40;  ///< batches of jobs, one per candidate motion
  unsigned particles = 15;   ///< jobs per batch (p-KPIECE's default n_p)
  unsigned processes = 2;
  unsigned repetitions = 3;
  double planTime = 20.0;
  std::uint32_t seed = 1;
};

double seconds(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Candidate batches as p-KPIECE makes them: a uniform control and duration, n_p particles
/// drawn around the start (poses, contacts, control noise).
std::vector<std::vector<planners::ParticleJob>> makeBatches(physics::PlanningContext& context,
                                                            const Options& options) {
  planners::MotionEvaluator evaluator(context, context.problem().interaction.maxDisplacement);
  const auto& si = context.spaceInformation();
  const std::vector<double>& start = context.startState();
  const auto belief =
      planners::ObjectPoseBelief::initial(context.layout(), evaluator.sampler(), start.data());
  std::mt19937_64 rng(options.seed);
  const auto uniform = [&rng] { return (rng() >> 11) * 0x1.0p-53; };
  std::vector<std::vector<planners::ParticleJob>> batches;
  for (unsigned c = 0; c < options.candidates; ++c) {
    std::vector<double> control(si->getControlSpace()->getDimension());
    for (double& u : control) u = -1.0 + 2.0 * uniform();
    const unsigned minSteps = si->getMinControlDuration();
    const unsigned maxSteps = si->getMaxControlDuration();
    const unsigned steps = minSteps + static_cast<unsigned>(uniform() * (maxSteps - minSteps + 1));
    planners::ParticleRequest request;
    request.start = start.data();
    request.control = control.data();
    request.steps = std::min(steps, maxSteps);
    request.poses = belief.get();
    request.particles = options.particles;
    request.streamSeed = 1000 * (c + 1);
    batches.push_back(evaluator.particleJobs(request));
  }
  return batches;
}

struct Timing {
  double seconds = 0.0;
  std::uint64_t jobs = 0;
  std::uint64_t physicsSteps = 0;
  std::vector<planners::ParticleResult> results;
};

Timing runBatches(physics::PlanningContext& context,
                  const std::vector<std::vector<planners::ParticleJob>>& batches,
                  unsigned processes) {
  planners::ParticleRunner runner(context);
  std::unique_ptr<planners::ParticleWorkers> workers;
  if (processes > 1) workers = std::make_unique<planners::ParticleWorkers>(runner, processes - 1);
  Timing timing;
  const std::uint64_t stepsBefore = context.propagator().counters().physicsSteps;
  const Clock::time_point start = Clock::now();
  for (const auto& batch : batches) {
    std::vector<planners::ParticleResult> results;
    if (workers) {
      results = workers->run(batch);
    } else {
      for (const auto& job : batch) results.push_back(runner.run(job));
    }
    timing.jobs += batch.size();
    for (auto& r : results) timing.results.push_back(std::move(r));
  }
  timing.seconds = seconds(start);
  timing.physicsSteps = context.propagator().counters().physicsSteps - stepsBefore;
  return timing;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App app{
      "Parallel particles on a problem (default problems/kuka_cans_10.xml): (a) particle jobs/s "
      "in 1 and N processes and the speed-up, (b) the share of p-KPIECE's planning time spent "
      "inside World::step in one single-process planning run. See docs/performance.md."};
  app.add_option("--problem", options.problem, "Problem file, from the repository root")
      ->capture_default_str();
  app.add_option("--candidates", options.candidates, "Batches of jobs (one per candidate)")
      ->capture_default_str();
  app.add_option("--particles", options.particles, "Jobs per batch (n_p)")->capture_default_str();
  app.add_option("--processes", options.processes, "Processes of the parallel runs")
      ->check(CLI::Range(2, 64))
      ->capture_default_str();
  app.add_option("--repetitions", options.repetitions, "Repetitions; the fastest one counts")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--plan-time", options.planTime,
                 "Seconds of p-KPIECE planning for the physics share (0: skip)")
      ->capture_default_str();
  app.add_option("--seed", options.seed, "Seed of the jobs and of the planning run")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);

  const core::Problem problem =
      core::loadProblem(std::string(KAUTHAM_SOURCE_DIR) + "/" + options.problem);
  const planners::PlanRequest defaults = planners::makeRequest(problem, "p-KPIECE", {}, 1);
  physics::PlanningContext context(problem, 0, defaults.propagation());
  const auto batches = makeBatches(context, options);

  std::printf("problem %s: %u candidates x %u particles, %zu doubles per state\n",
              options.problem.c_str(), options.candidates, options.particles,
              context.layout().stateSize());
  Timing best[2];
  const unsigned processes[2] = {1, options.processes};
  for (unsigned r = 0; r < options.repetitions; ++r)
    for (int k = 0; k < 2; ++k) {
      Timing t = runBatches(context, batches, processes[k]);
      if (r == 0 || t.seconds < best[k].seconds) best[k] = std::move(t);
    }
  bool identical = best[0].results.size() == best[1].results.size();
  for (std::size_t i = 0; identical && i < best[0].results.size(); ++i)
    identical = best[0].results[i].valid == best[1].results[i].valid &&
                best[0].results[i].end == best[1].results[i].end;
  for (int k = 0; k < 2; ++k)
    std::printf("%2u process%s %8.3f s  %8.1f jobs/s  %9.0f physics steps/s\n", processes[k],
                processes[k] == 1 ? "  " : "es", best[k].seconds, best[k].jobs / best[k].seconds,
                best[k].physicsSteps / best[k].seconds);
  std::printf("speed-up   %.2fx (fastest of %u); results identical: %s\n",
              best[0].seconds / best[1].seconds, options.repetitions, identical ? "yes" : "NO");

  if (options.planTime > 0.0) {
    const planners::PlanRequest request = planners::makeRequest(
        problem, "p-KPIECE", {{"time_limit", std::to_string(options.planTime)}, {"threads", "1"}},
        planners::seedRandomness(options.seed));
    physics::PlanningContext planning(problem, 0, request.propagation());
    stepNanoseconds = 0;
    stepCalls = 0;
    const planners::PlanOutcome outcome = planners::solve(planning, request);
    const double inStep = stepNanoseconds * 1e-9;
    const double total = outcome.statistics.planningTime;
    std::printf(
        "planning   p-KPIECE, 1 process, %.1f s (%s): %llu World::step calls, %.2f s inside "
        "World::step = %.1f%% of planning time (%.1f us per step)\n",
        total, outcome.solved ? "solved" : "not solved", static_cast<unsigned long long>(stepCalls),
        inStep, 100.0 * inStep / total, 1e6 * inStep / std::max<std::uint64_t>(stepCalls, 1));
  }
  return identical ? 0 : 1;
}
