// World::robotTouchesShifted (the geometric planners' clearance test without ODE's bounding-box
// update per shift) finds what a full collision test finds with the robot moved by the shift.

#include <filesystem>
#include <random>
#include <string>

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

/// Drives the robot of `problem` at random; at each state, compares the fast path (as
/// SceneChecker takes it: states written in turn, each with its shifts) with a second world,
/// used for nothing else, that tests every shifted state in full.
void compareWithFullTests(const std::string& problem) {
  test::ContextFixture fixture(problem);
  test::ContextFixture reference(problem);
  World& world = fixture.context.world();
  World& full = reference.context.world();
  const WorldLayout& layout = fixture.context.layout();
  const double margin = 0.05;
  std::vector<Eigen::Vector3d> shifts;
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {-1.0, 1.0}) shifts.push_back(sign * margin * Eigen::Vector3d::Unit(axis));

  std::mt19937 random(3);
  std::uniform_real_distribution<double> velocity(-1.0, 1.0);
  const std::size_t controls = fixture.context.propagator().mapping().size();
  const auto same = [](const RobotTouches& a, const RobotTouches& b) {
    return a.fixed == b.fixed && a.target == b.target && a.bodies == b.bodies;
  };
  int compared = 0, touching = 0, nearOnly = 0;
  for (int move = 0; move < 40; ++move) {
    std::vector<double> u(controls);
    for (double& x : u) x = velocity(random);
    fixture.driveControls(u, 3);  // wherever the arm ends, touching or not
    const std::vector<double> state = fixture.state;
    world.writeState(state.data());
    const RobotTouches here = world.robotTouchesNear(-1, margin);
    full.writeState(state.data());
    EXPECT_TRUE(same(here, full.robotTouches(-1))) << "move " << move;
    for (const Eigen::Vector3d& shift : shifts) {
      const RobotTouches fast = world.robotTouchesShifted(shift);
      const std::vector<double> moved = shifted(layout, state, shift);
      full.writeState(moved.data());
      const RobotTouches expected = full.robotTouches(-1);
      EXPECT_TRUE(same(fast, expected)) << "move " << move << ", shift " << shift.transpose();
      touching += expected.any();
      nearOnly += expected.any() && !here.any();
      ++compared;
    }
  }
  EXPECT_EQ(compared, 240);
  // The comparison means something: some shifted arms touch, some only because of the shift.
  EXPECT_GT(touching, 0);
  EXPECT_GT(nearOnly, 0);
}

TEST(ShiftedTouches, FindWhatAFullTestFindsAmongCans) {
  // The KUKA's links are convex hulls of meshes; ten cans stand around it on the table.
  compareWithFullTests("problems/kuka_clutter_10.xml");
}

TEST(ShiftedTouches, FindWhatAFullTestFindsAgainstATriangleMesh) {
  // Kautham's cube in its S-shaped passage, whose walls are one triangle mesh: ODE picks the
  // mesh's triangles by the cube's bounding box, which must follow the shift.
  const std::string demo =
      "../shared/kautham-demos/OMPL_geo_demos/Cube-sPassage_R2/OMPL_RRT_bigcube-s-passage_R2.xml";
  if (!std::filesystem::exists(test::repoFile(demo)))
    GTEST_SKIP() << "Kautham's demos (test data outside the project) are not at "
                 << test::repoFile(demo);
  compareWithFullTests(demo);
}

}  // namespace
}  // namespace kautham::physics
