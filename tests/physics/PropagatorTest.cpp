// The propagator is a function of (state, control, duration): the property every planner and
// every replay relies on.

#include <algorithm>

#include <gtest/gtest.h>

#include "kautham/physics/Execution.h"
#include "kautham/physics/Replay.h"
#include "physics/PhysicsTestSupport.h"

namespace kautham::physics {
namespace {

using test::ContextFixture;

std::vector<double> propagateOnce(ContextFixture& scene, const std::vector<double>& from,
                                  const std::vector<double>& velocities, double duration) {
  const auto& si = scene.context.spaceInformation();
  ompl::base::State* a = si->allocState();
  ompl::base::State* b = si->allocState();
  ompl::control::Control* control = si->allocControl();
  std::copy(from.begin(), from.end(), WorldStateSpace::values(a));
  std::copy(velocities.begin(), velocities.end(),
            control->as<ompl::control::RealVectorControlSpace::ControlType>()->values);
  scene.context.propagator().propagate(a, control, duration, b);
  const double* values = WorldStateSpace::values(b);
  std::vector<double> result(values, values + from.size());
  si->freeControl(control);
  si->freeState(a);
  si->freeState(b);
  return result;
}

TEST(PropagatorTest, SameInputGivesBitIdenticalResultWhateverRanBefore) {
  ContextFixture scene("problems/pusher_cans_5.xml");
  scene.drive({0.0, 0.25, 0.0}, 12);  // in contact with the cans
  const std::vector<double> from = scene.state;
  const std::vector<double> first = propagateOnce(scene, from, {0.1, 0.2, -0.5}, 0.5);
  scene.drive({-0.25, 0.1, 1.0}, 10);  // other contacts, other solver draws in between
  const std::vector<double> second = propagateOnce(scene, from, {0.1, 0.2, -0.5}, 0.5);
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t i = 0; i < first.size(); ++i) EXPECT_EQ(first[i], second[i]) << i;
  EXPECT_NE(first, from);  // and it did move something
}

TEST(PropagatorTest, CountsPropagationsAndPhysicsSteps) {
  ContextFixture scene("problems/pusher_free.xml");
  const PropagationCounters before = scene.context.propagator().counters();
  propagateOnce(scene, scene.state, {0.1, 0.0, 0.0}, 0.05);  // 5 steps of 0.01 s
  propagateOnce(scene, scene.state, {0.1, 0.0, 0.0}, 0.2);
  const PropagationCounters after = scene.context.propagator().counters();
  EXPECT_EQ(after.propagations - before.propagations, 2u);
  EXPECT_EQ(after.physicsSteps - before.physicsSteps, 25u);
}

TEST(PropagatorTest, VelocitiesBeyondTheJointLimitsAreClamped) {
  ContextFixture scene("problems/pusher_free.xml");
  // The x joint's limit is 0.25 m/s: asking for 10 m/s for 0.4 s moves it at most 10 cm.
  const std::vector<double> result = propagateOnce(scene, scene.state, {10.0, 0.0, 0.0}, 0.4);
  const double x = WorldLayout::position(result.data(), scene.body("pusher/gripper")).x();
  EXPECT_GT(x, 0.05);
  EXPECT_LE(x, 0.1 + 1e-3);
}

TEST(ReplayTest, ReplayingControlsTwiceGivesTheSameFrames) {
  ContextFixture scene("problems/pusher_cans_5.xml");
  const std::vector<ControlStep> controls = {{{0.0, 1.0, 0.0}, 10}, {{0.8, 0.4, 0.6}, 6}};
  const ReplayResult first = replay(scene.context, controls);
  const ReplayResult second = replay(scene.context, controls);
  ASSERT_EQ(first.frames.size(), 17u);  // the start and one frame per propagation step
  ASSERT_EQ(second.frames.size(), first.frames.size());
  for (std::size_t i = 0; i < first.frames.size(); ++i)
    EXPECT_EQ(first.frames[i].state, second.frames[i].state) << "frame " << i;
  EXPECT_FALSE(first.reachedGoal);
  EXPECT_NEAR(first.frames.back().time, 0.8, 1e-9);
}

TEST(ReplayTest, FramesRecordWhatTheRobotTouched) {
  ContextFixture scene("tests/data/pusher_wall.xml");
  const int can = static_cast<int>(scene.body("can1"));
  // Over to the can (x = 0.35), then forward into it. Controls are fractions of the joints'
  // velocity limits (0.25 m/s for x and y).
  const ReplayResult result = replay(scene.context, {{{1.0, 0.0, 0.0}, 28}, {{0.0, 0.8, 0.0}, 16}});
  ASSERT_EQ(result.firstViolation, Violation::None);
  std::size_t touching = 0;
  for (std::size_t f = 0; f < result.frames.size(); ++f) {
    const auto& touched = result.frames[f].touched;
    if (f <= 28) {
      EXPECT_TRUE(touched.empty()) << "frame " << f;  // moving in free space
    }
    touching += std::count(touched.begin(), touched.end(), can);
  }
  EXPECT_GT(touching, 0u);
}

TEST(ReplayTest, ReplayStopsAtTheFirstViolation) {
  ContextFixture scene("tests/data/pusher_wall.xml");
  const ReplayResult result = replay(scene.context, {{{0.0, 1.0, 0.0}, 40}});
  EXPECT_EQ(result.firstViolation, Violation::RobotTouchedFixed);
  EXPECT_LT(result.frames.size(), 41u);
  EXPECT_FALSE(result.reachedGoal);
}

TEST(ReplayTest, ARunThatEndsTouchingAFixedObstacleHasTouchedIt) {
  ContextFixture scene("tests/data/pusher_wall.xml");
  const ReplayResult intoTheWall = replay(scene.context, {{{0.0, 1.0, 0.0}, 40}});
  ASSERT_EQ(intoTheWall.firstViolation, Violation::RobotTouchedFixed);
  // The step to the violating frame started from the one before, already touching the wall.
  const auto touching = static_cast<unsigned>(intoTheWall.frames.size() - 2);
  ASSERT_GT(touching, 1u);
  const std::vector<ControlStep> endingThere = {{{0.0, 1.0, 0.0}, touching}};
  EXPECT_EQ(replay(scene.context, endingThere).firstViolation, Violation::RobotTouchedFixed);
  std::mt19937_64 rng(1);
  const ExecutionResult run = execute(scene.context, endingThere, rng, false);
  EXPECT_EQ(run.firstViolation, Violation::RobotTouchedFixed);
  EXPECT_EQ(run.brokenInControl, std::optional<std::size_t>(0));
  EXPECT_TRUE(run.linkAfterControl.empty());
  // One step short of the wall, the run ends clear of it.
  const std::vector<ControlStep> short1 = {{{0.0, 1.0, 0.0}, touching - 1}};
  EXPECT_EQ(replay(scene.context, short1).firstViolation, Violation::None);
  EXPECT_EQ(execute(scene.context, short1, rng, false).firstViolation, Violation::None);
}

}  // namespace
}  // namespace kautham::physics
