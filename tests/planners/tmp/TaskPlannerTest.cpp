// The task-and-motion-planning baseline (issue 12): it moves what blocks the way first, puts
// objects down off the way and off each other, and its grasps hold objects in the replay.

#include <gtest/gtest.h>
#include <ompl/util/Console.h>

#include "TestPaths.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/planners/Solve.h"
#include "kautham/planners/tmp/Placement.h"

namespace kautham::planners {
namespace {

const bool quietOmpl = [] {
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  return true;
}();

struct TaskRun {
  core::Problem problem;
  std::unique_ptr<physics::PlanningContext> context;
  PlanOutcome outcome;
  physics::ReplayResult replay;
};

TaskRun planWithTmp(const std::string& file, const std::string& planner, std::uint32_t seed) {
  TaskRun run;
  run.problem = core::loadProblem(test::repoFile(file));
  const PlanRequest request =
      makeRequest(run.problem, planner, {{"time_limit", "120"}}, seedRandomness(seed));
  run.context = std::make_unique<physics::PlanningContext>(run.problem, 0, request.propagation());
  run.outcome = solve(*run.context, request);
  run.replay = physics::replay(*run.context, run.outcome.controls);
  return run;
}

/// The planner says solved, and the replay reaches the goal without breaking a rule.
testing::AssertionResult solvedAndReplayedCleanly(const TaskRun& run) {
  if (!run.outcome.solved) return testing::AssertionFailure() << "not solved";
  if (!run.replay.reachedGoal) return testing::AssertionFailure() << "the replay misses the goal";
  if (run.replay.firstViolation != physics::Violation::None)
    return testing::AssertionFailure()
           << "the replay breaks a rule: " << physics::toString(run.replay.firstViolation);
  return testing::AssertionSuccess();
}

/// Index of the replay frame where control `index` starts.
std::size_t frameOfControl(const std::vector<physics::ControlStep>& controls, std::size_t index) {
  std::size_t frame = 0;
  for (std::size_t i = 0; i < index; ++i) frame += controls[i].steps;
  return frame;
}

TEST(TaskPlannerTest, MovesTheBlockerFirstThenReachesThePreGrasp) {
  // kuka_clutter_5: no collision-free path reaches the side pre-grasp as the scene starts.
  const TaskRun run = planWithTmp("problems/kuka_clutter_5.xml", "TMP", 1);
  ASSERT_TRUE(solvedAndReplayedCleanly(run));
  const auto& controls = run.outcome.controls;
  const auto grasp = std::find_if(controls.begin(), controls.end(), [](const auto& c) {
    return c.action == physics::GripperAction::Grasp;
  });
  ASSERT_NE(grasp, controls.end()) << "the plan grasps nothing";
  const auto release = std::find_if(grasp, controls.end(), [](const auto& c) {
    return c.action == physics::GripperAction::Release;
  });
  ASSERT_NE(release, controls.end()) << "the plan never lets go";
  // The object it grasped ends far from where it stood; the target did not move.
  const physics::WorldLayout& layout = run.context->layout();
  const auto body = static_cast<std::size_t>(grasp->object);
  EXPECT_EQ(layout.bodies[body].role, physics::BodyRole::Movable);
  const double moved =
      (physics::WorldLayout::position(run.replay.finalState().data(), body) -
       physics::WorldLayout::position(run.replay.frames.front().state.data(), body))
          .norm();
  EXPECT_GT(moved, 0.1);
}

TEST(TaskPlannerTest, TheGraspHoldsTheObjectToTheGripperInTheReplayUntilTheRelease) {
  const TaskRun run = planWithTmp("problems/kuka_clutter_5.xml", "TMP", 1);
  ASSERT_TRUE(run.outcome.solved);
  const auto& controls = run.outcome.controls;
  std::size_t graspAt = 0;
  std::size_t releaseAt = 0;
  for (std::size_t i = 0; i < controls.size(); ++i) {
    if (controls[i].action == physics::GripperAction::Grasp && !graspAt) graspAt = i;
    if (controls[i].action == physics::GripperAction::Release && graspAt && !releaseAt)
      releaseAt = i;
  }
  ASSERT_GT(releaseAt, graspAt);
  const physics::WorldLayout& layout = run.context->layout();
  const auto body = static_cast<std::size_t>(controls[graspAt].object);
  const auto relative = [&](std::size_t frame) {
    const double* state = run.replay.frames.at(frame).state.data();
    return layout.linkPose(state, static_cast<std::size_t>(layout.goalBody)).inverse() *
           layout.linkPose(state, body);
  };
  const std::size_t first = frameOfControl(controls, graspAt);
  const std::size_t last = frameOfControl(controls, releaseAt);
  ASSERT_GT(last, first + 5);
  const Eigen::Isometry3d held = relative(first);
  for (std::size_t frame = first; frame <= last; ++frame)
    EXPECT_LT((relative(frame).translation() - held.translation()).norm(), 0.002) << frame;
  // Carried off, then let go: it stands on the table again.
  const double* end = run.replay.finalState().data();
  const double* start = run.replay.frames.front().state.data();
  EXPECT_NEAR(physics::WorldLayout::position(end, body).z(),
              physics::WorldLayout::position(start, body).z(), 0.005);
}

TEST(TaskPlannerTest, PlacedObjectsStandOffEveryOtherObject) {
  const TaskRun run = planWithTmp("problems/kuka_clutter_10.xml", "TMP", 2);
  ASSERT_TRUE(run.outcome.solved);
  const physics::WorldLayout& layout = run.context->layout();
  const double* end = run.replay.finalState().data();
  for (const physics::ControlStep& c : run.outcome.controls) {
    if (c.action != physics::GripperAction::Grasp) continue;
    const auto moved = static_cast<std::size_t>(c.object);
    for (std::size_t b = 0; b < layout.bodies.size(); ++b) {
      if (b == moved || layout.bodies[b].role == physics::BodyRole::Robot) continue;
      const Eigen::Vector3d d =
          physics::WorldLayout::position(end, b) - physics::WorldLayout::position(end, moved);
      EXPECT_GT(d.head<2>().norm(), 0.07)
          << layout.bodies[moved].name << " by " << layout.bodies[b].name;  // two can radii
    }
  }
}

TEST(TaskPlannerTest, SolvesTwentyObjectsAndLetsGoOfEachObjectAtRest) {
  // kuka_clutter_20, seed 2: seven objects moved. Before placed objects stayed solid in
  // the next obstruction query, the clutter went round in circles; before the arm stopped
  // ahead of each release, the third can slid on and toppled.
  const TaskRun run = planWithTmp("problems/kuka_clutter_20.xml", "TMP", 2);
  ASSERT_TRUE(solvedAndReplayedCleanly(run));
  const auto& controls = run.outcome.controls;
  int held = -1;
  int releases = 0;
  for (std::size_t i = 0; i < controls.size(); ++i) {
    if (controls[i].action == physics::GripperAction::Grasp) held = controls[i].object;
    if (controls[i].action != physics::GripperAction::Release) continue;
    ASSERT_GE(held, 0);
    const double* state = run.replay.frames.at(frameOfControl(controls, i)).state.data();
    EXPECT_LT(physics::WorldLayout::linearVelocity(state, static_cast<std::size_t>(held)).norm(),
              0.01)
        << "released in motion at control " << i;
    ++releases;
  }
  EXPECT_GE(releases, 3);
}

TEST(TaskPlannerTest, GraspsAnObjectBeyondAVerticalReachWithATiltedApproach) {
  // kuka_clutter_30: can20 stands behind the target, in the pre-grasp's free space, 82 cm
  // from the arm's base, where no vertical approach reaches; the plan must move it.
  const TaskRun run = planWithTmp("problems/kuka_clutter_30.xml", "TMP", 5);
  ASSERT_TRUE(solvedAndReplayedCleanly(run));
  const physics::WorldLayout& layout = run.context->layout();
  bool graspedCan20 = false;
  for (const physics::ControlStep& c : run.outcome.controls)
    if (c.action == physics::GripperAction::Grasp &&
        layout.bodies[static_cast<std::size_t>(c.object)].name == "can20")
      graspedCan20 = true;
  EXPECT_TRUE(graspedCan20);
}

TEST(TaskPlannerTest, AFixedSeedGivesTheSamePlanWithTheSameGrasps) {
  const TaskRun a = planWithTmp("problems/kuka_clutter_10.xml", "TMP-U", 3);
  const TaskRun b = planWithTmp("problems/kuka_clutter_10.xml", "TMP-U", 3);
  ASSERT_TRUE(a.outcome.solved);
  ASSERT_EQ(a.outcome.controls.size(), b.outcome.controls.size());
  for (std::size_t i = 0; i < a.outcome.controls.size(); ++i) {
    EXPECT_EQ(a.outcome.controls[i].values, b.outcome.controls[i].values) << i;
    EXPECT_EQ(a.outcome.controls[i].action, b.outcome.controls[i].action) << i;
    EXPECT_EQ(a.outcome.controls[i].object, b.outcome.controls[i].object) << i;
  }
}

TEST(PlacementTest, SampledPlacementsKeepOffTheCorridorAndOffOtherObjects) {
  tmp::PlacementRules rules;
  rules.area = Eigen::AlignedBox2d(Eigen::Vector2d(-0.5, -0.3), Eigen::Vector2d(0.5, 0.3));
  rules.occupied = {{{0.0, 0.0}, 0.04}, {{0.2, 0.1}, 0.033}, {{-0.3, -0.2}, 0.05}};
  rules.corridors = {{{-0.5, 0.25}, {0.0, 0.05}, {0.1, -0.25}}};
  ompl::RNG rng(3);
  const double radius = 0.033;
  const auto places = tmp::samplePlacements(rules, radius, 2000, rng);
  ASSERT_GT(places.size(), 100u);
  for (const Eigen::Vector2d& p : places) {
    EXPECT_TRUE(rules.area.contains(p));
    for (const tmp::Footprint& other : rules.occupied)
      EXPECT_GE((p - other.centre).norm(), other.radius + radius + rules.gap);
    // Off the corridor: sampled along its segments, no point is nearer than the half-width.
    const auto& line = rules.corridors.front();
    for (std::size_t i = 0; i + 1 < line.size(); ++i)
      for (double t = 0.0; t <= 1.0; t += 0.01)
        EXPECT_GE((p - (line[i] + t * (line[i + 1] - line[i]))).norm(),
                  rules.corridorHalfWidth + radius - 1e-9);
  }
  // A point on the corridor and one on an object are refused.
  EXPECT_FALSE(tmp::isFreePlacement(rules, {0.0, 0.05}, radius));
  EXPECT_FALSE(tmp::isFreePlacement(rules, {0.2, 0.1}, radius));
}

}  // namespace
}  // namespace kautham::planners
