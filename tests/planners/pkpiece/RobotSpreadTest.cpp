// The robot states a p-KPIECE motion's particles reached, and particles that start from them;
// the steering control of goal-biased expansions.

#include <algorithm>

#include <gtest/gtest.h>

#include "TestPaths.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/planners/pkpiece/GoalSteering.h"
#include "kautham/planners/pkpiece/MotionEvaluator.h"
#include "kautham/planners/pkpiece/RobotSpread.h"

namespace kautham::planners {
namespace {

struct Scene {
  core::Problem problem = core::loadProblem(test::repoFile("problems/kuka_cans_5.xml"));
  physics::PlanningContext context{problem, 0, physics::PropagationSettings{}};
  std::shared_ptr<const RobotSpread::Part> part =
      std::make_shared<const RobotSpread::Part>(context.layout());
};

bool isRobotIndex(const physics::WorldLayout& layout, std::size_t index) {
  if (index >= layout.jointPositionIndex()) return index < layout.flagsIndex();
  return layout.bodies[index / physics::WorldLayout::kBodyStateSize].role ==
         physics::BodyRole::Robot;
}

TEST(RobotSpreadTest, ThePartIsTheRobotBodiesAndTheJointsAndNothingElse) {
  Scene scene;
  const physics::WorldLayout& layout = scene.context.layout();
  std::size_t robotBodies = 0;
  for (const auto& body : layout.bodies) robotBodies += body.role == physics::BodyRole::Robot;
  ASSERT_GT(robotBodies, 5u);
  EXPECT_EQ(scene.part->indices().size(),
            robotBodies * physics::WorldLayout::kBodyStateSize + 2 * layout.joints.size());
  for (std::size_t index : scene.part->indices()) EXPECT_TRUE(isRobotIndex(layout, index));
}

TEST(RobotSpreadTest, ApplyWritesTheRobotOfASampleCyclingAndLeavesTheObjects) {
  Scene scene;
  const physics::WorldLayout& layout = scene.context.layout();
  const std::vector<double>& start = scene.context.startState();
  std::vector<double> a = start;
  std::vector<double> b = start;
  for (std::size_t index = 0; index < start.size(); ++index) {
    a[index] += 1.0;
    b[index] += 2.0;
  }
  EXPECT_EQ(RobotSpread::fromStates(scene.part, {}), nullptr);
  const auto spread = RobotSpread::fromStates(scene.part, {&a, &b});
  ASSERT_NE(spread, nullptr);
  EXPECT_EQ(spread->size(), 2u);
  for (std::size_t i = 0; i < 3; ++i) {
    std::vector<double> state = start;
    spread->apply(i, state.data());
    const double offset = i % 2 == 0 ? 1.0 : 2.0;  // sample 2 is sample 0 again
    for (std::size_t index = 0; index < state.size(); ++index) {
      const bool robot = isRobotIndex(layout, index);
      EXPECT_DOUBLE_EQ(state[index], start[index] + (robot ? offset : 0.0)) << index;
    }
  }
}

TEST(RobotSpreadTest, ItCarriesTheWholeStateOfTheObjectsAPathMovedAndOnlyThose) {
  Scene scene;
  const physics::WorldLayout& layout = scene.context.layout();
  const std::vector<double>& start = scene.context.startState();
  std::size_t object = layout.bodies.size();
  for (std::size_t b = 0; b < layout.bodies.size(); ++b)
    if (layout.bodies[b].role == physics::BodyRole::Movable) object = b;
  ASSERT_LT(object, layout.bodies.size());
  std::vector<double> moved = start;
  for (std::size_t index = 0; index < start.size(); ++index) moved[index] += 1.0;
  const auto spread = RobotSpread::fromStates(scene.part, {&moved}, {object, object});
  ASSERT_NE(spread, nullptr);
  EXPECT_EQ(spread->objects(), std::vector<std::size_t>{object});  // once, however often named
  std::vector<double> state = start;
  spread->apply(0, state.data());
  const std::size_t k = physics::WorldLayout::kBodyStateSize;
  for (std::size_t index = 0; index < state.size(); ++index) {
    // Its pose, tilt and velocities: all 13 numbers of the carried object's body.
    const bool carried = isRobotIndex(layout, index) || index / k == object;
    EXPECT_DOUBLE_EQ(state[index], start[index] + (carried ? 1.0 : 0.0)) << index;
  }
}

TEST(RobotSpreadTest, ParticlesStartWithTheRobotOfTheirSampleAndTheirOwnObjectPoses) {
  Scene scene;
  MotionEvaluator evaluator(scene.context, 0.3);
  const std::vector<double>& start = scene.context.startState();
  const auto poses =
      ObjectPoseBelief::initial(scene.context.layout(), evaluator.sampler(), start.data());
  // Two robot states reached by earlier particles: the arm a little further on.
  const std::vector<double> control(scene.context.propagator().mapping().size(), 0.3);
  const NominalRun run = evaluator.runNominal(start.data(), control.data(), 3);
  ASSERT_EQ(run.steps, 3u);
  const auto spread = RobotSpread::fromStates(scene.part, {&run.states[0], &run.states[2]});

  ParticleRequest request;
  request.start = start.data();
  request.control = control.data();
  request.steps = 2;
  request.poses = poses.get();
  request.robots = spread.get();
  request.particles = 4;
  request.streamSeed = 5;
  const std::vector<ParticleJob> jobs = evaluator.particleJobs(request);
  const physics::WorldLayout& layout = scene.context.layout();
  for (std::size_t p = 0; p < jobs.size(); ++p) {
    const std::vector<double>& expected = run.states[p % 2 == 0 ? 0 : 2];
    for (std::size_t index : scene.part->indices())
      ASSERT_EQ(jobs[p].start[index], expected[index]) << p << " " << index;
    // The objects were sampled around the tree's state, not taken from the spread.
    bool objectsSampled = false;
    for (std::size_t index = 0; index < layout.jointPositionIndex(); ++index)
      if (!isRobotIndex(layout, index)) objectsSampled |= jobs[p].start[index] != start[index];
    EXPECT_TRUE(objectsSampled) << p;
  }
}

TEST(GoalSteeringTest, TheSteeredMotionBringsTheGripperMuchCloserToTheGoal) {
  Scene scene;
  MotionEvaluator evaluator(scene.context, 0.3);
  const GoalSteering steering(scene.context, evaluator, true, PushSettings{0.45}, false);
  const std::vector<double>& start = scene.context.startState();
  const std::optional<NominalMotion> motion = steering.towardsGoal(start.data());
  ASSERT_TRUE(motion.has_value());
  for (double u : motion->control) {
    EXPECT_GE(u, -1.0);
    EXPECT_LE(u, 1.0);
  }
  const NominalRun run =
      evaluator.runNominal(start.data(), motion->control.data(), motion->steps, true);
  ASSERT_GT(run.steps, 0u);
  const physics::WorkspaceGoal& goal = scene.context.goal();
  const double before =
      (scene.context.layout().goalLinkPosition(start.data()) - goal.position()).norm();
  const double after =
      (scene.context.layout().goalLinkPosition(run.end.data()) - goal.position()).norm();
  EXPECT_GT(before, 0.05);
  EXPECT_LT(after, 0.5 * before) << before << " -> " << after;
}

TEST(GoalSteeringTest, WithoutTheClearingPushNoSteeringWhileAnObjectFillsTheFreeSpace) {
  // kuka_clutter_10 stands can1 on the pre-grasp: steering straight at the goal would push
  // it on to the target.
  const core::Problem problem = core::loadProblem(test::repoFile("problems/kuka_clutter_10.xml"));
  physics::PlanningContext context{problem, 0, physics::PropagationSettings{}};
  MotionEvaluator evaluator(context, 0.3);
  const GoalSteering steering(context, evaluator, false, PushSettings{0.45}, false);
  std::vector<double> start = context.startState();
  EXPECT_FALSE(steering.towardsGoal(start.data()).has_value());

  const auto& bodies = context.layout().bodies;
  const auto can1 = std::find_if(bodies.begin(), bodies.end(),
                                 [](const physics::BodyInfo& b) { return b.name == "can1"; });
  ASSERT_NE(can1, bodies.end());
  // 20 cm aside (the state's x of can1), out of the free space: steering resumes.
  start[static_cast<std::size_t>(can1 - bodies.begin()) * physics::WorldLayout::kBodyStateSize] +=
      0.2;
  EXPECT_TRUE(steering.towardsGoal(start.data()).has_value());
}

}  // namespace
}  // namespace kautham::planners
