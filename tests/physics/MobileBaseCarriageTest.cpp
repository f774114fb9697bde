// Kautham's mobile base (<Limits name="X|Y">) under a heavy robot: the carriages between the
// base joints get the robot's mass, so ODE's iterative solver keeps the joints at their commanded
// speeds (with 0.5 kg carriages under a 25 kg sphere the rates jittered past 1.2 times their
// limit and nearly every state was rejected as "joint too fast"). A problem written here.

#include <random>

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

/// As Kautham's Sphere demos write it: the base's <Home> 10 m from the robot's range.
const char* kFarHomeProblem = R"(<?xml version="1.0"?>
<Problem name="far_home">
  <Robot robot="heavy.urdf" scale="1">
    <Limits name="X" min="-2" max="2"/>
    <Limits name="Y" min="-2" max="2"/>
    <Home X="10" Y="10" Z="0.3" WX="0" WY="0" WZ="1" TH="0"/>
  </Robot>
  <Planner>
    <Parameters><Name>KPIECE</Name></Parameters>
    <Queries><Query><Init>0.5 0.5</Init><Goal>0.9 0.5</Goal></Query></Queries>
  </Planner>
</Problem>
)";

TEST(MobileBaseCarriage, ABaseWhoseHomeIsFarFromItsRangeKeepsItsSpeed) {
  core::Problem problem = test::loadWrittenProblem(
      "kautham_far_home", {{"heavy.urdf", kHeavySphere}, {"far.xml", kFarHomeProblem}}, "far.xml");

  // The X carriage rides 10 m from the middle of the robot's travel in y: it turns as its
  // mass would there (10 cm of gyration of its own about the line to it).
  const core::KinematicModel& model = problem.robot.model;
  const core::Link& carriage =
      model.links[static_cast<std::size_t>(*model.findLink("mobile_base_X"))];
  EXPECT_NEAR(carriage.inertial.inertia(2, 2), 25.0 * (0.01 + 10.0 * 10.0), 1e-9);
  EXPECT_NEAR(carriage.inertial.inertia(0, 0), 25.0 * (0.01 + 10.0 * 10.0), 1e-9);
  EXPECT_NEAR(carriage.inertial.inertia(1, 1), 25.0 * 0.01, 1e-9);  // about the line to it

  // Random pushes at up to full speed, each held for a few steps (as KPIECE's controls are):
  // with a 10 cm radius of gyration, 3 % of such states broke the speed rule.
  test::ContextFixture fixture(std::move(problem));
  std::mt19937 random(1);
  std::uniform_real_distribution<double> control(-1.0, 1.0);
  for (int push = 0; push < 60; ++push) {
    const std::vector<double> u{control(random), control(random)};
    ASSERT_EQ(fixture.driveControls(u, 2 + push % 8), Violation::None) << "push " << push;
  }
}

}  // namespace
}  // namespace kautham::physics
