// Each constraint of the validity checker, violated and not violated, on real scenes.

#include <cmath>

#include <gtest/gtest.h>

#include "physics/PhysicsTestSupport.h"

namespace kautham::physics {
namespace {

using test::ContextFixture;

TEST(ValidityTest, StartStatesOfTheShippedProblemsAreValid) {
  for (const char* file : {"problems/pusher_cans_5.xml", "problems/pusher_free.xml",
                           "tests/data/pusher_wall.xml", "problems/pusher_shelf.xml"}) {
    ContextFixture scene(file);
    EXPECT_EQ(scene.context.startViolation(), Violation::None) << file;
    EXPECT_EQ(scene.context.validityChecker().check(scene.state.data()), Violation::None) << file;
  }
}

TEST(ValidityTest, ObjectsInterpenetratingAtTheStartAreReported) {
  EXPECT_TRUE(ContextFixture("tests/data/pusher_wall.xml").context.startOverlaps().empty());
  ContextFixture scene("tests/data/overlap_can_in_glass.xml");
  const auto& overlaps = scene.context.startOverlaps();
  ASSERT_EQ(overlaps.size(), 1u);
  EXPECT_TRUE((overlaps[0].first == "can1" && overlaps[0].second == "glass") ||
              (overlaps[0].first == "glass" && overlaps[0].second == "can1"));
  EXPECT_GT(overlaps[0].depth, 0.002);
}

TEST(ValidityTest, RobotTouchingAFixedWallIsInvalid) {
  ContextFixture scene("tests/data/pusher_wall.xml");
  // The wall stands 15 cm ahead of the palm: driving forward must hit it, and nothing else.
  EXPECT_EQ(scene.drive({0.0, 0.2, 0.0}, 40), Violation::RobotTouchedFixed);
  EXPECT_LT(scene.state[0], 1.0);  // it stopped there: the state is the one that touched
}

TEST(ValidityTest, RobotMovingAlongsideAWallIsValid) {
  ContextFixture scene("tests/data/pusher_wall.xml");
  EXPECT_EQ(scene.drive({0.2, 0.0, 0.0}, 10), Violation::None);  // sideways, away from it
}

TEST(ValidityTest, RobotTouchingTheTargetIsInvalid) {
  ContextFixture scene("problems/pusher_free.xml");
  EXPECT_EQ(scene.drive({0.0, 0.25, 0.0}, 60), Violation::RobotTouchedTarget);
}

TEST(ValidityTest, RobotPushingAMovableCanIsValid) {
  ContextFixture scene("tests/data/pusher_wall.xml");
  // can1 stands at x = 0.35 beside the wall: move over to it, then push it with the palm.
  const Eigen::Vector3d before = WorldLayout::position(scene.state.data(), scene.body("can1"));
  EXPECT_EQ(scene.drive({0.25, 0.0, 0.0}, 28), Violation::None);  // 35 cm to the right
  EXPECT_EQ(scene.drive({0.0, 0.2, 0.0}, 16), Violation::None);   // 16 cm forward, into it
  const Eigen::Vector3d after = WorldLayout::position(scene.state.data(), scene.body("can1"));
  EXPECT_GT((after - before).norm(), 0.03);
}

TEST(ValidityTest, TargetMovedBeyondToleranceIsInvalid) {
  ContextFixture scene("problems/pusher_cans_5.xml");
  double* glass = scene.bodyState("glass");
  glass[0] += 0.004;  // within the 5 mm tolerance
  EXPECT_EQ(scene.context.validityChecker().check(scene.state.data()), Violation::None);
  glass[0] += 0.002;
  EXPECT_EQ(scene.context.validityChecker().check(scene.state.data()), Violation::TargetMoved);
}

TEST(ValidityTest, FastObjectIsInvalid) {
  ContextFixture scene("problems/pusher_cans_5.xml");
  double* can = scene.bodyState("can3");
  can[WorldLayout::kLinearVelocity] = 0.9;  // limit 1.0 m/s
  EXPECT_EQ(scene.context.validityChecker().check(scene.state.data()), Violation::None);
  can[WorldLayout::kLinearVelocity] = 1.1;
  EXPECT_EQ(scene.context.validityChecker().check(scene.state.data()), Violation::ObjectTooFast);
}

TEST(ValidityTest, TiltedObjectIsInvalid) {
  ContextFixture scene("problems/pusher_cans_5.xml");
  auto tilt = [&](double angle) {
    const Eigen::Quaterniond q(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()));
    double* can = scene.bodyState("can2");
    can[3] = q.w();
    can[4] = q.x();
    can[5] = q.y();
    can[6] = q.z();
    return scene.context.validityChecker().check(scene.state.data());
  };
  EXPECT_EQ(tilt(0.30), Violation::None);  // limit 0.35 rad
  EXPECT_EQ(tilt(0.40), Violation::ObjectTilted);
}

TEST(ValidityTest, ObjectOffTheTableIsInvalid) {
  ContextFixture scene("problems/pusher_cans_5.xml");
  double* can = scene.bodyState("can5");
  can[0] = 0.59;  // the table top spans x in [-0.6, 0.6]
  EXPECT_EQ(scene.context.validityChecker().check(scene.state.data()), Violation::None);
  can[0] = 0.61;
  EXPECT_EQ(scene.context.validityChecker().check(scene.state.data()), Violation::ObjectOffSupport);
  can[0] = 0.0;
  can[2] -= 0.01;  // settling into the table a little is fine
  EXPECT_EQ(scene.context.validityChecker().check(scene.state.data()), Violation::None);
  can[2] -= 0.02;  // fell through: well below its resting height
  EXPECT_EQ(scene.context.validityChecker().check(scene.state.data()), Violation::ObjectOffSupport);
}

TEST(ValidityTest, TheSupportIsTheTableTopEvenWhenTheTableIsTurned) {
  core::Problem problem = core::loadProblem(test::repoFile("problems/pusher_cans_5.xml"));
  core::ObjectInstance& table = problem.objects.at(*problem.findObject("table"));
  table.home.orientation = Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d::UnitZ());
  PlanningContext context(problem, 0, {});
  std::vector<double> state = context.startState();
  double* can = state.data() + 4 * WorldLayout::kBodyStateSize;  // a can (bodies 4..8)
  ASSERT_EQ(context.layout().bodies[4].role, BodyRole::Movable);
  can[0] = 0.3;  // on the turned 1.2 m x 0.8 m top
  can[1] = 0.2;
  EXPECT_EQ(context.validityChecker().check(state.data()), Violation::None);
  can[0] = 0.55;  // inside the top's bounding box, but off its corner
  can[1] = 0.35;
  EXPECT_EQ(context.validityChecker().check(state.data()), Violation::ObjectOffSupport);
}

