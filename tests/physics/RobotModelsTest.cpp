// The shipped arm models (KUKA LWR 4+, ABB YuMi): what their URDFs say, where their forward
// kinematics puts the TCP, and how they behave in the real ODE world of a table problem.

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "TestPaths.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/core/UrdfLoader.h"
#include "kautham/physics/World.h"

namespace kautham::physics {
namespace {

constexpr double kDeg = M_PI / 180.0;

core::KinematicModel loadRobot(const std::string& file) {
  const auto path = test::repoFile("models/robots/" + file);
  return core::loadUrdf(path, 1.0, core::SourceLocation{path, 0});
}

const core::Joint& jointNamed(const core::KinematicModel& model, const std::string& name) {
  for (const core::Joint& joint : model.joints)
    if (joint.name == name) return joint;
  throw std::runtime_error("no joint " + name);
}

std::vector<std::string> movableNames(const core::KinematicModel& model) {
  std::vector<std::string> names;
  for (int j : model.movableJoints()) names.push_back(model.joints[j].name);
  return names;
}

void expectRevolute(const core::KinematicModel& model, const std::string& name, double lowerDeg,
                    double upperDeg, double velocityDeg, double effort = -1.0) {
  SCOPED_TRACE(name);
  const core::Joint& joint = jointNamed(model, name);
  EXPECT_EQ(joint.type, core::JointType::Revolute);
  EXPECT_NEAR(joint.lower, lowerDeg * kDeg, 1e-4);
  EXPECT_NEAR(joint.upper, upperDeg * kDeg, 1e-4);
  EXPECT_NEAR(joint.maxVelocity, velocityDeg * kDeg, 1e-4);
  if (effort > 0.0)
    EXPECT_DOUBLE_EQ(joint.maxEffort, effort);
  else
    EXPECT_GT(joint.maxEffort, 0.0);
}

void expectFinger(const core::KinematicModel& model, const std::string& name, double travel) {
  SCOPED_TRACE(name);
  const core::Joint& joint = jointNamed(model, name);
  EXPECT_EQ(joint.type, core::JointType::Prismatic);
  EXPECT_DOUBLE_EQ(joint.lower, 0.0);
  EXPECT_DOUBLE_EQ(joint.upper, travel);
  EXPECT_DOUBLE_EQ(joint.maxVelocity, 0.1);
  EXPECT_DOUBLE_EQ(joint.maxEffort, 20.0);
}

double totalMass(const core::KinematicModel& model) {
  double mass = 0.0;
  for (const core::Link& link : model.links) mass += link.inertial.mass;
  return mass;
}

/// The rotation of a child link relative to its parent, read as an angle about the joint axis.
double angleBetween(const core::Joint& joint, const Eigen::Isometry3d& parent,
                    const Eigen::Isometry3d& child) {
  const Eigen::Matrix3d motion =
      joint.origin.linear().transpose() * parent.linear().transpose() * child.linear();
  const Eigen::AngleAxisd angleAxis(motion);
  const double sign = angleAxis.axis().dot(joint.axis) < 0.0 ? -1.0 : 1.0;
  return sign * angleAxis.angle();
}

// ---------------------------------------------------------------------------------------------
// The URDF files, through the real loader

TEST(KukaModel, HasSevenArmJointsAndTwoFingersWithThePublishedLimits) {
  const core::KinematicModel model = loadRobot("kuka_lwr4.urdf");
  EXPECT_EQ(model.links[model.rootLink].name, "kuka_base");
  const std::vector<std::string> expected = {
      "kuka_joint_1", "kuka_joint_2",           "kuka_joint_3",
      "kuka_joint_4", "kuka_joint_5",           "kuka_joint_6",
      "kuka_joint_7", "kuka_finger_left_joint", "kuka_finger_right_joint"};
  EXPECT_EQ(movableNames(model), expected);
  const double range[] = {170, 120, 170, 120, 170, 120, 170};
  const double speed[] = {110, 110, 128, 128, 204, 184, 184};
  const double torque[] = {176, 176, 100, 100, 100, 38, 38};  // N*m
  for (int i = 0; i < 7; ++i)
    expectRevolute(model, "kuka_joint_" + std::to_string(i + 1), -range[i], range[i], speed[i],
                   torque[i]);
  expectFinger(model, "kuka_finger_left_joint", 0.045);
  expectFinger(model, "kuka_finger_right_joint", 0.045);
  ASSERT_TRUE(model.findLink("kuka_tcp").has_value());
  EXPECT_NEAR(totalMass(model), 16.6, 1e-9);  // 16 kg arm and base, 0.6 kg gripper
}

TEST(YumiModel, HasTwoSevenAxisArmsInChainOrderAndTwoFingersEach) {
  const core::KinematicModel model = loadRobot("yumi.urdf");
  EXPECT_EQ(model.links[model.rootLink].name, "yumi_body");
  std::vector<std::string> expected;
  for (const std::string side : {"l", "r"}) {
    for (const std::string axis : {"1", "2", "7", "3", "4", "5", "6"})
      expected.push_back("yumi_joint_" + axis + "_" + side);
    expected.push_back("yumi_" + side + "_finger_left_joint");
    expected.push_back("yumi_" + side + "_finger_right_joint");
  }
  EXPECT_EQ(movableNames(model), expected);
  for (const std::string side : {"l", "r"}) {
    // ABB IRB 14000 product specification: working range and maximum speed per axis
    expectRevolute(model, "yumi_joint_1_" + side, -168.5, 168.5, 180);
    expectRevolute(model, "yumi_joint_2_" + side, -143.5, 43.5, 180);
    expectRevolute(model, "yumi_joint_7_" + side, -168.5, 168.5, 180);
    expectRevolute(model, "yumi_joint_3_" + side, -123.5, 80, 180);
    expectRevolute(model, "yumi_joint_4_" + side, -290, 290, 400);
    expectRevolute(model, "yumi_joint_5_" + side, -88, 138, 400);
    expectRevolute(model, "yumi_joint_6_" + side, -229, 229, 400);
    expectFinger(model, "yumi_" + side + "_finger_left_joint", 0.025);
    expectFinger(model, "yumi_" + side + "_finger_right_joint", 0.025);
  }
  EXPECT_TRUE(model.findLink("yumi_left_tcp").has_value());
  EXPECT_TRUE(model.findLink("yumi_right_tcp").has_value());
  EXPECT_NEAR(totalMass(model), 38.0, 0.5);
}

TEST(RobotModels, EveryMovingBodyHasAtLeastATenthOfAKilogramAndAPositiveInertia) {
  for (const std::string file : {"kuka_lwr4.urdf", "yumi.urdf"}) {
    const core::KinematicModel model = loadRobot(file);
    for (int j : model.movableJoints()) {
      const core::Link& link = model.links[model.joints[j].childLink];
      SCOPED_TRACE(file + ": " + link.name);
      EXPECT_GE(link.inertial.mass, 0.1);
      EXPECT_GT(link.inertial.inertia.diagonal().minCoeff(), 0.0);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Forward kinematics at the zero configuration

TEST(KukaModel, PointsStraightUpAtZeroWithTheTcpAtThePublishedHeight) {
  const core::KinematicModel model = loadRobot("kuka_lwr4.urdf");
  const std::vector<Eigen::Isometry3d> poses = model.linkPoses(
      Eigen::Isometry3d::Identity(), std::vector<double>(model.movableJoints().size(), 0.0));
  // base to A2, A2 to A4, A4 to A6, A6 to flange, flange to fingertips (palm + fingers)
  const double height = 0.3105 + 0.4 + 0.39 + 0.078 + (0.03 + 0.06);
  const Eigen::Isometry3d& tcp = poses[*model.findLink("kuka_tcp")];
  EXPECT_NEAR((tcp.translation() - Eigen::Vector3d(0, 0, height)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(tcp.linear().col(2).z(), 1.0, 1e-9);  // approach direction: up, along the arm
  const Eigen::Isometry3d& a2 = poses[model.joints[1].childLink];
  EXPECT_NEAR(a2.translation().z(), 0.3105, 1e-9);
}

TEST(KukaModel, ElbowAtNinetyDegreesMovesTheTcpSidewaysByTheForearm) {
  // Independent check of axis directions: A4 = -90 deg turns the forearm about +y (A4's axis
  // is -y), so the wrist goes to +x by 0.39 m and the flange and gripper point along +x.
  const core::KinematicModel model = loadRobot("kuka_lwr4.urdf");
  std::vector<double> q(model.movableJoints().size(), 0.0);
  q[3] = -M_PI / 2;
  const std::vector<Eigen::Isometry3d> poses = model.linkPoses(Eigen::Isometry3d::Identity(), q);
  const Eigen::Vector3d expected(0.39 + 0.078 + 0.09, 0, 0.3105 + 0.4);
  const Eigen::Isometry3d& tcp = poses[*model.findLink("kuka_tcp")];
  EXPECT_NEAR((tcp.translation() - expected).norm(), 0.0, 1e-9);
  EXPECT_NEAR(tcp.linear().col(2).x(), 1.0, 1e-9);
}

TEST(YumiModel, ZeroConfigurationPutsTheTcpsWhereTheChainOfOffsetsSays) {
  const core::KinematicModel model = loadRobot("yumi.urdf");
  const std::vector<Eigen::Isometry3d> poses = model.linkPoses(
      Eigen::Isometry3d::Identity(), std::vector<double>(model.movableJoints().size(), 0.0));
  // The left arm's frames composed by hand from the published offsets (x-y-z, roll-pitch-yaw):
  auto frame = [](double x, double y, double z, double roll, double pitch, double yaw) {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.translation() = Eigen::Vector3d(x, y, z);
    t.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    return t;
  };
  const double h = M_PI / 2;
  for (const int side : {1, -1}) {
    const Eigen::Isometry3d tcp =
        frame(0.05355, side * 0.0725, 0.41492, side * 0.9781, -0.5716, side * 2.3180) *
        frame(0.03, 0, 0.1, h, 0, 0) * frame(-0.03, 0.17283, 0, -h, 0, 0) *
        frame(-0.04188, 0, 0.07873, h, -h, 0) * frame(0.0405, 0.16461, 0, -h, 0, 0) *
        frame(-0.027, 0, 0.10039, h, 0, 0) * frame(0.027, 0.029, 0, -h, 0, 0) *
        frame(0, 0, 0.007, 0, 0, M_PI) *       // flange to gripper
        frame(0, 0, 0.0837 + 0.045, 0, 0, 0);  // gripper body and fingers
    const std::string name = side > 0 ? "yumi_left_tcp" : "yumi_right_tcp";
    SCOPED_TRACE(name);
    const Eigen::Isometry3d& model_tcp = poses[*model.findLink(name)];
    // 1e-5: the URDF writes pi/2 and pi with 6 decimals
    EXPECT_NEAR((model_tcp.translation() - tcp.translation()).norm(), 0.0, 1e-5);
    EXPECT_NEAR((model_tcp.linear().col(2) - tcp.linear().col(2)).norm(), 0.0, 1e-5);
  }
  // the two arms are mirror images in the body's x-z plane
  const Eigen::Vector3d left = poses[*model.findLink("yumi_left_tcp")].translation();
  const Eigen::Vector3d right = poses[*model.findLink("yumi_right_tcp")].translation();
  EXPECT_NEAR((left - Eigen::Vector3d(right.x(), -right.y(), right.z())).norm(), 0.0, 1e-5);
}

// ---------------------------------------------------------------------------------------------
// In the real ODE world of a table problem

class ArmWorld {
 public:
  explicit ArmWorld(const std::string& problemFile)
      : problem(core::loadProblem(test::repoFile(problemFile))),
        world(problem, problem.queries.front()),
        state(world.layout().stateSize()) {
    world.resetSolverSeed();
  }

  /// Holds the given joint velocities for `seconds`; returns the ContactEvent flags raised, and
  /// the largest amount by which `watched` passed one of its limits at the end of any step.
  unsigned run(double seconds, const std::vector<double>& velocities, int watched = -1,
               double* pastLimit = nullptr) {
    world.setJointVelocities(velocities.data());
    const int steps = static_cast<int>(std::lround(seconds / world.settings().stepSize));
    unsigned events = 0;
    for (int i = 0; i < steps; ++i) {
      world.step();
      events |= world.takeEvents();
      if (pastLimit) {
        const core::Joint& joint = jointAt(watched);
        const double q = world.jointPositions()[static_cast<std::size_t>(watched)];
        *pastLimit = std::max({*pastLimit, q - joint.upper, joint.lower - q});
      }
    }
    return events;
  }

  const core::Joint& jointAt(int actuator) const {
    const core::KinematicModel& model = problem.robot.model;
    return model.joints[model.movableJoints()[static_cast<std::size_t>(actuator)]];
  }

  /// World pose of every robot link that is a body's main link, by link name.
  Eigen::Isometry3d linkPose(const std::string& link) {
    world.readState(state.data());
    const std::string name = problem.robot.name + "/" + link;
    const auto& bodies = world.layout().bodies;
    for (std::size_t b = 0; b < bodies.size(); ++b)
      if (bodies[b].name == name) return world.layout().linkPose(state.data(), b);
    // the root link is static: it stays at <Home>
    if (link == problem.robot.model.links[problem.robot.model.rootLink].name)
      return problem.robot.home.isometry();
    throw std::runtime_error("no body " + name);
  }

  /// The joint's angle measured from the poses of the two links it joins.
  double measuredAngle(int actuator) {
    const core::KinematicModel& model = problem.robot.model;
    const core::Joint& joint = jointAt(actuator);
    return angleBetween(joint, linkPose(model.links[joint.parentLink].name),
                        linkPose(model.links[joint.childLink].name));
  }

  std::vector<Eigen::Vector3d> robotBodyPositions() {
    world.readState(state.data());
    std::vector<Eigen::Vector3d> positions;
    for (std::size_t b = 0; b < world.layout().bodies.size(); ++b)
      if (world.layout().bodies[b].role == BodyRole::Robot)
        positions.push_back(WorldLayout::position(state.data(), b));
    return positions;
  }

  std::vector<double> zeros() const { return std::vector<double>(world.actuators().size(), 0.0); }

  core::Problem problem;
  World world;
  std::vector<double> state;
};

void expectArmHoldsStillForTwoSeconds(const std::string& problemFile, std::size_t bodies) {
  ArmWorld arm(problemFile);
  const std::vector<Eigen::Vector3d> before = arm.robotBodyPositions();
  ASSERT_EQ(before.size(), bodies);
  EXPECT_EQ(arm.run(2.0, arm.zeros()), 0u);
  const std::vector<Eigen::Vector3d> after = arm.robotBodyPositions();
  for (std::size_t i = 0; i < before.size(); ++i)
    EXPECT_LT((after[i] - before[i]).norm(), 1e-3) << "robot body " << i;
}

void expectJointTurnsAsCommanded(const std::string& problemFile, int actuator) {
  ArmWorld arm(problemFile);
  const double start = arm.measuredAngle(actuator);
  EXPECT_NEAR(start, arm.problem.initialJointValues(arm.problem.queries.front())[actuator], 1e-6);
  std::vector<double> velocities = arm.zeros();
  velocities[static_cast<std::size_t>(actuator)] = 0.3;
  EXPECT_EQ(arm.run(1.0, velocities), 0u);
  EXPECT_NEAR(arm.measuredAngle(actuator) - start, 0.3, 0.3 * 0.05);
}

void expectStopHolds(const std::string& problemFile, int actuator, double velocity) {
  ArmWorld arm(problemFile);
  std::vector<double> velocities = arm.zeros();
  velocities[static_cast<std::size_t>(actuator)] = velocity;
  double pastLimit = -1.0;
  const unsigned events = arm.run(3.0, velocities, actuator, &pastLimit);
  EXPECT_EQ(events & kSimulationDiverged, 0u);
  EXPECT_EQ(events, 0u) << "the arm touched something on its way to the stop";
  const core::Joint& joint = arm.jointAt(actuator);
  const double q = arm.world.jointPositions()[static_cast<std::size_t>(actuator)];
  // it reached the stop it was driven into ...
  EXPECT_NEAR(q, velocity > 0 ? joint.upper : joint.lower, 0.02);
  // ... and never passed it by more than 0.02 rad
  EXPECT_LE(pastLimit, 0.02);
  // driving back out of the stop neither blows up nor kicks the joint beyond its command, and
  // the joint reaches the commanded speed
  velocities[static_cast<std::size_t>(actuator)] = -velocity;
  const double speed = std::min(std::abs(velocity), joint.maxVelocity);
  double fastest = 0.0;
  for (int i = 0; i < 50; ++i) {
    EXPECT_EQ(arm.run(0.01, velocities) & kSimulationDiverged, 0u);
    fastest = std::max(fastest, std::abs(arm.world.jointVelocities()[std::size_t(actuator)]));
  }
  EXPECT_LE(fastest, 1.2 * speed);
  EXPECT_NEAR(arm.world.jointVelocities()[static_cast<std::size_t>(actuator)],
              velocity > 0 ? -speed : speed, 0.05 * speed);
}

TEST(KukaInWorld, ArmHoldsStillWithinOneMillimetreForTwoSeconds) {
  expectArmHoldsStillForTwoSeconds("tests/data/kuka_table.xml", 9);
}

TEST(KukaInWorld, JointOneTurnsByTheCommandedAngle) {
  expectJointTurnsAsCommanded("tests/data/kuka_table.xml", 0);
}

TEST(KukaInWorld, JointTwoDrivenIntoItsStopStaysThere) {
  // A2 from +40 deg to its -120 deg stop: the arm swings back, away from the table.
  expectStopHolds("tests/data/kuka_table.xml", 1, -1.0);
}

TEST(KukaInWorld, JointTwoDrivenIntoItsStopAtFullSpeedStaysThere) {
  expectStopHolds("tests/data/kuka_table.xml", 1, -10.0);  // clamped to 110 deg/s
}

TEST(KukaInWorld, WristWithItsPublishedTorqueLeavesItsStopWithoutAKick) {
  // A6 (38 N*m on the light wrist) from +50 deg to its +120 deg stop at full speed and back:
  // ODE pushes a joint out of its stop with the fudge factor times its effort.
  expectStopHolds("tests/data/kuka_table.xml", 5, 10.0);  // clamped to 184 deg/s
}

TEST(YumiInWorld, BothArmsHoldStillWithinOneMillimetreForTwoSeconds) {
  expectArmHoldsStillForTwoSeconds("tests/data/yumi_table.xml", 18);
}

TEST(YumiInWorld, AxisOneOfEachArmTurnsByTheCommandedAngle) {
  expectJointTurnsAsCommanded("tests/data/yumi_table.xml", 0);  // left
  expectJointTurnsAsCommanded("tests/data/yumi_table.xml", 9);  // right
}

TEST(YumiInWorld, AxisTwoOfEachArmDrivenIntoItsStopStaysThere) {
  expectStopHolds("tests/data/yumi_table.xml", 1, 1.0);   // left, up to +43.5 deg
  expectStopHolds("tests/data/yumi_table.xml", 10, 1.0);  // right
}

}  // namespace
}  // namespace kautham::physics
