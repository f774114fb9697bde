// Mesh objects in the ODE world of tests/data/pusher_bottle.xml: a bottle (movable) and a wine
// glass (target) collide as their convex hulls with the table (a box), cans (cylinders) and the
// robot.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

#include "TestPaths.h"
#include "kautham/core/Pose.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/physics/World.h"

namespace kautham::physics {
namespace {

class MeshWorldTest : public ::testing::Test {
 protected:
  core::Problem problem = core::loadProblem(test::repoFile("tests/data/pusher_bottle.xml"));
  World world{problem, problem.queries.front()};
  std::vector<double> state = std::vector<double>(world.layout().stateSize());

  std::size_t bodyNamed(const std::string& name) const {
    const auto& bodies = world.layout().bodies;
    for (std::size_t b = 0; b < bodies.size(); ++b)
      if (bodies[b].name == name) return b;
    throw std::runtime_error("no body " + name);
  }
  Eigen::Isometry3d poseOf(const std::string& name) {
    world.readState(state.data());
    return world.layout().linkPose(state.data(), bodyNamed(name));
  }
  double tiltOf(const std::string& name) {
    world.readState(state.data());
    return core::tiltAngle(WorldLayout::orientation(state.data(), bodyNamed(name)));
  }
  void run(double seconds) {
    const std::vector<double> still(world.actuators().size(), 0.0);
    world.setJointVelocities(still.data());
    const int steps = static_cast<int>(std::lround(seconds / world.settings().stepSize));
    for (int i = 0; i < steps; ++i) world.step();
  }
};

TEST_F(MeshWorldTest, MeshObjectsAreBodiesWithTheirMeshShapes) {
  std::size_t meshes = 0;
  for (const ShapeInfo& shape : world.layout().shapes)
    if (std::holds_alternative<core::Mesh>(shape.shape)) {
      ++meshes;
      EXPECT_TRUE(shape.owner == "bottle" || shape.owner == "wine_glass") << shape.owner;
      EXPECT_GE(shape.body, 0);  // on a dynamic body: collides as its convex hull
    }
  EXPECT_EQ(meshes, 2u);
  EXPECT_TRUE(world.probeContacts(0.002).empty());  // standing on the table, no overlap
}

TEST_F(MeshWorldTest, BottleStandsOnTheTableForTwoSeconds) {
  const Eigen::Isometry3d before = poseOf("bottle");
  run(2.0);
  const Eigen::Isometry3d after = poseOf("bottle");
  EXPECT_LT((after.translation() - before.translation()).norm(), 1e-3);
  EXPECT_LT(tiltOf("bottle"), 0.01);
  // Its hull's bottom rests on the table top (z = 0.75), not in it or above it.
  EXPECT_NEAR(after.translation().z() - 0.125, 0.75, 1e-3);
}

TEST_F(MeshWorldTest, WineGlassTargetStandsOnItsFoot) {
  const Eigen::Vector3d before = poseOf("wine_glass").translation();
  run(2.0);
  EXPECT_LT((poseOf("wine_glass").translation() - before).norm(),
            problem.interaction.targetTolerance);
  EXPECT_LT(tiltOf("wine_glass"), 0.02);  // it rocks on its foot by about 0.01 rad
}

TEST_F(MeshWorldTest, CanPushedIntoTheBottleMovesIt) {
  // Put can2 just left of the bottle and slide it to the right: cylinder against convex hull.
  world.readState(state.data());
  const std::size_t can = bodyNamed("can2"), bottle = bodyNamed("bottle");
  double* c = state.data() + can * WorldLayout::kBodyStateSize;
  const Eigen::Vector3d b = WorldLayout::position(state.data(), bottle);
  c[0] = b.x() - 0.033 - 0.035 - 0.003;
  c[1] = b.y();
  c[WorldLayout::kLinearVelocity] = 1.0;
  world.writeState(state.data());
  const Eigen::Vector3d before = poseOf("bottle").translation();
  run(1.0);
  const Eigen::Vector3d after = poseOf("bottle").translation();
  EXPECT_GT(after.x() - before.x(), 0.01) << "the can did not push the bottle";
  EXPECT_LT(std::abs(after.y() - before.y()), 0.01);
  EXPECT_LT(tiltOf("bottle"), 0.2);  // pushed low, it slides rather than falls
  world.readState(state.data());
  EXPECT_LT(WorldLayout::position(state.data(), can).x(), after.x());  // not through it
}

/// The same scene with the bottle as a fixed obstacle: it collides as its triangles (trimesh).
TEST(FixedMeshWorld, CanPushedIntoAFixedBottleStopsAtItsSurface) {
  std::ifstream in(test::repoFile("tests/data/pusher_bottle.xml"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string movable = "obstacle=\"objects/bottle.urdf\" role=\"movable\"";
  ASSERT_NE(text.find(movable), std::string::npos);
  text.replace(text.find(movable), movable.size(),
               "obstacle=\"objects/bottle.urdf\" role=\"fixed\"");
  const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                     ("kautham_fixed_bottle_" + std::to_string(getpid()) + ".xml");
  std::ofstream(file) << text;
  const core::Problem problem = core::loadProblem(file, {test::repoFile("models")});
  std::filesystem::remove(file);
  World world(problem, problem.queries.front());
  for (const ShapeInfo& shape : world.layout().shapes)
    if (shape.owner == "bottle") {
      EXPECT_EQ(shape.body, -1);  // static geometry
    }

  std::vector<double> state(world.layout().stateSize());
  world.readState(state.data());
  std::size_t can = 0;
  while (world.layout().bodies[can].name != "can2") ++can;
  double* c = state.data() + can * WorldLayout::kBodyStateSize;
  const Eigen::Vector3d bottle = problem.objects[*problem.findObject("bottle")].home.position;
  c[0] = bottle.x() - 0.033 - 0.035 - 0.003;
  c[1] = bottle.y();
  c[WorldLayout::kLinearVelocity] = 1.0;
  const double start = c[0];
  world.writeState(state.data());
  for (int i = 0; i < 100; ++i) world.step();
  world.readState(state.data());
  // Stopped by the bottle's triangles: the can's side at most a few millimetres inside them.
  EXPECT_LT(WorldLayout::position(state.data(), can).x() + 0.033, bottle.x() - 0.035 + 0.003);
  EXPECT_GT(WorldLayout::position(state.data(), can).x(), start - 0.05);  // not bounced away
}

}  // namespace
}  // namespace kautham::physics
