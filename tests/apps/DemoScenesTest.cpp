// The two hand-made demo scenes (docs/demos.md): problems/yumi_demo_wine_glass.xml and
// problems/kuka_demo_bottle.xml pass `kautham check` and hold what the documentation says.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include <gtest/gtest.h>

#include "TestPaths.h"
#include "apps/CommandTestSupport.h"
#include "kautham/core/Geometry.h"
#include "kautham/core/ProblemLoader.h"

namespace kautham::apps {
namespace {

namespace fs = std::filesystem;

using test::CommandRun;
using test::kautham;

core::Problem load(const std::string& file) {
  return core::loadProblem(fs::path(KAUTHAM_SOURCE_DIR) / file,
                           {fs::path(KAUTHAM_SOURCE_DIR) / "models"});
}

const core::ObjectInstance& object(const core::Problem& problem, const std::string& name) {
  const std::optional<int> index = problem.findObject(name);
  if (!index) throw std::runtime_error("no object " + name);
  return problem.objects[static_cast<std::size_t>(*index)];
}

std::vector<std::string> namesWithRole(const core::Problem& problem, core::ObjectRole role) {
  std::vector<std::string> names;
  for (const core::ObjectInstance& o : problem.objects)
    if (o.role == role) names.push_back(o.name);
  return names;
}

/// The only collision shape of a one-link object.
const core::Shape& onlyShape(const core::ObjectInstance& o) {
  EXPECT_EQ(o.model.links.size(), 1u) << o.name;
  EXPECT_EQ(o.model.links.front().collisions.size(), 1u) << o.name;
  return o.model.links.front().collisions.front().shape;
}

/// Distance in x and y from a point to the footprint of an object at its home pose, seen from
/// above (its bounding box; exact for upright cylinders along the axes through their centre,
/// and for unrotated boxes). 0 when the point is inside it.
double footprintDistance(const core::ObjectInstance& o, const Eigen::Vector3d& point) {
  const core::CollisionShape& c = o.model.links.front().collisions.front();
  const Eigen::Isometry3d pose = o.home.isometry() * c.origin;
  if (const auto* cylinder = std::get_if<core::Cylinder>(&c.shape))
    return std::max(0.0, (pose.translation() - point).head<2>().norm() - cylinder->radius);
  const Eigen::AlignedBox3d box = core::boundingBox(c.shape, pose);
  const double dx = std::max({box.min().x() - point.x(), 0.0, point.x() - box.max().x()});
  const double dy = std::max({box.min().y() - point.y(), 0.0, point.y() - box.max().y()});
  return std::hypot(dx, dy);
}

/// Lowest point of an object at its home pose.
double bottom(const core::ObjectInstance& o) {
  const core::CollisionShape& c = o.model.links.front().collisions.front();
  return core::boundingBox(c.shape, o.home.isometry() * c.origin).min().z();
}

/// What both scenes promise: every object stands on the table; the pre-grasp point lies in
/// front of the target, between it and the robot, at the target's height, pointing down; some
/// movable object stands within 2 cm of the pre-grasp point without covering it (the approach
/// is partly blocked), and none stands on it.
void expectDemoLayout(const core::Problem& problem) {
  SCOPED_TRACE(problem.name);
  constexpr double kTableTop = 0.75;
  for (const core::ObjectInstance& o : problem.objects) {
    if (o.role != core::ObjectRole::Fixed) {
      EXPECT_NEAR(bottom(o), kTableTop, 1e-3) << o.name;
    }
  }

  ASSERT_EQ(problem.queries.size(), 1u);
  const core::GoalRegion& goal = problem.queries.front().goal;
  const core::ObjectInstance& target = problem.target();
  EXPECT_EQ(goal.relativeTo, target.name);
  EXPECT_DOUBLE_EQ(goal.tolerance, 0.03);
  EXPECT_LE(goal.approachTolerance, 0.6);
  const std::optional<Eigen::Vector3d> approach = problem.goalApproach(goal);
  ASSERT_TRUE(approach.has_value());
  EXPECT_LT((*approach - Eigen::Vector3d(0, 0, -1)).norm(), 1e-9);

  const Eigen::Vector3d pregrasp = problem.goalPosition(goal);
  const Eigen::Vector3d targetAt = target.home.position;
  const double robotY = problem.robot.home.position.y();
  EXPECT_NEAR(pregrasp.x(), targetAt.x(), 1e-9);  // straight in front of the target ...
  EXPECT_LT(pregrasp.y(), targetAt.y() - 0.08);   // ... clear of it, on the robot's side
  EXPECT_GT(pregrasp.y(), robotY);
  EXPECT_NEAR(pregrasp.z(), targetAt.z(), 1e-9);
  EXPECT_TRUE(problem.workspace.contains(pregrasp));

  double nearest = 1e9;
  for (const core::ObjectInstance& o : problem.objects)
    if (o.role == core::ObjectRole::Movable)
      nearest = std::min(nearest, footprintDistance(o, pregrasp));
  EXPECT_GT(nearest, 0.0);   // nothing stands on the pre-grasp point ...
  EXPECT_LT(nearest, 0.02);  // ... but something stands right beside it
}

TEST(DemoScenesTest, YumiWineGlassPassesCheck) {
  const CommandRun run = kautham("check problems/yumi_demo_wine_glass.xml");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("target: wine_glass"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("wine_glass (wine_glass.stl: 386 vertices, 768 triangles"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("start valid"), std::string::npos) << run.output;
}

TEST(DemoScenesTest, KukaBottlePassesCheck) {
  const CommandRun run = kautham("check problems/kuka_demo_bottle.xml");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("target: cyan_cylinder"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("bottle (bottle.obj: 290 vertices, 576 triangles"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("start valid"), std::string::npos) << run.output;
}

TEST(DemoScenesTest, YumiWineGlassHasAMeshTargetAmongCans) {
  const core::Problem problem = load("problems/yumi_demo_wine_glass.xml");
  EXPECT_EQ(problem.robot.name, "yumi");
  EXPECT_EQ(namesWithRole(problem, core::ObjectRole::Fixed), std::vector<std::string>{"table"});
  EXPECT_EQ(namesWithRole(problem, core::ObjectRole::Target),
            std::vector<std::string>{"wine_glass"});
  const std::vector<std::string> cans = namesWithRole(problem, core::ObjectRole::Movable);
  EXPECT_EQ(cans,
            (std::vector<std::string>{"red_can1", "red_can2", "red_can3", "red_can4", "red_can5"}));

  const auto* glass = std::get_if<core::Mesh>(&onlyShape(object(problem, "wine_glass")));
  ASSERT_NE(glass, nullptr);
  EXPECT_EQ(glass->data->source.filename(), "wine_glass.stl");
  for (const std::string& name : cans) {
    const auto* can = std::get_if<core::Cylinder>(&onlyShape(object(problem, name)));
    ASSERT_NE(can, nullptr) << name;
    EXPECT_DOUBLE_EQ(can->radius, 0.033);
  }
  // The same robot, start and goal link as the generated YuMi scenes.
  const core::Problem generated = load("problems/yumi_cans_5.xml");
  EXPECT_EQ(problem.robot.home.position, generated.robot.home.position);
  EXPECT_EQ(problem.queries.front().init, generated.queries.front().init);
  EXPECT_EQ(problem.queries.front().goal.link, "yumi_left_tcp");
  EXPECT_EQ(problem.robot.controls.size(), generated.robot.controls.size());
  expectDemoLayout(problem);
}

TEST(DemoScenesTest, KukaBottleHasABottleMeshAndBoxesAroundACylinder) {
  const core::Problem problem = load("problems/kuka_demo_bottle.xml");
  EXPECT_EQ(problem.robot.name, "kuka");
  EXPECT_EQ(namesWithRole(problem, core::ObjectRole::Fixed), std::vector<std::string>{"table"});
  EXPECT_EQ(namesWithRole(problem, core::ObjectRole::Target),
            std::vector<std::string>{"cyan_cylinder"});
  EXPECT_EQ(namesWithRole(problem, core::ObjectRole::Movable),
            (std::vector<std::string>{"bottle", "box1", "box2", "box3", "box4"}));

  const core::ObjectInstance& target = object(problem, "cyan_cylinder");
  const auto* cylinder = std::get_if<core::Cylinder>(&onlyShape(target));
  ASSERT_NE(cylinder, nullptr);
  EXPECT_DOUBLE_EQ(cylinder->radius, 0.035);
  EXPECT_DOUBLE_EQ(cylinder->length, 0.14);

  const core::ObjectInstance& bottle = object(problem, "bottle");
  const auto* mesh = std::get_if<core::Mesh>(&onlyShape(bottle));
  ASSERT_NE(mesh, nullptr);
  EXPECT_EQ(mesh->data->source.filename(), "bottle.obj");

  for (const char* name : {"box1", "box2", "box3", "box4"}) {
    const core::ObjectInstance& box = object(problem, name);
    const auto* shape = std::get_if<core::Box>(&onlyShape(box));
    ASSERT_NE(shape, nullptr) << name;
    EXPECT_TRUE(shape->size.isApprox(Eigen::Vector3d(0.06, 0.06, 0.1))) << name;
    // models/objects/box.urdf: a uniform 300 g box, its inertia that of the box shape.
    const core::Inertial& inertial = box.model.links.front().inertial;
    EXPECT_DOUBLE_EQ(inertial.mass, 0.3);
    const Eigen::Vector3d s = shape->size;
    const Eigen::Vector3d uniform(s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(),
                                  s.x() * s.x() + s.y() * s.y());
    EXPECT_TRUE(inertial.inertia.diagonal().isApprox(inertial.mass / 12.0 * uniform, 1e-3))
        << inertial.inertia;
  }
  const core::Inertial& targetInertial = target.model.links.front().inertial;
  const double r = cylinder->radius, h = cylinder->length, m = targetInertial.mass;
  EXPECT_NEAR(targetInertial.inertia(0, 0), m * (3 * r * r + h * h) / 12.0, 1e-6);
  EXPECT_NEAR(targetInertial.inertia(2, 2), m * r * r / 2.0, 1e-6);

  const core::Problem generated = load("problems/kuka_cans_5.xml");
  EXPECT_EQ(problem.robot.home.position, generated.robot.home.position);
  EXPECT_EQ(problem.queries.front().init, generated.queries.front().init);
  EXPECT_EQ(problem.queries.front().goal.link, "kuka_tcp");
  expectDemoLayout(problem);
}

}  // namespace
}  // namespace kautham::apps
