// Particle jobs in worker processes: the same results as inline, bit for bit; a dead worker is
// an error, not a hang; workers are reaped; the `threads` parameter.

#include <sys/wait.h>

#include <cerrno>
#include <csignal>

#include <gtest/gtest.h>

#include "TestPaths.h"
#include "WorkBudget.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/planners/PlanRequest.h"
#include "kautham/planners/Solve.h"
#include "kautham/planners/pkpiece/MotionEvaluator.h"
#include "kautham/planners/pkpiece/ParticleWorkers.h"

namespace kautham::planners {
namespace {

struct Scene {
  core::Problem problem = core::loadProblem(test::repoFile("tests/data/pusher_cans_uncertain.xml"));
  physics::PlanningContext context{problem, 0, physics::PropagationSettings{}};
};

/// A request for `particles` particles of `control` from the scene's start, with the initial
/// pose uncertainty; states are kept after `recordAfter` steps.
ParticleRequest startRequest(const std::vector<double>& start, const std::vector<double>& control,
                             unsigned steps, const ObjectPoseBelief& poses, unsigned particles,
                             std::uint64_t seed, std::vector<unsigned> recordAfter) {
  ParticleRequest request;
  request.start = start.data();
  request.control = control.data();
  request.steps = steps;
  request.poses = &poses;
  request.recordAfter = std::move(recordAfter);
  request.particles = particles;
  request.streamSeed = seed;
  return request;
}

/// Particle jobs of a push straight ahead from the start, drawn as p-KPIECE draws them.
std::vector<ParticleJob> someJobs(Scene& scene, unsigned particles) {
  MotionEvaluator evaluator(scene.context, 0.3);
  const std::vector<double>& start = scene.context.startState();
  const auto belief =
      ObjectPoseBelief::initial(scene.context.layout(), evaluator.sampler(), start.data());
  const std::vector<double> control = {0.1, 0.9, 0.0};
  return evaluator.particleJobs(startRequest(start, control, 12, *belief, particles, 77, {3, 12}));
}

TEST(ParticleWorkersTest, WorkersGiveTheInlineResultsBitForBitAndCountTheirWork) {
  Scene scene;
  const std::vector<ParticleJob> jobs = someJobs(scene, 9);
  ParticleRunner runner(scene.context);
  const physics::PropagationCounters before = scene.context.propagator().counters();
  std::vector<ParticleResult> inline_;
  for (const ParticleJob& job : jobs) inline_.push_back(runner.run(job));
  const physics::PropagationCounters middle = scene.context.propagator().counters();

  ParticleWorkers workers(runner, 2);
  EXPECT_EQ(workers.size(), 2u);
  const std::vector<ParticleResult> pooled = workers.run(jobs);
  const physics::PropagationCounters after = scene.context.propagator().counters();

  ASSERT_EQ(pooled.size(), jobs.size());
  bool someMoved = false;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    EXPECT_EQ(pooled[i].valid, inline_[i].valid) << i;
    EXPECT_EQ(pooled[i].end, inline_[i].end) << i;  // exact equality of every double
    EXPECT_EQ(pooled[i].recorded, inline_[i].recorded) << i;
    EXPECT_FALSE(pooled[i].recorded.empty()) << i;  // the state after 3 steps, at least
    someMoved = someMoved || pooled[i].end != jobs[i].start;
  }
  EXPECT_TRUE(someMoved);
  // The particles differ from each other (sampled poses, contacts, noise).
  EXPECT_NE(pooled[0].end, pooled[1].end);
  // The workers' physics steps count as if they had run here.
  EXPECT_EQ(after.physicsSteps - middle.physicsSteps, middle.physicsSteps - before.physicsSteps);
  EXPECT_EQ(after.propagations - middle.propagations, middle.propagations - before.propagations);

