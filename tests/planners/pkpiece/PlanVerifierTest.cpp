// PlanVerifier on a real problem: its runs are physics::execute's sampled executions, one
// random stream each, never repeated, and it stops once the threshold is out of reach.

#include <gtest/gtest.h>
#include <ompl/util/Console.h>

#include "TestPaths.h"
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
      {{"particles", "4"}, {"candidates", "3"}, {"verify_runs", "0"}, {"time_limit", "300"}},
      seedRandomness(2));
  physics::PlanningContext context{problem, 0, request.propagation()};
};

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
  PlanVerifier verifier(scene.context, kSeedBase);
  const VerificationResult first = verifier.verify(plan.controls, 12, 0.0);
  const VerificationResult second = verifier.verify(plan.controls, 12, 0.0);
  EXPECT_EQ(first.runs, 12u);
  EXPECT_TRUE(first.passed);
  EXPECT_EQ(first.successes, successesOfStreams(scene.context, plan.controls, 0, 12));
  // The second verification does not reuse the first one's worlds.
  EXPECT_EQ(second.successes, successesOfStreams(scene.context, plan.controls, 12, 12));
  EXPECT_GT(first.successes + second.successes, 0u);  // the planner's plan does work
}

TEST(PlanVerifierTest, StopsAtTheFailureThatPutsTheThresholdOutOfReach) {
  Scene scene;
  // A plan that goes nowhere: it never reaches the goal, so every run fails.
  std::vector<physics::ControlStep> idle(1);
  idle[0].values.assign(scene.context.propagator().mapping().size(), 0.0);
  idle[0].steps = 2;
  PlanVerifier verifier(scene.context, kSeedBase);
  // 10 runs at 0.75: the third failure leaves at most 7 successes.
  const VerificationResult strict = verifier.verify(idle, 10, 0.75);
  EXPECT_FALSE(strict.passed);
  EXPECT_EQ(strict.runs, 3u);
  EXPECT_EQ(strict.successes, 0u);
  EXPECT_EQ(strict.rate(), 0.0);
  // With no threshold it runs them all, and a rate of 0 passes 0.
  const VerificationResult all = verifier.verify(idle, 10, 0.0);
  EXPECT_EQ(all.runs, 10u);
  EXPECT_TRUE(all.passed);
}

}  // namespace
}  // namespace kautham::planners
