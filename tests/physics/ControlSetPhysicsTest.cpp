// Kautham's control sets, mobile bases and goals in the ODE world: driven through the real
// propagator on the real problem files (problems/kuka_cans_5.xml, problems/kautham/).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "physics/PhysicsTestSupport.h"

namespace kautham::physics {
namespace {

namespace fs = std::filesystem;
using test::ContextFixture;
using test::repoFile;

const char* const kKuka = "problems/kuka_cans_5.xml";
const char* const kSphere = "problems/kautham/sphere_cubes.xml";

double jointPosition(const ContextFixture& scene, std::size_t joint) {
  return scene.state[scene.context.layout().jointPositionIndex() + joint];
}

std::vector<double> jointPositions(const ContextFixture& scene) {
  const std::size_t first = scene.context.layout().jointPositionIndex();
  const std::size_t count = scene.context.layout().joints.size();
  return {scene.state.begin() + static_cast<long>(first),
          scene.state.begin() + static_cast<long>(first + count)};
}

// ----- joints that no control moves are held -----

TEST(ControlSetPhysics, KukaFingersStayPutWhileTheArmMoves) {
  ContextFixture scene(kKuka);
  const WorldLayout& layout = scene.context.layout();
  ASSERT_EQ(layout.joints.size(), 9u);
  ASSERT_EQ(scene.context.propagator().mapping().size(), 7u);  // the controls, not the joints
  EXPECT_EQ(layout.joints[7].name, "kuka_finger_left_joint");
  const std::vector<double> before = jointPositions(scene);
  EXPECT_NEAR(before[7], 0.0225, 1e-6);
  EXPECT_NEAR(before[8], 0.0225, 1e-6);
  // Lift the arm (A2 back, A4 and A6 on) and turn the wrist: every arm joint but A1, A3, A5.
  EXPECT_EQ(scene.driveControls({0.0, -0.2, 0.0, 0.2, 0.0, -0.2, 0.5}, 6), Violation::None);
  const std::vector<double> after = jointPositions(scene);
  EXPECT_LT(after[1], before[1] - 0.1);  // 0.2 * 1.92 rad/s for 0.3 s: 0.115 rad
  EXPECT_GT(after[3], before[3] + 0.1);
  EXPECT_GT(after[6], before[6] + 0.3);
  EXPECT_NEAR(after[0], before[0], 0.01);  // a zero control holds its joint too
  // The fingers, which no control moves, have not moved.
  EXPECT_NEAR(after[7], before[7], 1e-3);
  EXPECT_NEAR(after[8], before[8], 1e-3);
}

TEST(ControlSetPhysics, YumisIdleRightArmIsBuiltIntoTheStaticBaseWhereItsOffsetPutsIt) {
  ContextFixture scene("problems/yumi_clutter_5.xml");
  const WorldLayout& layout = scene.context.layout();
  const core::KinematicModel& model = scene.problem.robot.model;
  // The right arm and its fingers hang from the base through joints no control moves: no
  // bodies of theirs; the left arm's links and fingers (held, but on the moving arm) are.
  for (const BodyInfo& body : layout.bodies) {
    const std::string& name = body.name;
    EXPECT_FALSE(name.size() > 2 && name.compare(name.size() - 2, 2, "_r") == 0) << name;
    EXPECT_EQ(name.find("yumi_r_"), std::string::npos) << name;
  }
  EXPECT_NO_THROW(scene.body("yumi/yumi_link_7_l"));
  EXPECT_NO_THROW(scene.body("yumi/yumi_l_finger_right"));
  // Its links stand, static, where the query's start puts them.
  const std::vector<double> start = jointPositions(scene);
  const std::vector<Eigen::Isometry3d> poses =
      model.linkPoses(scene.problem.robot.home.isometry(), start);
  for (const std::string link : {"yumi_link_1_r", "yumi_link_7_r", "yumi_right_tcp"}) {
    const std::size_t l = static_cast<std::size_t>(*model.findLink(link));
    EXPECT_EQ(layout.robotLinks.at(l).body, -1) << link;
    EXPECT_TRUE(layout.robotLinks.at(l).pose.isApprox(poses[l], 1e-9)) << link;
  }
  std::size_t staticShapes = 0;
  bool linkSevenNamed = false;
  for (const ShapeInfo& shape : layout.shapes) {
    staticShapes += shape.role == "robot" && shape.body < 0 ? 1u : 0u;
    // Each static shape is named by its own link (what the replay page shows), not the base's.
    linkSevenNamed |= shape.body < 0 && shape.owner == "yumi/yumi_link_7_r";
  }
  EXPECT_GT(staticShapes, 8u);  // the body and the right arm's links collide still
  EXPECT_TRUE(linkSevenNamed);
  // Its joints read as their held values while the left arm moves, to the last bit.
  const std::size_t rightOne = 9;
  ASSERT_EQ(layout.joints[rightOne].name, "yumi_joint_1_r");
  EXPECT_TRUE(layout.joints[rightOne].held);
  EXPECT_EQ(scene.driveControls({0.3, -0.3, 0.2, 0.3, 0.0, 0.2, 0.5}, 6), Violation::None);
  const std::vector<double> after = jointPositions(scene);
  for (std::size_t j = rightOne; j < after.size(); ++j)
    EXPECT_EQ(after[j], start[j]) << layout.joints[j].name;
  EXPECT_GT(std::abs(after[0] - start[0]), 0.05);
}

TEST(ControlSetPhysics, AGoalLinkThatOnlyHeldJointsJoinToTheBaseIsABadInputNamingIt) {
  // yumi_clutter_5's goal is the left gripper's; a control set that moves only the right arm
  // builds the left arm into the static base, where it can never reach the goal.
  const fs::path file =
      fs::temp_directory_path() / ("kautham_right_" + std::to_string(::getpid()) + ".cntr");
  std::ofstream(file) << R"(<ControlSet>
  <Control name="right axis 1" eigValue="1"><DOF name="yumi/yumi_joint_1_r" value="1"/></Control>
</ControlSet>)";
  core::Problem problem = core::loadProblem(repoFile("problems/yumi_clutter_5.xml"));
  problem.robot.controls = core::loadControlSet(file, problem.robot.model, {});
  fs::remove(file);
  problem.queries.at(0).init = {0.5};
  try {
    ContextFixture scene(std::move(problem));
    FAIL() << "built a world whose goal link cannot move";
  } catch (const core::InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("yumi_clutter_5.xml"), std::string::npos) << message;
    EXPECT_NE(message.find("'yumi_left_tcp'"), std::string::npos) << message;
    EXPECT_NE(message.find("no control moves"), std::string::npos) << message;
  }
}

