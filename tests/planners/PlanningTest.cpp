// Real planners on real problems: solve, then check the plan by replaying it in the physics.

#include <gtest/gtest.h>
#include <ompl/util/Console.h>

#include "TestPaths.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/planners/Solve.h"

namespace kautham::planners {
namespace {

// OMPL's informational messages would bury the test output.
const bool quietOmpl = [] {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  return true;
}();

struct PlanRun {
  PlanOutcome outcome;
  physics::ReplayResult replay;
  std::vector<physics::ObjectDisplacement> moved;
};

/// Plans a shipped problem as `kautham plan` does (time limit generous: the tests assert what
/// is found, never how fast).
PlanRun plan(const std::string& file, const std::string& planner, std::uint32_t seed) {
  const core::Problem problem = core::loadProblem(test::repoFile(file));
  const PlanRequest request =
      makeRequest(problem, planner, {{"time_limit", "120"}}, seedRandomness(seed));
  physics::PlanningContext context(problem, 0, request.propagation());
  PlanRun run;
  run.outcome = solve(context, request);
  run.replay = physics::replay(context, run.outcome.controls);
  run.moved = physics::movedObjects(context.layout(), run.replay);
  return run;
}

TEST(PlanningTest, KpieceSolvesTheFreeSpaceProblem) {
  const PlanRun run = plan("problems/pusher_free.xml", "KPIECE", 1);
  ASSERT_TRUE(run.outcome.solved);
  EXPECT_FALSE(run.outcome.controls.empty());
  EXPECT_TRUE(run.replay.reachedGoal) << physics::toString(run.replay.firstViolation);
  EXPECT_GT(run.outcome.statistics.treeStates, 1u);
  EXPECT_GE(run.outcome.statistics.physicsSteps, 5 * run.outcome.statistics.propagations);
}

TEST(PlanningTest, KpiecePushesCansToReachTheGlass) {
  const PlanRun run = plan("problems/pusher_cans_5.xml", "KPIECE", 1);
  ASSERT_TRUE(run.outcome.solved);
  // Re-propagating the controls from the start reaches the pre-grasp region, with every state
  // valid on the way: the target never touched nor moved, no can fallen or thrown.
  EXPECT_TRUE(run.replay.reachedGoal);
  EXPECT_EQ(run.replay.firstViolation, physics::Violation::None);
  // A can stands where the gripper must go: reaching the goal means pushing.
  EXPECT_FALSE(run.moved.empty());
}

TEST(PlanningTest, SameSeedGivesTheSamePlan) {
  const PlanRun first = plan("problems/pusher_cans_5.xml", "KPIECE", 4);
  const PlanRun second = plan("problems/pusher_cans_5.xml", "KPIECE", 4);
  ASSERT_TRUE(first.outcome.solved);
  ASSERT_EQ(first.outcome.controls.size(), second.outcome.controls.size());
  for (std::size_t i = 0; i < first.outcome.controls.size(); ++i) {
    EXPECT_EQ(first.outcome.controls[i].values, second.outcome.controls[i].values);
    EXPECT_EQ(first.outcome.controls[i].steps, second.outcome.controls[i].steps);
  }
  EXPECT_EQ(first.outcome.statistics.propagations, second.outcome.statistics.propagations);
  EXPECT_EQ(first.replay.finalState(), second.replay.finalState());
}

TEST(PlanningTest, DifferentSeedsExploreDifferently) {
  const PlanRun a = plan("problems/pusher_cans_5.xml", "KPIECE", 1);
  const PlanRun b = plan("problems/pusher_cans_5.xml", "KPIECE", 4);
  EXPECT_NE(a.outcome.statistics.propagations, b.outcome.statistics.propagations);
}

TEST(PlanningTest, RrtSolvesTheFreeSpaceProblem) {
  const PlanRun run = plan("problems/pusher_free.xml", "RRT", 1);
  ASSERT_TRUE(run.outcome.solved);
  EXPECT_TRUE(run.replay.reachedGoal);
}

TEST(PlanningTest, StopHookEndsPlanningWithoutASolution) {
  const core::Problem problem = core::loadProblem(test::repoFile("problems/pusher_cans_5.xml"));
  const PlanRequest request = makeRequest(problem, std::nullopt, {}, seedRandomness(3));
  physics::PlanningContext context(problem, 0, request.propagation());
  SolveHooks hooks;
  hooks.stop = [] { return true; };
  const PlanOutcome outcome = solve(context, request, hooks);
  EXPECT_FALSE(outcome.solved);
}

}  // namespace
}  // namespace kautham::planners