TEST(ValidityTest, EndEffectorOutsideTheWorkspaceIsInvalid) {
  ContextFixture scene("problems/pusher_free.xml");
  // The workspace stops at x = 0.45, inside the x joint's reach (0.5): its stops are never
  // part of a valid plan.
  double* gripper = scene.bodyState("pusher/gripper");
  gripper[0] = 0.44;
  EXPECT_EQ(scene.context.validityChecker().check(scene.state.data()), Violation::None);
  gripper[0] = 0.46;
  EXPECT_EQ(scene.context.validityChecker().check(scene.state.data()), Violation::OutsideWorkspace);
}

TEST(ValidityTest, StatesRecordTheRobotJointsAsTheyMove) {
  ContextFixture scene("problems/pusher_free.xml");
  const WorldLayout& layout = scene.context.layout();
  ASSERT_EQ(layout.joints.size(), 3u);
  EXPECT_EQ(layout.joints[0].name, "x");
  const double x0 = scene.state[layout.jointPositionIndex()];
  const double palm0 = scene.bodyState("pusher/gripper")[0];
  EXPECT_EQ(scene.drive({0.2, 0.0, 0.0}, 10), Violation::None);
  const double x1 = scene.state[layout.jointPositionIndex()];
  // The joint moved as the palm did, and its rate is the commanded one.
  EXPECT_NEAR(x1 - x0, scene.bodyState("pusher/gripper")[0] - palm0, 1e-6);
  EXPECT_NEAR(x1 - x0, 0.1, 0.01);
  EXPECT_NEAR(scene.state[layout.jointVelocityIndex()], 0.2, 0.01);
}

