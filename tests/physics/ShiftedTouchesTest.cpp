// World::robotTouchesShifted (the geometric planners' clearance test without ODE's bounding-box
// update per shift) finds what a full collision test finds with the robot moved by the shift.

#include <random>

#include <gtest/gtest.h>

#include "physics/PhysicsTestSupport.h"

namespace kautham::physics {
namespace {

/// `state` with every robot body moved by `offset`.
std::vector<double> shifted(const WorldLayout& layout, std::vector<double> state,
                            const Eigen::Vector3d& offset) {
  for (std::size_t b = 0; b < layout.bodies.size(); ++b) {
    if (layout.bodies[b].role != BodyRole::Robot) continue;
    double* p = state.data() + b * WorldLayout::kBodyStateSize + WorldLayout::kPosition;
    for (int k = 0; k < 3; ++k) p[k] += offset[k];
  }
  return state;
}

TEST(ShiftedTouches, FindWhatAFullTestOfTheShiftedRobotFinds) {
  // The KUKA's links are convex hulls of meshes; ten cans stand around it on the table.
  test::ContextFixture fixture("problems/kuka_clutter_10.xml");
  World& world = fixture.context.world();
  const WorldLayout& layout = fixture.context.layout();
  const double margin = 0.05;
  std::vector<Eigen::Vector3d> shifts;
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {-1.0, 1.0}) shifts.push_back(sign * margin * Eigen::Vector3d::Unit(axis));

  std::mt19937 random(3);
  std::uniform_real_distribution<double> velocity(-1.0, 1.0);
  const std::size_t controls = fixture.context.propagator().mapping().size();
  int compared = 0, touching = 0, nearOnly = 0;
  for (int move = 0; move < 40; ++move) {
    std::vector<double> u(controls);
    for (double& x : u) x = velocity(random);
    fixture.driveControls(u, 3);  // wherever the arm ends, touching or not
    const std::vector<double> state = fixture.state;
    world.writeState(state.data());
    const RobotTouches here = world.robotTouchesNear(-1, margin);
    for (const Eigen::Vector3d& shift : shifts) {
      const RobotTouches fast = world.robotTouchesShifted(shift);
      const std::vector<double> moved = shifted(layout, state, shift);
      world.writeState(moved.data());
      const RobotTouches full = world.robotTouches(-1);
      EXPECT_EQ(fast.fixed, full.fixed) << "move " << move;
      EXPECT_EQ(fast.target, full.target) << "move " << move;
      EXPECT_EQ(fast.bodies, full.bodies) << "move " << move;
      touching += full.any();
      nearOnly += full.any() && !here.any();
      ++compared;
      // Back to the state the pairs were found in.
      world.writeState(state.data());
      world.robotTouchesNear(-1, margin);
    }
  }
  EXPECT_EQ(compared, 240);
  // The comparison means something: some shifted arms touch, some only because of the shift.
  EXPECT_GT(touching, 0);
  EXPECT_GT(nearOnly, 0);
}

}  // namespace
}  // namespace kautham::physics
