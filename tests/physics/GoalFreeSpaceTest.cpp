// The side pre-grasp's free space on the real dense scene kuka_clutter_10.xml, whose first
// object the generator stands on the pre-grasp: the goal sees it there, and not once it moves.

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

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

/// The free space's answer worked out the slow way: every grid point (laid out as
/// GoalFreeSpace documents it) against every shape of every movable body, no culling.
std::vector<std::string> occupantsByEveryPoint(const WorldLayout& layout, const double* state,
                                               const Eigen::Isometry3d& goalLink,
                                               const Eigen::Vector3d& size,
                                               const Eigen::Vector3d& center) {
  Eigen::Vector3i count;
  for (int a = 0; a < 3; ++a)
    count[a] = std::max(2, 1 + static_cast<int>(std::ceil(size[a] / GoalFreeSpace::kSpacing)));
  std::vector<std::string> names;
  for (std::size_t b = 0; b < layout.bodies.size(); ++b) {
    if (layout.bodies[b].role != BodyRole::Movable) continue;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = WorldLayout::orientation(state, b).normalized().toRotationMatrix();
    pose.translation() = WorldLayout::position(state, b);
    bool occupies = false;
    for (const ShapeInfo& info : layout.shapes) {
      if (info.body != static_cast<int>(b)) continue;
      const Eigen::Isometry3d toShape = (pose * info.pose).inverse();
      for (int i = 0; i < count.x() && !occupies; ++i)
        for (int j = 0; j < count.y() && !occupies; ++j)
          for (int k = 0; k < count.z() && !occupies; ++k) {
            const Eigen::Vector3d fraction(i / double(count.x() - 1), j / double(count.y() - 1),
                                           k / double(count.z() - 1));
            const Eigen::Vector3d p =
                toShape *
                (goalLink * (center + (fraction.array() - 0.5).matrix().cwiseProduct(size)));
            if (const auto* c = std::get_if<core::Cylinder>(&info.shape))
              occupies = p.head<2>().norm() <= c->radius && std::abs(p.z()) <= 0.5 * c->length;
            else if (const auto* box = std::get_if<core::Box>(&info.shape))
              occupies = (p.cwiseAbs() - 0.5 * box->size).maxCoeff() <= 0.0;
            else
              ADD_FAILURE() << "the reference knows cylinders and boxes only";
          }
    }
    if (occupies) names.push_back(layout.bodies[b].name);
  }
  return names;
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

TEST(GoalFreeSpaceTest, SkippingFarGridPointsChangesNoAnswer) {
  // Dense scenes, the gripper swept over a lattice about the pre-grasp and turned: the
  // free space names the same occupants as testing every point against every shape, and is
  // free exactly when it names none. Most poses have one or more cans only partly inside.
  for (const char* file : {"problems/kuka_clutter_30.xml", "problems/yumi_clutter_30.xml"}) {
    test::ContextFixture fixture(file);
    const GoalSpec& spec = fixture.context.goal().spec();
    ASSERT_TRUE(spec.freeSpace.has_value()) << file;
    const WorldLayout& layout = fixture.context.layout();
    const GoalFreeSpace freeSpace(std::make_shared<WorldLayout>(layout), spec.freeSpace->size,
                                  spec.freeSpace->center);
    std::size_t occupied = 0, poses = 0;
    for (double dx = -0.12; dx <= 0.121; dx += 0.03)
      for (double dy = -0.12; dy <= 0.121; dy += 0.03)
        for (double yaw : {-0.4, 0.0, 0.7}) {
          Eigen::Isometry3d link = fixture.context.goal().nominalGoalPose();
          link.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * link.linear();
          link.translation() += Eigen::Vector3d(dx, dy, 0.0);
          const auto expected = occupantsByEveryPoint(layout, fixture.state.data(), link,
                                                      spec.freeSpace->size, spec.freeSpace->center);
          EXPECT_EQ(freeSpace.occupants(fixture.state.data(), link), expected)
              << file << " at " << dx << ", " << dy << ", yaw " << yaw;
          EXPECT_EQ(freeSpace.isFree(fixture.state.data(), link), expected.empty());
          occupied += expected.empty() ? 0 : 1;
          ++poses;
        }
    EXPECT_GT(occupied, poses / 4) << file << ": the lattice should meet the clutter";
    EXPECT_LT(occupied, poses) << file << ": and some clear poses";
  }
}

TEST(GoalFreeSpaceTest, AnObjectAtAPoseThatIsNotANumberFillsNoPoint) {
  test::ContextFixture fixture("problems/kuka_clutter_10.xml");
  const GoalSpec& spec = fixture.context.goal().spec();
  const GoalFreeSpace freeSpace(std::make_shared<WorldLayout>(fixture.context.layout()),
                                spec.freeSpace->size, spec.freeSpace->center);
  const Eigen::Isometry3d goal = tcpAtGoal(fixture.context);
  ASSERT_TRUE(contains(freeSpace.occupants(fixture.state.data(), goal), "can1"));
  fixture.bodyState("can1")[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(contains(freeSpace.occupants(fixture.state.data(), goal), "can1"));
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
