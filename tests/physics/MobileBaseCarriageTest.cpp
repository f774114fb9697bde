// Kautham's mobile base (<Limits name="X|Y">) under a heavy robot: the carriages between the
// base joints get the robot's mass, so ODE's iterative solver keeps the joints at their commanded
// speeds (with 0.5 kg carriages under a 25 kg sphere the rates jittered past 1.2 times their
// limit and nearly every state was rejected as "joint too fast"). A problem written here.

#include <gtest/gtest.h>

#include "physics/PhysicsTestSupport.h"

namespace kautham::physics {
namespace {

/// Kautham's SphereDE as its demos scale it: 25 kg, 25 cm radius.
const char* kHeavySphere = R"(<?xml version="1.0"?>
<robot name="heavy">
  <link name="ball">
    <inertial><mass value="25"/><inertia ixx="0.625" iyy="0.625" izz="0.625" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><sphere radius="0.25"/></geometry></collision>
  </link>
</robot>
)";

const char* kProblem = R"(<?xml version="1.0"?>
<Problem name="heavy_base">
  <Robot robot="heavy.urdf" scale="1">
    <Limits name="X" min="-2" max="2"/>
    <Limits name="Y" min="-2" max="2"/>
    <Home X="0" Y="0" Z="0.3" WX="0" WY="0" WZ="1" TH="0"/>
  </Robot>
  <Obstacle obstacle="box.urdf" scale="1"><Home X="0.8" Y="0" Z="0.15"/></Obstacle>
  <Planner>
    <Parameters><Name>KPIECE</Name></Parameters>
    <Queries><Query><Init>0.5 0.5</Init><Goal>0.9 0.5</Goal></Query></Queries>
  </Planner>
</Problem>
)";

TEST(MobileBaseCarriage, AHeavyRobotsBaseKeepsItsSpeedWhilePushing) {
  core::Problem problem = test::loadWrittenProblem(
      "kautham_heavy_base",
      {{"heavy.urdf", kHeavySphere}, {"box.urdf", test::kBoxUrdf}, {"heavy.xml", kProblem}},
      "heavy.xml");

  const core::KinematicModel& model = problem.robot.model;
  const core::Link& carriage =
      model.links[static_cast<std::size_t>(*model.findLink("mobile_base_X"))];
  EXPECT_DOUBLE_EQ(carriage.inertial.mass, 25.0);  // the robot's own mass

  test::ContextFixture fixture(std::move(problem));
  // Full speed along +x into the box (pushing it), back, and sideways.
  EXPECT_EQ(fixture.driveControls({1.0, 0.0}, 40), Violation::None);
  EXPECT_EQ(fixture.driveControls({-1.0, 1.0}, 20), Violation::None);
  EXPECT_EQ(fixture.driveControls({1.0, -1.0}, 20), Violation::None);
}

}  // namespace
}  // namespace kautham::physics