  // A second batch on the same workers, and an empty one.
  const std::vector<ParticleResult> again = workers.run(jobs);
  for (std::size_t i = 0; i < jobs.size(); ++i) EXPECT_EQ(again[i].end, inline_[i].end) << i;
  EXPECT_TRUE(workers.run({}).empty());
}

TEST(ParticleWorkersTest, AKilledWorkerIsAnErrorNamingItNotAHang) {
  Scene scene;
  const std::vector<ParticleJob> jobs = someJobs(scene, 6);
  ParticleRunner runner(scene.context);
  ParticleWorkers workers(runner, 2);
  const pid_t victim = workers.pids().at(1);
  ASSERT_EQ(::kill(victim, SIGKILL), 0);
  try {
    workers.run(jobs);
    FAIL() << "a dead worker was not noticed";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("particle worker 1 (pid " + std::to_string(victim) + ")"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("signal 9"), std::string::npos) << message;
  }
  // The pool refuses further work instead of hanging on the survivor.
  EXPECT_THROW(workers.run(jobs), std::runtime_error);
}

TEST(ParticleWorkersTest, TheDestructorReapsEveryWorker) {
  Scene scene;
  std::vector<pid_t> pids;
  {
    ParticleRunner runner(scene.context);
    ParticleWorkers workers(runner, 3);
    pids = workers.pids();
    workers.run(someJobs(scene, 4));
  }
  ASSERT_EQ(pids.size(), 3u);
  for (pid_t pid : pids) {
    errno = 0;
    EXPECT_EQ(::waitpid(pid, nullptr, WNOHANG), -1) << pid;  // not our child any more
    EXPECT_EQ(errno, ECHILD) << pid;
  }
}

TEST(ParticleWorkersTest, MotionEvaluatorGivesTheSameVerdictWithAndWithoutWorkers) {
  Scene scene;
  MotionEvaluator evaluator(scene.context, 0.05);
  const std::vector<double>& start = scene.context.startState();
  const auto belief =
      ObjectPoseBelief::initial(scene.context.layout(), evaluator.sampler(), start.data());
  const std::vector<double> control = {0.0, 1.0, 0.2};
  const ParticleRequest request = startRequest(start, control, 15, *belief, 7, 1234, {5, 15});
  const ParticleVerdict alone = evaluator.runParticles(request);
  evaluator.useWorkers(3);
  EXPECT_EQ(evaluator.threads(), 3u);
  const ParticleVerdict spread = evaluator.runParticles(request);
  EXPECT_EQ(spread.stateValidity, alone.stateValidity);
  EXPECT_EQ(spread.interaction, alone.interaction);
  EXPECT_EQ(spread.ends, alone.ends);
  EXPECT_EQ(spread.recorded, alone.recorded);
  // The world keeps its mean contact parameters for the nominal runs.
  EXPECT_EQ(scene.context.world().contactParameters().friction, scene.problem.physics.friction);
  evaluator.useWorkers(1);
  EXPECT_EQ(evaluator.threads(), 1u);
}

TEST(ParticleWorkersTest, NominalRunsInWorkersAreTheRunsOneByOne) {
  Scene scene;
  MotionEvaluator evaluator(scene.context, 0.05);
  const std::vector<double>& start = scene.context.startState();
  const std::vector<NominalMotion> motions = {
      {{0.0, 1.0, 0.2}, 15}, {{0.5, -0.3, 0.0}, 8}, {{-1.0, 0.2, 0.9}, 20}, {{0.1, 0.9, 0.0}, 3}};
  std::vector<NominalRun> alone;
  for (const NominalMotion& m : motions)
    alone.push_back(evaluator.runNominal(start.data(), m.control.data(), m.steps, true));
  evaluator.useWorkers(2);
  const std::vector<NominalRun> spread = evaluator.runNominals(start.data(), motions, true);
  ASSERT_EQ(spread.size(), motions.size());
  for (std::size_t i = 0; i < motions.size(); ++i) {
    EXPECT_EQ(spread[i].steps, alone[i].steps) << i;
    EXPECT_EQ(spread[i].states, alone[i].states) << i;
    EXPECT_EQ(spread[i].end, alone[i].end) << i;
    EXPECT_EQ(spread[i].goalFrom, alone[i].goalFrom) << i;
    EXPECT_GT(spread[i].steps, 0u) << i;
  }
}

PlanOutcome planWithThreads(const std::string& threads) {
  const core::Problem problem =
      core::loadProblem(test::repoFile("tests/data/pusher_cans_uncertain.xml"));
  const PlanRequest request =
      makeRequest(problem, "p-KPIECE",
                  // Whole-plan verification included: its executions run in this process.
                  test::withWorkBudget({{"particles", "4"},
                                        {"candidates", "3"},
                                        {"verify_runs", "10"},
                                        {"goal_confidence", "0.2"},
                                        {"threads", threads}}),
                  seedRandomness(2));
  physics::PlanningContext context(problem, 0, request.propagation());
  return solve(context, request);
}

TEST(ParticleWorkersTest, PKpiecePlansTheSameWithOneAndTwoThreads) {
  const PlanOutcome one = planWithThreads("1");
  const PlanOutcome two = planWithThreads("2");
  ASSERT_TRUE(one.solved);
  ASSERT_TRUE(two.solved);
  ASSERT_EQ(one.controls.size(), two.controls.size());
  for (std::size_t i = 0; i < one.controls.size(); ++i) {
    EXPECT_EQ(one.controls[i].values, two.controls[i].values) << i;
    EXPECT_EQ(one.controls[i].steps, two.controls[i].steps) << i;
  }
  EXPECT_EQ(one.beliefs, two.beliefs);
  EXPECT_EQ(one.statistics.treeStates, two.statistics.treeStates);
  // The same work, wherever it ran.
  EXPECT_EQ(one.statistics.physicsSteps, two.statistics.physicsSteps);
  EXPECT_EQ(one.statistics.propagations, two.statistics.propagations);
  EXPECT_EQ(one.statistics.plannerProperties, two.statistics.plannerProperties);
}

TEST(ParticleWorkersTest, ThreadsIsACommonParameterFrom1To64) {
  const core::Problem problem =
      core::loadProblem(test::repoFile("tests/data/pusher_cans_uncertain.xml"));
  EXPECT_EQ(makeRequest(problem, "p-KPIECE", {}, 1).threads(), 1u);
  EXPECT_EQ(makeRequest(problem, "p-KPIECE", {{"threads", "4"}}, 1).threads(), 4u);
  EXPECT_EQ(makeRequest(problem, "KPIECE", {{"Threads", "2"}}, 1).threads(), 2u);
  EXPECT_THROW(makeRequest(problem, "p-KPIECE", {{"threads", "0"}}, 1), std::invalid_argument);
  EXPECT_THROW(makeRequest(problem, "p-KPIECE", {{"threads", "65"}}, 1), std::invalid_argument);
}

}  // namespace
}  // namespace kautham::planners
