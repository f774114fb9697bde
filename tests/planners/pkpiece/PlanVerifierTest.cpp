// PlanVerifier on a real problem: its runs are physics::execute's sampled executions, one
// random stream each, never repeated, and it stops once the verdict is sure either way; with
// worker processes it counts the same runs.

#include <chrono>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <ompl/util/Console.h>

#include "TestPaths.h"
#include "WorkBudget.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/core/Random.h"
#include "kautham/physics/Execution.h"
#include "kautham/planners/Solve.h"
#include "kautham/planners/pkpiece/PlanVerifier.h"

namespace kautham::planners {
namespace {

const bool quietOmpl = [] {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  return true;
}();

constexpr std::uint64_t kSeedBase = 77;

struct Scene {
  core::Problem problem = core::loadProblem(test::repoFile("tests/data/pusher_cans_uncertain.xml"));
  PlanRequest request = makeRequest(
      problem, "p-KPIECE",
      test::withWorkBudget({{"particles", "4"}, {"candidates", "3"}, {"verify_runs", "0"}}),
      seedRandomness(2));
  physics::PlanningContext context{problem, 0, request.propagation()};
  MotionEvaluator evaluator{context, 0.0};
};

/// A plan that goes nowhere: it never reaches the goal, so every run fails.
std::vector<physics::ControlStep> idlePlan(const Scene& scene) {
  std::vector<physics::ControlStep> idle(1);
  idle[0].values.assign(scene.context.propagator().mapping().size(), 0.0);
  idle[0].steps = 2;
  return idle;
}

/// Successes of the executions kSeedBase's streams first..first+runs-1 give, as validate runs them.
unsigned successesOfStreams(physics::PlanningContext& context,
                            const std::vector<physics::ControlStep>& controls, unsigned first,
                            unsigned runs) {
  unsigned successes = 0;
  for (unsigned i = first; i < first + runs; ++i) {
    std::mt19937_64 rng(core::runSeed(kSeedBase, i));
    if (physics::execute(context, controls, rng, true).reachedGoal) ++successes;
  }
  return successes;
}

TEST(PlanVerifierTest, RunsSampledExecutionsOnFreshStreamsEachTime) {
  Scene scene;
  const PlanOutcome plan = solve(scene.context, scene.request);
  ASSERT_TRUE(plan.solved);
  PlanVerifier verifier(scene.evaluator, kSeedBase);
  const VerificationResult first = verifier.measure(plan.controls, 12);
  const VerificationResult second = verifier.measure(plan.controls, 12);
  EXPECT_EQ(first.runs, 12u);
  EXPECT_TRUE(first.passed);
  EXPECT_EQ(first.successes, successesOfStreams(scene.context, plan.controls, 0, 12));
  // The second verification does not reuse the first one's worlds.
  EXPECT_EQ(second.successes, successesOfStreams(scene.context, plan.controls, 12, 12));
  EXPECT_GT(first.successes + second.successes, 0u);  // the planner's plan does work
}

TEST(PlanVerifierTest, CountsHowFarThroughThePlanEachRunGot) {
  // Per control: the runs that began it and those that got through it (through the last: that
  // ended in the goal), as physics::execute's runs on the same streams say.
  Scene scene;
  const PlanOutcome plan = solve(scene.context, scene.request);
  ASSERT_TRUE(plan.solved);
  const std::size_t controls = plan.controls.size();
  ASSERT_GE(controls, 2u);
  std::vector<unsigned> entered(controls, 0);
  std::vector<unsigned> gotThrough(controls, 0);
  unsigned broken = 0;
  for (unsigned i = 0; i < 12; ++i) {
    std::mt19937_64 rng(core::runSeed(kSeedBase, i));
    const physics::ExecutionResult run = physics::execute(scene.context, plan.controls, rng, true);
    const std::size_t lastBegun = run.brokenInControl ? *run.brokenInControl : controls - 1;
    broken += run.brokenInControl ? 1 : 0;
    for (std::size_t c = 0; c <= lastBegun; ++c) {
      ++entered[c];
      if (c < lastBegun || (!run.brokenInControl && run.reachedGoal)) ++gotThrough[c];
    }
  }
  ASSERT_GT(broken, 0u) << "some of the 12 runs should break a rule on the way";
  PlanVerifier verifier(scene.evaluator, kSeedBase);
  const VerificationResult result = verifier.measure(plan.controls, 12);
  EXPECT_EQ(result.entered, entered);
  EXPECT_EQ(result.gotThrough, gotThrough);
  EXPECT_EQ(result.entered.front(), 12u);
  EXPECT_EQ(result.gotThrough.back(), result.successes);
}

TEST(PlanVerifierTest, StopsAtTheFailureThatPutsTheThresholdOutOfReach) {
  Scene scene;
  const std::vector<physics::ControlStep> idle = idlePlan(scene);
  PlanVerifier verifier(scene.evaluator, kSeedBase);
  // 10 runs at 0.75: the third failure leaves at most 7 successes.
  const VerificationResult strict = verifier.verify(idle, 10, 0.75);
  EXPECT_FALSE(strict.passed);
  EXPECT_EQ(strict.runs, 3u);
  EXPECT_EQ(strict.successes, 0u);
  EXPECT_EQ(strict.rate(), 0.0);
  // A measurement runs them all.
  const VerificationResult all = verifier.measure(idle, 10);
  EXPECT_EQ(all.runs, 10u);
  EXPECT_EQ(all.successes, 0u);
}

TEST(PlanVerifierTest, StopsAtTheSuccessThatMakesTheThresholdSure) {
  Scene scene;
  const PlanOutcome plan = solve(scene.context, scene.request);
  ASSERT_TRUE(plan.solved);
  // Which of the first 12 streams the plan succeeds in, as validate runs them.
  std::vector<unsigned> successAt;
  for (unsigned i = 0; i < 12; ++i)
    if (successesOfStreams(scene.context, plan.controls, i, 1) == 1) successAt.push_back(i);
  ASSERT_GE(successAt.size(), 2u) << "the planner's plan should work in 2 of 12 runs";
  PlanVerifier verifier(scene.evaluator, kSeedBase);
  // 12 runs at 0.15: the second success makes the rate over all 12 at least 0.15.
  const VerificationResult early = verifier.verify(plan.controls, 12, 0.15);
  EXPECT_TRUE(early.passed);
  EXPECT_EQ(early.successes, 2u);
  EXPECT_EQ(early.runs, successAt[1] + 1);
  // The runs it did not need are drawn by the next count, as if it had stopped there.
  const VerificationResult next = verifier.measure(plan.controls, 1);
  EXPECT_EQ(next.successes, successesOfStreams(scene.context, plan.controls, early.runs, 1));
}

TEST(PlanVerifierTest, PastItsDeadlineACountIsCutShortAndAVerificationDoesNotPass) {
  Scene scene;
  const std::vector<physics::ControlStep> idle = idlePlan(scene);
  PlanVerifier verifier(scene.evaluator, kSeedBase);
  verifier.stopAt(PlanVerifier::Clock::now());
  // No run is made: the verdict is undecided, and so not passed.
  const VerificationResult verdict = verifier.verify(idle, 10, 0.5);
  EXPECT_TRUE(verdict.cutShort);
  EXPECT_FALSE(verdict.passed);
  EXPECT_EQ(verdict.runs, 0u);
  const VerificationResult measured = verifier.measure(idle, 10);
  EXPECT_TRUE(measured.cutShort);
  EXPECT_EQ(measured.runs, 0u);
  // A deadline still ahead changes nothing.
  verifier.stopAt(PlanVerifier::Clock::now() + std::chrono::hours(1));
  const VerificationResult all = verifier.measure(idle, 10);
  EXPECT_FALSE(all.cutShort);
  EXPECT_EQ(all.runs, 10u);
}

/// Runs spread over worker processes are counted as one after another: the same verdict, the
/// same count at an early stop, and the next verification draws the same streams.
TEST(PlanVerifierTest, WorkerProcessesCountTheSameRuns) {
  Scene scene;
  const PlanOutcome plan = solve(scene.context, scene.request);
  ASSERT_TRUE(plan.solved);
  std::vector<VerificationResult> byThreads[2];
  for (unsigned threads : {1u, 2u}) {
    scene.evaluator.useWorkers(threads);
    PlanVerifier verifier(scene.evaluator, kSeedBase);
    auto& results = byThreads[threads - 1];
    results.push_back(verifier.measure(plan.controls, 11));
    results.push_back(verifier.verify(plan.controls, 20, 0.9));  // stops early, mid-batch
    results.push_back(verifier.verify(plan.controls, 20, 0.1));  // passes early, mid-batch
    results.push_back(verifier.measure(plan.controls, 7));
  }
  ASSERT_EQ(scene.evaluator.threads(), 2u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(byThreads[0][i].entered, byThreads[1][i].entered) << "verification " << i;
    EXPECT_EQ(byThreads[0][i].gotThrough, byThreads[1][i].gotThrough) << "verification " << i;
    EXPECT_EQ(byThreads[0][i].runs, byThreads[1][i].runs) << "verification " << i;
    EXPECT_EQ(byThreads[0][i].successes, byThreads[1][i].successes) << "verification " << i;
    EXPECT_EQ(byThreads[0][i].passed, byThreads[1][i].passed) << "verification " << i;
  }
  EXPECT_EQ(byThreads[0][0].successes, successesOfStreams(scene.context, plan.controls, 0, 11));
  // The plan succeeds about a fifth of the time: 0.9 stops after a few runs, not all 20.
  EXPECT_LT(byThreads[0][1].runs, 20u);
  EXPECT_FALSE(byThreads[0][1].passed);
  // 0.1 of 20: the second success decides it.
  EXPECT_TRUE(byThreads[0][2].passed);
  EXPECT_EQ(byThreads[0][2].successes, 2u);
  const unsigned counted = 11 + byThreads[0][1].runs + byThreads[0][2].runs;
  EXPECT_EQ(byThreads[1][3].successes,
            successesOfStreams(scene.context, plan.controls, counted, 7));
}

}  // namespace
}  // namespace kautham::planners