/// kuka_cans_5 with its arm driven by one control that combines two joints.
core::Problem kukaWithCombinedControl() {
  const fs::path file =
      fs::temp_directory_path() / ("kautham_combined_" + std::to_string(::getpid()) + ".cntr");
  // The offset is kuka_cans_5's <Init> (gripper down over the table, fingers half open); one
  // control turns A1 at half its weight and A7 at full weight, scaled by eigValue 0.5.
  std::ofstream(file) << R"(<ControlSet>
  <Offset>
    <DOF name="kuka/kuka_link_2" value="0.6667"/>
    <DOF name="kuka/kuka_link_4" value="0.125"/>
    <DOF name="kuka/kuka_link_6" value="0.7083"/>
  </Offset>
  <Control name="turn" eigValue="0.5">
    <DOF name="kuka/kuka_link_1" value="0.5"/>
    <DOF name="kuka/kuka_link_7" value="1"/>
  </Control>
</ControlSet>)";
  core::Problem problem = core::loadProblem(repoFile(kKuka));
  problem.robot.controls = core::loadControlSet(file, problem.robot.model, {});
  fs::remove(file);
  problem.queries.at(0).init = {0.5};
  return problem;
}

TEST(ControlSetPhysics, ACombinedControlMovesBothJointsAtTheRatioOfKTimesVmax) {
  ContextFixture scene(kukaWithCombinedControl());
  const WorldLayout& layout = scene.context.layout();
  ASSERT_EQ(scene.context.propagator().mapping().size(), 1u);
  // The start is the offset: A2 = +40 deg, the fingers half open.
  EXPECT_NEAR(jointPosition(scene, 1), 40.0 * M_PI / 180.0, 2e-3);
  EXPECT_NEAR(jointPosition(scene, 7), 0.0225, 1e-6);
  ASSERT_EQ(scene.context.startViolation(), Violation::None);
  const std::vector<double> before = jointPositions(scene);
  // K = 0.5 * (0.5, 0, .., 0, 1): u = 0.8 asks A1 for 0.2 vmax1 and A7 for 0.4 vmax7.
  EXPECT_EQ(scene.driveControls({0.8}, 8), Violation::None);
  const std::vector<double> after = jointPositions(scene);
  const double a1 = after[0] - before[0];
  const double a7 = after[6] - before[6];
  EXPECT_NEAR(a1, 0.2 * layout.joints[0].maxVelocity * 0.4, 0.02);  // 8 steps of 0.05 s
  EXPECT_GT(a7, 0.3);
  const double expectedRatio =
      (0.4 * layout.joints[6].maxVelocity) / (0.2 * layout.joints[0].maxVelocity);  // 3.35
  EXPECT_NEAR(a7 / a1, expectedRatio, 0.1 * expectedRatio);
  // The joints outside the control hold.
  for (std::size_t j : {1u, 2u, 3u, 4u, 5u, 7u, 8u})
    EXPECT_NEAR(after[j], before[j], 5e-3) << layout.joints[j].name;
}

