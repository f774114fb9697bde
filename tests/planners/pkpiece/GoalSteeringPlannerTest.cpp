// The goal-steering planner: p-KPIECE's goal steering followed from the start without a search,
// on the real dense scenes, in the real physics.

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <ompl/util/Console.h>

#include "TestPaths.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/planners/Solve.h"

namespace kautham::planners {
namespace {

const bool quietOmpl = [] {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  return true;
}();

struct Followed {
  PlanOutcome outcome;
  physics::ReplayResult replay;
  double goalTolerance = 0.0;
};

/// `kautham plan FILE --planner goal-steering --seed SEED [--set ...]`: the file's p-KPIECE
/// parameters carry over to it.
Followed follow(const std::string& file, const std::vector<ParameterOverride>& sets = {},
                std::uint32_t seed = 1) {
  const core::Problem problem = core::loadProblem(test::repoFile(file));
  const PlanRequest request = makeRequest(problem, "goal-steering", sets, seedRandomness(seed));
  physics::PlanningContext context(problem, 0, request.propagation());
  Followed run;
  run.outcome = solve(context, request);
  run.replay = physics::replay(context, run.outcome.controls);
  run.goalTolerance = context.goal().spec().tolerance;
  return run;
}

std::string property(const PlanOutcome& outcome, const std::string& name) {
  for (const auto& [key, value] : outcome.statistics.plannerProperties)
    if (key == name) return value;
  return "(none)";
}

TEST(GoalSteeringPlannerTest, FollowsTheSteeringThroughKukaClutter30sPushesToTheGoal) {
  // kuka_clutter_30's steering clears the corridor and the free space push by push and ends
  // within the file's goal margin (half the 2 cm tolerance), every motion valid.
  const Followed run = follow("problems/kuka_clutter_30.xml");
  ASSERT_TRUE(run.outcome.solved);
  EXPECT_TRUE(run.replay.reachedGoal);
  EXPECT_EQ(run.replay.firstViolation, physics::Violation::None);
  EXPECT_LE(run.replay.finalGoalDistance, 0.5 * run.goalTolerance + 1e-9);
  EXPECT_GT(run.outcome.controls.size(), 10u);  // pushes, not a straight reach
  EXPECT_TRUE(run.outcome.candidateFailures.empty());
  EXPECT_EQ(property(run.outcome, "stalled"), "0");
}

TEST(GoalSteeringPlannerTest, StopsAtTheFirstRuleBrokenAndSaysWhichObjectBrokeIt) {
  // kuka_clutter_40 with the corridor cleared 10 cm behind the goal point: can8 is pushed first,
  // from its +x side, where lowering the gripper tips can33 (docs/benchmarks.md, session 59).
  const Followed run = follow("problems/kuka_clutter_40.xml", {{"clear_behind", "0.1"}});
  EXPECT_FALSE(run.outcome.solved);
  EXPECT_TRUE(run.outcome.approximate);
  ASSERT_EQ(run.outcome.candidateFailures.size(), 1u);
  EXPECT_EQ(run.outcome.candidateFailures[0].reason,
            physics::toString(physics::Violation::ObjectTilted));
  EXPECT_EQ(run.outcome.candidateFailures[0].object, "can33");
  EXPECT_EQ(run.outcome.candidateFailures[0].count, 1u);
  // The plan is the part that stayed valid.
  EXPECT_EQ(run.replay.firstViolation, physics::Violation::None);
  EXPECT_FALSE(run.replay.reachedGoal);
}

TEST(GoalSteeringPlannerTest, FollowsTheTreeItIsToldTo) {
  // kuka_clutter_25 with push_angle_spread 0.4, seed 2: the first tree's steering pushes
  // straight across and tips can21; tree 1 pushes at angles of its own and reaches the goal
  // (`scripts/steering-trees.py --seed 2` shows trees 1-4, 6 and 7 do; under seed 1 tree 1 tips
  // can21 too). With push_angle_after 2, tree 1 pushes straight, as the first tree does.
  constexpr std::uint32_t kSeed = 2;
  const std::vector<ParameterOverride> spread{{"push_angle_spread", "0.4"}};
  const Followed first = follow("problems/kuka_clutter_25.xml", spread, kSeed);
  EXPECT_FALSE(first.outcome.solved);
  ASSERT_EQ(first.outcome.candidateFailures.size(), 1u);
  EXPECT_EQ(first.outcome.candidateFailures[0].object, "can21");

  std::vector<ParameterOverride> treeOne = spread;
  treeOne.push_back({"tree", "1"});
  const Followed turned = follow("problems/kuka_clutter_25.xml", treeOne, kSeed);
  // The angles are the seed's: under seed 1 tree 1 tips can21 as the first tree does.
  const Followed seedOne = follow("problems/kuka_clutter_25.xml", treeOne, 1);
  EXPECT_FALSE(seedOne.replay.reachedGoal);
  EXPECT_TRUE(turned.outcome.solved);
  EXPECT_TRUE(turned.replay.reachedGoal);
  EXPECT_EQ(turned.replay.firstViolation, physics::Violation::None);

  treeOne.push_back({"push_angle_after", "2"});
  const Followed held = follow("problems/kuka_clutter_25.xml", treeOne, kSeed);
  ASSERT_EQ(held.outcome.controls.size(), first.outcome.controls.size());
  for (std::size_t i = 0; i < held.outcome.controls.size(); ++i)
    EXPECT_EQ(held.outcome.controls[i].values, first.outcome.controls[i].values) << i;
}

/// How far the target has drifted from its start, at most, over the replay (m).
double mostTargetDrift(const std::string& file, const physics::ReplayResult& replay) {
  const core::Problem problem = core::loadProblem(test::repoFile(file));
  const physics::PlanningContext context(problem, 0, physics::PropagationSettings{});
  const std::size_t target = *context.validityChecker().targetBody();
  const Eigen::Vector3d start =
      physics::WorldLayout::position(replay.frames.front().state.data(), target);
  double most = 0.0;
  for (const physics::ReplayFrame& frame : replay.frames)
    most =
        std::max(most, (physics::WorldLayout::position(frame.state.data(), target) - start).norm());
  return most;
}

TEST(GoalSteeringPlannerTest, WithATargetMarginTheNominalMotionsKeepTheTargetNearerItsStart) {
  // yumi_clutter_35, seed 1, tree 12 with push_angle_spread 0.8: the steering's pushes nudge
  // the glass 1.9 mm (of the scene's 5 mm) before can4 tips. With target_margin 0.2 a motion
  // that moves it more than 1 mm breaks the target rule there, sooner, and the plan keeps the
  // glass within 1 mm. The limit travels with the jobs to the worker processes.
  const std::string file = "problems/yumi_clutter_35.xml";
  std::vector<ParameterOverride> sets{{"push_angle_spread", "0.8"}, {"tree", "12"}};
  const Followed free = follow(file, sets);
  sets.push_back({"target_margin", "0.2"});
  const Followed margin = follow(file, sets);
  sets.push_back({"threads", "2"});
  const Followed twoThreads = follow(file, sets);

  EXPECT_GT(mostTargetDrift(file, free.replay), 0.001);
  ASSERT_EQ(free.outcome.candidateFailures.size(), 1u);
  EXPECT_EQ(free.outcome.candidateFailures[0].object, "can4");

  EXPECT_LE(mostTargetDrift(file, margin.replay), 0.001);
  EXPECT_EQ(margin.replay.firstViolation, physics::Violation::None);
  ASSERT_EQ(margin.outcome.candidateFailures.size(), 1u);
  EXPECT_EQ(margin.outcome.candidateFailures[0].reason,
            physics::toString(physics::Violation::TargetMoved));
  EXPECT_EQ(margin.outcome.candidateFailures[0].object, "glass");
  EXPECT_LT(margin.outcome.controls.size(), free.outcome.controls.size());
  ASSERT_EQ(twoThreads.outcome.controls.size(), margin.outcome.controls.size());
  for (std::size_t i = 0; i < margin.outcome.controls.size(); ++i)
    EXPECT_EQ(twoThreads.outcome.controls[i].values, margin.outcome.controls[i].values) << i;
}

}  // namespace
}  // namespace kautham::planners