TEST(ValidityTest, JointBeyondItsLimitIsInvalid) {
  ContextFixture scene("problems/pusher_free.xml");
  const WorldLayout& layout = scene.context.layout();
  const std::size_t yaw = layout.jointPositionIndex() + 2;  // limits +-0.6 rad
  scene.state[yaw] = 0.6 + 0.015;                           // within the 0.02 tolerance
  EXPECT_EQ(scene.context.validityChecker().check(scene.state.data()), Violation::None);
  scene.state[yaw] = 0.6 + 0.03;
  EXPECT_EQ(scene.context.validityChecker().check(scene.state.data()), Violation::JointLimit);
  scene.state[yaw] = std::nan("");
  EXPECT_EQ(scene.context.validityChecker().check(scene.state.data()), Violation::JointLimit);
}

TEST(ValidityTest, JointFasterThanItsLimitIsInvalid) {
  ContextFixture scene("problems/pusher_free.xml");
  const std::size_t yawRate = scene.context.layout().jointVelocityIndex() + 2;  // 0.5 rad/s
  scene.state[yawRate] = -0.59;  // within the default factor 1.2
  EXPECT_EQ(scene.context.validityChecker().check(scene.state.data()), Violation::None);
  scene.state[yawRate] = -0.61;
  EXPECT_EQ(scene.context.validityChecker().check(scene.state.data()), Violation::JointTooFast);
}

TEST(ValidityTest, RobotLinkFasterThanTheLimitIsInvalid) {
  ContextFixture scene("problems/pusher_free.xml");
  double* gripper = scene.bodyState("pusher/gripper");
  gripper[WorldLayout::kLinearVelocity + 2] = 1.9;  // default limit 2 m/s
  EXPECT_EQ(scene.context.validityChecker().check(scene.state.data()), Violation::None);
  gripper[WorldLayout::kLinearVelocity + 2] = 2.1;
  EXPECT_EQ(scene.context.validityChecker().check(scene.state.data()), Violation::LinkTooFast);
}

TEST(ValidityTest, KinodynamicLimitsComeFromTheProblemFile) {
  ContextFixture scene("tests/data/pusher_wall.xml");  // <Kinodynamics maxLinkSpeed="0.3" ..>
  EXPECT_DOUBLE_EQ(scene.problem.kinodynamics.maxLinkSpeed, 0.3);
  EXPECT_DOUBLE_EQ(scene.problem.kinodynamics.jointSpeedFactor, 1.5);
  EXPECT_DOUBLE_EQ(scene.problem.kinodynamics.jointLimitTolerance, 0.01);
  scene.bodyState("pusher/gripper")[WorldLayout::kLinearVelocity] = 0.31;
  EXPECT_EQ(scene.context.validityChecker().check(scene.state.data()), Violation::LinkTooFast);
}

TEST(ValidityTest, SimulationBlowUpIsDetectedAndRejected) {
  ContextFixture scene("problems/pusher_cans_5.xml");
  scene.bodyState("can4")[WorldLayout::kLinearVelocity] = std::nan("");
  EXPECT_EQ(scene.drive({0.0, 0.0, 0.0}, 1), Violation::SimulationDiverged);
  EXPECT_TRUE(scene.context.layout().flags(scene.state.data()) & kSimulationDiverged);
}

TEST(ValidityTest, RunawaySpeedIsDetectedAsBlowUp) {
  ContextFixture scene("problems/pusher_cans_5.xml");
  scene.bodyState("can4")[WorldLayout::kLinearVelocity + 2] = 1e6;  // a kick no push can give
  EXPECT_EQ(scene.drive({0.0, 0.0, 0.0}, 1), Violation::SimulationDiverged);
}

// ----- a sensed environment: the shelf of problems/pusher_shelf.xml, boxes from an octree -----

TEST(ValidityTest, RobotTouchingAShelfBoardIsInvalid) {
  ContextFixture scene("problems/pusher_shelf.xml");
  const std::size_t gripper = scene.body("pusher/gripper");
  // Left of the cans and the glass (x = -0.3), then forward: the fingers (8 cm ahead of the
  // gripper's origin) come within 2 cm of the lowest board (its front face at y = 0.42, at
  // the palm's height) without touching it, then slide along it, then touch it.
  EXPECT_EQ(scene.drive({-0.2, 0.0, 0.0}, 30), Violation::None);
  EXPECT_EQ(scene.drive({0.0, 0.2, 0.0}, 59), Violation::None);
  EXPECT_GT(WorldLayout::position(scene.state.data(), gripper).y(), 0.27);
  EXPECT_EQ(scene.drive({0.2, 0.0, 0.0}, 5), Violation::None);
  EXPECT_EQ(scene.drive({0.0, 0.2, 0.0}, 20), Violation::RobotTouchedFixed);
  const double y = WorldLayout::position(scene.state.data(), gripper).y();
  EXPECT_GT(y, 0.33);  // the fingers' tips reached the board ...
  EXPECT_LT(y, 0.36);  // ... inside the workspace: it is the board that made the state invalid
}