// ----- a mobile base from <Limits> -----

TEST(MobileBasePhysics, DrivingTheBaseJointsMovesTheSphere) {
  ContextFixture scene(kSphere);
  const WorldLayout& layout = scene.context.layout();
  ASSERT_EQ(layout.joints.size(), 2u);
  EXPECT_EQ(layout.joints[0].name, "base_X");
  EXPECT_EQ(layout.joints[1].name, "base_Y");
  ASSERT_EQ(scene.context.startViolation(), Violation::None);
  const std::size_t sphere = scene.body("sphere/sphere");
  const Eigen::Vector3d start = WorldLayout::position(scene.state.data(), sphere);
  EXPECT_TRUE(start.isApprox(Eigen::Vector3d(-0.15, 0.0, 0.795), 1e-3)) << start.transpose();

  // X at half speed for 0.2 s: 0.5 * vmax * 0.2 s along +x, nothing else.
  const double vmax = layout.joints[0].maxVelocity;
  EXPECT_EQ(scene.driveControls({0.5, 0.0}, 4), Violation::None);
  const Eigen::Vector3d forward = WorldLayout::position(scene.state.data(), sphere);
  EXPECT_NEAR(forward.x() - start.x(), 0.5 * vmax * 0.2, 0.01);
  EXPECT_NEAR(forward.y(), start.y(), 1e-3);
  EXPECT_NEAR(forward.z(), start.z(), 1e-3);  // Z is fixed by <Home>
  EXPECT_NEAR(jointPosition(scene, 0), forward.x(), 1e-3);

  // Then Y backwards.
  EXPECT_EQ(scene.driveControls({0.0, -0.5}, 3), Violation::None);
  const Eigen::Vector3d sideways = WorldLayout::position(scene.state.data(), sphere);
  EXPECT_NEAR(sideways.y() - forward.y(), -0.5 * layout.joints[1].maxVelocity * 0.15, 0.01);
  EXPECT_NEAR(sideways.x(), forward.x(), 1e-3);
}

TEST(MobileBasePhysics, TheSpherePushesACube) {
  ContextFixture scene(kSphere);
  const std::size_t cube = scene.body("cube2");
  const Eigen::Vector3d before = WorldLayout::position(scene.state.data(), cube);
  // 0.35 m/s for 0.5 s: 17 cm along +x from x = -0.15, the cube's back face is at -0.025.
  Violation violation = Violation::None;
  for (int i = 0; i < 10 && violation == Violation::None; ++i)
    violation = scene.driveControls({0.7, 0.0}, 1);
  EXPECT_EQ(violation, Violation::None);
  const Eigen::Vector3d after = WorldLayout::position(scene.state.data(), cube);
  EXPECT_GT(after.x() - before.x(), 0.01);
}

// ----- goals -----

