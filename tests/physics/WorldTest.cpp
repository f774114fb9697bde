#include <gtest/gtest.h>

#include "TestPaths.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/physics/World.h"

namespace kautham::physics {
namespace {

class WorldTest : public ::testing::Test {
 protected:
  core::Problem problem = core::loadProblem(test::repoFile("problems/pusher_cans_5.xml"));
  World world{problem, problem.queries.front()};
  std::vector<double> state = std::vector<double>(world.layout().stateSize());

  std::size_t bodyNamed(const std::string& name) const {
    const auto& bodies = world.layout().bodies;
    for (std::size_t b = 0; b < bodies.size(); ++b)
      if (bodies[b].name == name) return b;
    throw std::runtime_error("no body " + name);
  }

  Eigen::Vector3d positionOf(const std::string& name) {
    world.readState(state.data());
    return WorldLayout::position(state.data(), bodyNamed(name));
  }

  /// Writes `saved` as a propagation does (state, then the solver seed), drives the gripper
  /// forward for 0.5 s and returns the state it ends in.
  std::vector<double> runFrom(const std::vector<double>& saved) {
    world.writeState(saved.data());
    world.resetSolverSeed();
    run(0.5, {0.0, 0.2, 0.0});
    std::vector<double> result(state.size());
    world.readState(result.data());
    return result;
  }

  void run(double seconds, const std::vector<double>& velocities) {
    world.setJointVelocities(velocities.data());
    const int steps = static_cast<int>(std::lround(seconds / world.settings().stepSize));
    for (int i = 0; i < steps; ++i) world.step();
  }
};

TEST_F(WorldTest, HasOneBodyPerMovingLinkAndObject) {
  // 3 robot links that move + 5 cans + the glass; the table is static geometry.
  EXPECT_EQ(world.layout().bodies.size(), 9u);
  EXPECT_EQ(world.actuators().size(), 3u);
}

TEST_F(WorldTest, UntouchedCanStaysWithinOneMillimetreForTwoSeconds) {
  const Eigen::Vector3d before = positionOf("can4");
  run(2.0, {0.0, 0.0, 0.0});
  EXPECT_LT((positionOf("can4") - before).norm(), 1e-3);
}

TEST_F(WorldTest, JointsStartAtTheQueryInitAndFollowTheirMotors) {
  std::vector<double> q = world.jointPositions();
  EXPECT_NEAR(q[0], 0.0, 1e-9);  // x: normalized 0.5 of [-0.5, 0.5]
  EXPECT_NEAR(q[1], 0.0, 1e-9);  // y: normalized 0 of [0, 0.7]
  EXPECT_NEAR(q[2], 0.0, 1e-9);  // yaw: normalized 0.5 of [-1.57, 1.57]
  run(0.4, {0.1, 0.0, 0.5});
  q = world.jointPositions();
  EXPECT_NEAR(q[0], 0.04, 5e-3);
  EXPECT_NEAR(q[2], 0.2, 2e-2);
  // The gripper moved along +x in the world, as the URDF's joint axis says.
  EXPECT_NEAR(positionOf("pusher/gripper").x(), 0.04, 5e-3);
}

TEST_F(WorldTest, PushedCanMovesAndTargetDoesNot) {
  // Drive the gripper straight forward (+y) into can4, which stands at x = -0.15.
  const Eigen::Vector3d canBefore = positionOf("can4");
  const Eigen::Vector3d glassBefore = positionOf("glass");
  run(0.75, {-0.2, 0.0, 0.0});  // line up with can4 (x = -0.15) first
  run(2.3, {0.0, 0.2, 0.0});
  EXPECT_GT((positionOf("can4") - canBefore).norm(), 0.04);
  EXPECT_LT((positionOf("glass") - glassBefore).norm(), 1e-3);
}

TEST_F(WorldTest, RunFromAWrittenStateDoesNotDependOnHistory) {
  // This is what makes propagation a function: the propagator writes the start state and
  // resets the solver seed before every run of steps.
  run(0.3, {0.1, 0.2, 0.3});
  std::vector<double> saved(state.size());
  world.readState(saved.data());
  const std::vector<double> first = runFrom(saved);
  run(0.7, {0.2, -0.1, 0.5});  // wander off with other contacts and other solver draws
  const std::vector<double> second = runFrom(saved);
  for (std::size_t i = 0; i < first.size(); ++i)
    EXPECT_EQ(first[i], second[i]) << "state number " << i;  // bit for bit
}

/// Whether every velocity of the body in `state` is exactly zero: how the state says it sleeps.
bool asleep(const std::vector<double>& state, std::size_t body) {
  return WorldLayout::linearVelocity(state.data(), body).isZero(0.0) &&
         WorldLayout::angularVelocity(state.data(), body).isZero(0.0);
}

TEST_F(WorldTest, RestingObjectsFallAsleepAndTheStateSaysSo) {
  run(0.3, {0.0, 0.0, 0.0});
  world.readState(state.data());
  for (const char* name : {"can1", "can2", "can3", "can4", "can5", "glass"})
    EXPECT_TRUE(asleep(state, bodyNamed(name))) << name;
}

TEST_F(WorldTest, SleepingCanWakesWhenPushed) {
  run(0.3, {0.0, 0.0, 0.0});
  world.readState(state.data());
  world.writeState(state.data());  // every object asleep from here on
  const Eigen::Vector3d canBefore = positionOf("can4");
  run(0.75, {-0.2, 0.0, 0.0});
  run(2.3, {0.0, 0.2, 0.0});
  EXPECT_GT((positionOf("can4") - canBefore).norm(), 0.04);
}

TEST_F(WorldTest, SleepIsPartOfTheWrittenState) {
  // A state taken while can4 is being pushed holds moving and sleeping objects; runs from it
  // repeat bit for bit whatever slept or woke in between.
  run(0.75, {-0.2, 0.0, 0.0});
  std::vector<double> saved(state.size());
  for (int i = 0; i < 23; ++i) {  // forward until the gripper pushes can4
    run(0.1, {0.0, 0.2, 0.0});
    world.readState(saved.data());
    if (!asleep(saved, bodyNamed("can4"))) break;
  }
  ASSERT_FALSE(asleep(saved, bodyNamed("can4")));
  ASSERT_TRUE(asleep(saved, bodyNamed("can1")));
  const std::vector<double> first = runFrom(saved);
  run(1.0, {0.0, 0.0, 0.0});  // let everything settle and sleep
  const std::vector<double> second = runFrom(saved);
  for (std::size_t i = 0; i < first.size(); ++i)
    EXPECT_EQ(first[i], second[i]) << "state number " << i;
}

}  // namespace
}  // namespace kautham::physics
