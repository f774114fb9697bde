// Tracking a joint-space path (what a geometric planner's plan becomes) with a heavy mobile base
// on a weak motor under a light, strong arm: the tracked motion must stay on the straight segment
// the geometric planner checked. Without ramps the arm ran ahead while the base was still
// speeding up, and the robot left the segment (Kautham's TX90 on its base: 5 cm, into a column).
// A problem written here; jointInertias is checked on the same robot.

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "kautham/core/JointInertia.h"
#include "kautham/physics/PathTracking.h"
#include "physics/PhysicsTestSupport.h"

namespace kautham::physics {
namespace {

/// A 25 kg ball with a 5 kg arm turning about the ball's vertical axis, its centre of mass
/// 0.5 m out.
const char* kBallWithArm = R"(<?xml version="1.0"?>
<robot name="ballarm">
  <link name="ball">
    <inertial><mass value="25"/><inertia ixx="0.625" iyy="0.625" izz="0.625" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><sphere radius="0.25"/></geometry></collision>
  </link>
  <link name="arm">
    <inertial><origin xyz="0.5 0 0"/><mass value="5"/><inertia ixx="0.001" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0.5 0 0"/><geometry><box size="0.2 0.05 0.05"/></geometry></collision>
  </link>
  <joint name="arm_joint" type="revolute">
    <parent link="ball"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-3.14159" upper="3.14159" velocity="2" effort="200"/>
  </joint>
</robot>
)";

/// The base's motors give 30 N: 60 kg (the robot and one carriage of its mass) speed up at
/// 0.5 m/s^2, a tenth of a second at least to half their 0.5 m/s.
const char* kProblem = R"(<?xml version="1.0"?>
<Problem name="heavy_base_arm">
  <Robot robot="ballarm.urdf" scale="1">
    <Limits name="X" min="-2" max="2" effort="30"/>
    <Limits name="Y" min="-2" max="2" effort="30"/>
    <Home X="0" Y="0" Z="0.3" WX="0" WY="0" WZ="1" TH="0"/>
  </Robot>
  <Obstacle obstacle="box.urdf" scale="1"><Home X="0" Y="1.8" Z="0.15"/></Obstacle>
  <Planner>
    <Parameters><Name>RRTConnect</Name></Parameters>
    <Queries><Query><Init>0.5 0.5 0.5</Init><Goal>0.6 0.5 0.7</Goal></Query></Queries>
  </Planner>
</Problem>
)";

class HeavyBaseTest : public ::testing::Test {
 protected:
  static core::Problem load() {
    return test::loadWrittenProblem(
        "kautham_heavy_base_arm",
        {{"ballarm.urdf", kBallWithArm}, {"box.urdf", test::kBoxUrdf}, {"heavy.xml", kProblem}},
        "heavy.xml");
  }
};

TEST_F(HeavyBaseTest, JointInertiasAreWhatEachMotorMoves) {
  const core::Problem problem = load();
  const core::KinematicModel& model = problem.robot.model;
  const std::vector<double> inertias =
      core::jointInertias(model, problem.robot.home.isometry(), {0.0, 0.0, 0.0});
  ASSERT_EQ(inertias.size(), 3u);        // base_X, base_Y, arm_joint
  EXPECT_NEAR(inertias[0], 60.0, 1e-9);  // the Y carriage (30 kg) and the robot (30 kg)
  EXPECT_NEAR(inertias[1], 30.0, 1e-9);
  EXPECT_NEAR(inertias[2], 0.01 + 5.0 * 0.5 * 0.5, 1e-9);  // its own, and 5 kg 0.5 m out
}

TEST_F(HeavyBaseTest, TheTrackedMotionStaysOnTheSegmentWhileTheBaseSpeedsUp) {
  test::ContextFixture fixture(load());
  const PlanningContext& context = fixture.context;
  const std::size_t joints = context.layout().jointPositionIndex();
  const std::vector<double> start = context.startState();
  const std::vector<double> from(start.begin() + static_cast<long>(joints),
                                 start.begin() + static_cast<long>(joints) + 3);
  // The base 0.6 m along x while the arm turns 1.2 rad: both at once, along one straight segment.
  const std::vector<double> to{from[0] + 0.6, from[1], from[2] + 1.2};
  const TrackedPath tracked = trackJointPath(fixture.context, start, {to});
  EXPECT_TRUE(tracked.complete) << static_cast<int>(tracked.violation);
  EXPECT_GT(tracked.controls.size(), 5u);

  // On the segment, the base and the arm are equally far along it. 0.02 of the way is 1.2 cm of
  // the base or 1 cm of the arm's centre of mass.
  double worst = 0.0;
  for (const std::vector<double>& state : tracked.states) {
    const double base = (state[joints] - from[0]) / 0.6;
    const double arm = (state[joints + 2] - from[2]) / 1.2;
    worst = std::max(worst, std::abs(base - arm));
  }
  EXPECT_LT(worst, 0.02);
  const std::vector<double>& end = tracked.states.back();
  EXPECT_NEAR(end[joints], to[0], 1e-3);
  EXPECT_NEAR(end[joints + 2], to[2], 1e-3);
}

}  // namespace
}  // namespace kautham::physics