TEST(ConfigurationGoalPhysics, ReachedWhenTheNormalizedJointsAreWithinTolerance) {
  ContextFixture scene(kSphere);
  const WorkspaceGoal& goal = scene.context.goal();
  ASSERT_EQ(goal.spec().joints.size(), 2u);
  EXPECT_NEAR(goal.spec().joints[0], 0.15, 1e-12);  // <Goal>0.75 0.5</Goal>
  EXPECT_NEAR(goal.spec().joints[1], 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(goal.getThreshold(), 0.05);
  EXPECT_FALSE(goal.reached(scene.state.data()));  // the start: 0.5 normalized away in X
  EXPECT_NEAR(goal.distance(scene.state.data()), 0.5, 1e-3);

  const std::size_t q = scene.context.layout().jointPositionIndex();
  // X spans 0.6 m and Y 0.24 m: 0.04 normalized is 2.4 cm in X, 0.96 cm in Y.
  const std::vector<std::pair<std::pair<double, double>, bool>> cases = {
      {{0.15, 0.0}, true},
      {{0.15 + 0.024, 0.0}, true},
      {{0.15 - 0.036, 0.0}, false},  // 0.06 normalized
      {{0.15, 0.0096}, true},
      {{0.15, -0.0144}, false},           // 0.06 normalized
      {{0.15 + 0.018, 0.0072}, true},     // (0.03, 0.03): 0.042
      {{0.15 + 0.024, -0.0096}, false}};  // (0.04, 0.04): 0.057
  for (const auto& [joints, reached] : cases) {
    scene.state[q] = joints.first;
    scene.state[q + 1] = joints.second;
    EXPECT_EQ(goal.reached(scene.state.data()), reached) << joints.first << " " << joints.second;
    ompl::base::ScopedState<> state(scene.context.spaceInformation());
    std::copy(scene.state.begin(), scene.state.end(), WorldStateSpace::values(state.get()));
    double distance = -1.0;
    EXPECT_EQ(goal.isSatisfied(state.get(), &distance), reached);
    EXPECT_EQ(distance <= 0.05, reached) << distance;
  }
}

/// kuka_cans_5 with a world-frame goal region at the TCP's start position, approached along
/// `approach` within `tolerance`.
core::Problem kukaGoalAtStart(const Eigen::Vector3d& approach, double tolerance) {
  core::Problem problem = core::loadProblem(repoFile(kKuka));
  const ContextFixture probe(problem);
  core::GoalRegion& goal = problem.queries.at(0).goal;
  goal.relativeTo.clear();
  goal.offset = probe.context.layout().goalLinkPosition(probe.state.data());
  goal.approach = approach.normalized();
  goal.approachTolerance = tolerance;
  return problem;
}

TEST(ApproachGoalPhysics, TheKukaStartsWithTheGripperPointingDown) {
  const ContextFixture scene(kKuka);
  const Eigen::Vector3d axis =
      scene.context.layout().goalLinkOrientation(scene.state.data()) * Eigen::Vector3d::UnitZ();
  EXPECT_LT(std::acos(std::clamp(-axis.z(), -1.0, 1.0)), 0.02) << axis.transpose();
}

TEST(ApproachGoalPhysics, PositionFitsButTheApproachMustToo) {
  // Tilted 0.3 rad from straight down, about x.
  const Eigen::Vector3d tilted(0.0, std::sin(0.3), -std::cos(0.3));
  const std::vector<std::tuple<Eigen::Vector3d, double, bool>> cases = {
      {Eigen::Vector3d(0, 0, -1), 0.1, true},
      {tilted, 0.4, true},
      {tilted, 0.2, false},
      {Eigen::Vector3d(1, 0, 0), 0.6, false},  // the gripper points sideways
      {Eigen::Vector3d(0, 0, 1), 3.0, false}};
  for (const auto& [approach, tolerance, satisfied] : cases) {
    SCOPED_TRACE(::testing::Message() << approach.transpose() << " within " << tolerance);
    ContextFixture scene(kukaGoalAtStart(approach, tolerance));
    const WorkspaceGoal& goal = scene.context.goal();
    ompl::base::ScopedState<> start(scene.context.spaceInformation());
    std::copy(scene.state.begin(), scene.state.end(), WorldStateSpace::values(start.get()));
    double distance = -1.0;
    EXPECT_EQ(goal.isSatisfied(start.get(), &distance), satisfied);
    EXPECT_EQ(goal.reached(scene.state.data()), satisfied);
    if (satisfied) {
      EXPECT_NEAR(distance, 0.0, 1e-6);  // the position is exact
    } else {
      // The distance counts the excess angle, 0.1 m per radian.
      const double excess = goal.approachError(scene.state.data()) - tolerance;
      EXPECT_GT(excess, 0.0);
      EXPECT_NEAR(distance, 0.1 * excess, 1e-6);
    }
  }
}

}  // namespace
}  // namespace kautham::physics