// ODE's box-cylinder collider finds no contact when the centre of one lies inside the other:
// the start probe looks for it, so a can standing around the pusher's 2 cm palm is reported.
TEST(ValidityTest, ARobotStartingInsideACanIsReported) {
  core::Problem problem = core::loadProblem(test::repoFile("problems/pusher_cans_5.xml"));
  const PlanningContext clear(problem, 0, PropagationSettings{});
  EXPECT_TRUE(clear.startOverlaps().empty());
  const Eigen::Vector3d palm = clear.layout().goalLinkPosition(clear.startState().data());
  core::Pose& can1 = problem.objects[*problem.findObject("can1")].home;
  can1.position.x() = palm.x();
  can1.position.y() = palm.y();
  const PlanningContext inside(problem, 0, PropagationSettings{});
  const auto& overlaps = inside.startOverlaps();
  ASSERT_EQ(overlaps.size(), 1u);
  EXPECT_EQ(overlaps[0].first, "pusher/gripper");
  EXPECT_EQ(overlaps[0].second, "can1");
  EXPECT_GT(overlaps[0].depth, 0.01);
}

TEST(ValidityTest, ObjectsInterpenetratingTheEnvironmentAtTheStartAreReported) {
  core::Problem problem = core::loadProblem(test::repoFile("problems/pusher_shelf.xml"));
  PlanningContext fine(problem, 0, PropagationSettings{});
  EXPECT_TRUE(fine.startOverlaps().empty());
  // can3 pushed back into the lowest board of the shelf.
  problem.objects[*problem.findObject("can3")].home.position.y() = 0.43;
  PlanningContext overlapping(problem, 0, PropagationSettings{});
  const auto& overlaps = overlapping.startOverlaps();
  ASSERT_EQ(overlaps.size(), 1u);
  EXPECT_TRUE((overlaps[0].first == "can3" && overlaps[0].second == "shelf") ||
              (overlaps[0].first == "shelf" && overlaps[0].second == "can3"));
  EXPECT_GT(overlaps[0].depth, 0.005);
}

// Objects start asleep, so one placed in the air would hang there: the start is left to rest
// once, and the objects that fall, slide or tip are named; the shipped scenes have none.
TEST(ValidityTest, ObjectsThatDoNotRestAtTheStartAreNamed) {
  for (const char* file : {"problems/kuka_clutter_40.xml", "problems/yumi_clutter_40.xml"})
    EXPECT_TRUE(ContextFixture(file).context.restlessAtStart().empty()) << file;
  core::Problem problem = core::loadProblem(test::repoFile("problems/pusher_cans_5.xml"));
  const PlanningContext resting(problem, 0, PropagationSettings{});
  EXPECT_TRUE(resting.restlessAtStart().empty());
  problem.objects[*problem.findObject("can2")].home.position.z() += 0.05;  // 5 cm up
  const PlanningContext floating(problem, 0, PropagationSettings{});
  const auto& restless = floating.restlessAtStart();
  ASSERT_EQ(restless.size(), 1u);
  EXPECT_EQ(restless[0].name, "can2");
  EXPECT_GT(restless[0].moved, 0.04);
  // The start itself is kept: the can is still where the file puts it, 5 cm up, asleep.
  std::size_t can2 = 0;
  while (floating.layout().bodies[can2].name != "can2") ++can2;
  EXPECT_NEAR(WorldLayout::position(floating.startState().data(), can2).z() -
                  WorldLayout::position(resting.startState().data(), can2).z(),
              0.05, 1e-9);
}

TEST(ValidityTest, ARobotStartingInsideTheEnvironmentIsInvalid) {
  core::Problem problem = core::loadProblem(test::repoFile("problems/pusher_shelf.xml"));
  // <Init> leaves the y joint at 0: the gripper starts at its home, here with the fingers'
  // tips at y = 0.36 + 0.08, 2 cm into the lowest board.
  problem.robot.home.position.y() = 0.36;
  PlanningContext context(problem, 0, PropagationSettings{});
  EXPECT_EQ(context.startViolation(), Violation::RobotTouchedFixed);
}

}  // namespace
}  // namespace kautham::physics
