// The side pre-grasp's free space on the real dense scene kuka_clutter_10.xml, whose first
// object the generator stands on the pre-grasp: the goal sees it there, and not once it moves.

#include <algorithm>

#include <gtest/gtest.h>

#include "physics/PhysicsTestSupport.h"

namespace kautham::physics {
namespace {

/// The KUKA's TCP at the pre-grasp: +z (the approach) along world +y, +y (the fingers' axis)
/// along world +x, level.
Eigen::Isometry3d tcpAtGoal(const PlanningContext& context) {
  Eigen::Matrix3d rotation;
  rotation.col(0) = Eigen::Vector3d::UnitZ();
  rotation.col(1) = Eigen::Vector3d::UnitX();
  rotation.col(2) = Eigen::Vector3d::UnitY();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation;
  pose.translation() = context.goal().position();
  return pose;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

TEST(GoalFreeSpaceTest, AnObjectOnThePregraspOccupiesItUntilItIsPushedAway) {
  test::ContextFixture fixture("problems/kuka_clutter_10.xml");
  const GoalSpec& spec = fixture.context.goal().spec();
  ASSERT_TRUE(spec.freeSpace.has_value());
  const GoalFreeSpace freeSpace(std::make_shared<WorldLayout>(fixture.context.layout()),
                                spec.freeSpace->size, spec.freeSpace->center);
  const Eigen::Isometry3d goal = tcpAtGoal(fixture.context);

  const auto before = freeSpace.occupants(fixture.state.data(), goal);
  EXPECT_TRUE(contains(before, "can1")) << "the generator stands can1 on the pre-grasp";
  EXPECT_FALSE(contains(before, "cylinder")) << "the target belongs between the fingers";

  // Pushed 20 cm aside, can1 leaves the free space.
  fixture.bodyState("can1")[0] += 0.2;
  const auto after = freeSpace.occupants(fixture.state.data(), goal);
  EXPECT_FALSE(contains(after, "can1"));
  EXPECT_EQ(after.size() + 1, before.size());
}

TEST(GoalFreeSpaceTest, TheSearchDistanceCountsTheBlockerUntilItIsPushedAway) {
  test::ContextFixture fixture("problems/kuka_clutter_10.xml");
  const WorkspaceGoal& goal = fixture.context.goal();
  // The nominal goal pose is the one tcpAtGoal builds by hand.
  EXPECT_TRUE(goal.nominalGoalPose().isApprox(tcpAtGoal(fixture.context), 1e-9));
  const std::size_t can1 = fixture.body("can1");
  EXPECT_EQ(goal.freeSpaceBlocker(fixture.state.data()), std::optional<std::size_t>(can1));
  const double blocked =
      goal.searchDistance(fixture.state.data()) - goal.distance(fixture.state.data());
  EXPECT_GT(blocked, 0.1) << "a can in the box counts like being 10 cm or more away";
  EXPECT_LT(blocked, 0.3);

  fixture.bodyState("can1")[0] += 0.05;  // half way out: less in the way
  const double halfWay =
      goal.searchDistance(fixture.state.data()) - goal.distance(fixture.state.data());
  EXPECT_GT(halfWay, 0.0);
  EXPECT_LT(halfWay, blocked);

  fixture.bodyState("can1")[0] += 0.15;
  EXPECT_FALSE(goal.freeSpaceBlocker(fixture.state.data()).has_value());
  EXPECT_EQ(goal.searchDistance(fixture.state.data()), goal.distance(fixture.state.data()));
}

TEST(GoalFreeSpaceTest, TheStartIsLevelButFarFromTheGoal) {
  test::ContextFixture fixture("problems/kuka_clutter_10.xml");
  const WorkspaceGoal& goal = fixture.context.goal();
  EXPECT_LT(goal.levelError(fixture.state.data()), 0.01);
  EXPECT_LT(goal.approachError(fixture.state.data()), 0.01);
  EXPECT_GE(
      (fixture.context.layout().goalLinkPosition(fixture.state.data()) - goal.position()).norm(),
      0.25);
  EXPECT_FALSE(goal.reached(fixture.state.data()));
}

}  // namespace
}  // namespace kautham::physics
