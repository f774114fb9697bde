// Files researchers already have (issue 14): Kautham's Open Inventor / VRML meshes, URDFs that
// urdfdom reads only in part, ROS description packages (package://, mimic joints, xacro),
// Kautham's mobile bases with its own DOF names, several robots, GUI-only elements. All on small
// files in tests/data/kautham_compat.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "TestPaths.h"
#include "kautham/core/InputError.h"
#include "kautham/core/Log.h"
#include "kautham/core/PackagePaths.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/core/UrdfLoader.h"

namespace kautham::core {
namespace {

namespace fs = std::filesystem;
using test::repoFile;

fs::path compatFile(const std::string& name) {
  return repoFile("tests/data/kautham_compat/" + name);
}

/// Collects the warnings given while it lives.
class Warnings {
 public:
  Warnings() {
    resetWarnOnce();
    previous_ = setWarningSink([this](const std::string& m) { messages.push_back(m); });
  }
  ~Warnings() { setWarningSink(previous_); }
  int count(const std::string& phrase) const {
    int n = 0;
    for (const std::string& m : messages) n += m.find(phrase) != std::string::npos;
    return n;
  }
  std::vector<std::string> messages;

 private:
  WarningSink previous_;
};

std::string loadError(const fs::path& urdf) {
  try {
    loadUrdf(urdf, 1.0, {});
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << urdf << " loaded";
  return "";
}

Eigen::AlignedBox3d meshBounds(const KinematicModel& model) {
  Eigen::AlignedBox3d box;
  for (const Link& link : model.links)
    for (const CollisionShape& c : link.collisions) box.extend(boundingBox(c.shape, c.origin));
  return box;
}

/// Six times the volume the triangles enclose: positive when they face outwards.
double signedVolume(const Mesh& mesh) {
  double volume = 0.0;
  for (const auto& t : mesh.triangles())
    volume += mesh.vertices()[t[0]].dot(mesh.vertices()[t[1]].cross(mesh.vertices()[t[2]]));
  return volume;
}

TEST(InventorMesh, AnIvMeshIsReadWithItsTransformAndANegativeScaleMirrorsIt) {
  const KinematicModel model = loadUrdf(compatFile("iv_block.urdf"), 1.0, {});
  ASSERT_EQ(model.links.at(0).collisions.size(), 1u);
  const Mesh& mesh = std::get<Mesh>(model.links[0].collisions[0].shape);
  EXPECT_EQ(mesh.triangles().size(), 12u);
  const Eigen::AlignedBox3d box = meshBounds(model);
  EXPECT_TRUE(box.min().isApprox(Eigen::Vector3d(-0.1, 0.0, -0.03), 1e-6)) << box.min();
  EXPECT_TRUE(box.max().isApprox(Eigen::Vector3d(0.1, 0.1, 0.03), 1e-6)) << box.max();
  // scale="-1 1 1" mirrors it: the triangles are turned so they still face outwards.
  EXPECT_NEAR(signedVolume(mesh), 6.0 * 0.2 * 0.1 * 0.06, 1e-6);
}

TEST(InventorMesh, AVrmlMeshIsReadLikeTheIvOne) {
  const KinematicModel model = loadUrdf(compatFile("wrl_block.urdf"), 2.0, {});
  const Eigen::AlignedBox3d box = meshBounds(model);
  EXPECT_TRUE(box.min().isApprox(Eigen::Vector3d(-0.2, 0.0, -0.06), 1e-6)) << box.min();
  EXPECT_TRUE(box.max().isApprox(Eigen::Vector3d(0.2, 0.2, 0.06), 1e-6)) << box.max();
  EXPECT_GT(signedVolume(std::get<Mesh>(model.links[0].collisions[0].shape)), 0.0);
}

TEST(InventorMesh, AnUnreadableIvFileNamesTheUrdfLineAndCoinsReason) {
  const std::string message = loadError(compatFile("broken_iv.urdf"));
  EXPECT_NE(message.find("broken_iv.urdf:6: link 'block': mesh 'meshes/broken.iv': not a readable "
                         "Open Inventor / VRML file (Coin3D: "),
            std::string::npos)
      << message;
}

TEST(UrdfCollision, AMaterialWithoutANameKeepsTheCollisionBox) {
  const KinematicModel model = loadUrdf(compatFile("unnamed_material.urdf"), 1.0, {});
  ASSERT_EQ(model.links.at(0).collisions.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<Box>(model.links[0].collisions[0].shape));
  EXPECT_DOUBLE_EQ(model.links[0].inertial.mass, 0.5);
}

TEST(UrdfCollision, ACollisionUrdfdomDropsIsAnErrorWithItsLine) {
  const std::string message = loadError(compatFile("dropped_collision.urdf"));
  // urdfdom's own complaint first, then what it cost and what a collision needs.
  EXPECT_NE(message.find("dropped_collision.urdf:4: link 'base': urdfdom could not read it: "
                         "Unknown geometry type 'capsule'"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("so it read 0 of its 1 <collision> elements; each needs a <geometry>"),
            std::string::npos)
      << message;
}

TEST(UrdfCollision, AXacroFileSaysHowToExpandIt) {
  try {
    loadUrdf(compatFile("robot.xacro"), 1.0, {compatFile("problem.xml"), 4});
    FAIL() << "a .xacro loaded";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.where().line, 4);
    EXPECT_NE(message.find("'robot.xacro' is a xacro macro file, not a URDF: expand it first, "
                           "e.g. `xacro robot.xacro > robot.urdf`"),
              std::string::npos)
        << message;
  }
}

// ----- package:// -----

TEST(PackagePath, PackagesAreFoundAboveAndBesideTheUrdf) {
  setPackagePaths({});
  const KinematicModel model =
      loadUrdf(compatFile("ros/my_arm_description/urdf/arm.urdf"), 1.0, {});
  std::vector<std::string> sources;
  for (const Link& link : model.links)
    for (const CollisionShape& c : link.collisions)
      sources.push_back(std::get<Mesh>(c.shape).data->source.filename().string());
  EXPECT_EQ(sources, (std::vector<std::string>{"base.stl", "link.stl", "gripper.stl"}));
}

TEST(PackagePath, PackagePathOptionAndRosPackagePathFindAPackage) {
  const fs::path elsewhere = compatFile("iv_block.urdf");  // no package above it
  setPackagePaths({});
  ::unsetenv("ROS_PACKAGE_PATH");
  EXPECT_FALSE(findPackage("shared_meshes", elsewhere));
  ::setenv("ROS_PACKAGE_PATH", ("/nonexistent:" + compatFile("ros").string()).c_str(), 1);
  EXPECT_EQ(findPackage("shared_meshes", elsewhere), compatFile("ros/shared_meshes"));
  ::unsetenv("ROS_PACKAGE_PATH");
  setPackagePaths({{"shared_meshes", compatFile("meshes")}});  // the option wins
  EXPECT_EQ(findPackage("shared_meshes", elsewhere), compatFile("meshes"));
  setPackagePaths({});
  EXPECT_EQ(parsePackagePath("ur_description=../robots/ur").first, "ur_description");
  EXPECT_THROW(parsePackagePath("ur_description"), std::invalid_argument);
}

TEST(PackagePath, EveryMissingMeshIsReportedAtOnce) {
  setPackagePaths({});
  const std::string message = loadError(compatFile("ros/my_arm_description/urdf/missing.urdf"));
  EXPECT_NE(message.find("missing.urdf:5: 2 mesh files not found:"), std::string::npos) << message;
  EXPECT_NE(message.find("line 5: link 'base': mesh "
                         "'package://my_arm_description/meshes/nothing.stl': file not found"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("line 6: link 'base': mesh 'package://no_such_package/meshes/x.stl': "
                         "package 'no_such_package' not found (give --package-path "
                         "no_such_package=DIR"),
            std::string::npos)
      << message;
}

// ----- mimic joints -----

TEST(MimicJoint, AMimicJointFollowsItsLeaderAndHasNoControlOfItsOwn) {
  const Problem problem = loadProblem(compatFile("mimic_arm.xml"));
  EXPECT_EQ(problem.robot.controls.names, (std::vector<std::string>{"shoulder"}));
  // finger = 0.5 * shoulder: at the goal (shoulder at its upper limit 1) the finger is at 0.5.
  const std::vector<double> goal = problem.jointValuesFromControls({1.0});
  ASSERT_EQ(goal.size(), 2u);
  EXPECT_NEAR(goal[0], 1.0, 1e-12);
  EXPECT_NEAR(goal[1], 0.5, 1e-12);
  const std::vector<double> start = problem.initialJointValues(problem.queries.at(0));
  EXPECT_NEAR(start[0], 0.0, 1e-12);
  EXPECT_NEAR(start[1], 0.0, 1e-12);
  // Its speed limit keeps the ratio when the shared control turns both.
  const KinematicModel& model = problem.robot.model;
  EXPECT_NEAR(model.joints[1].maxVelocity, model.joints[0].maxVelocity * 1.0 / 2.0, 1e-12);
}

TEST(KauthamOdeDemo, GroundPlaneFloatingObjectsAndTinyInertiaAreHandledAndSaid) {
  Warnings warnings;
  const Problem problem = loadProblem(compatFile("mimic_arm.xml"));
  ASSERT_TRUE(problem.groundHeight.has_value());
  EXPECT_DOUBLE_EQ(*problem.groundHeight, 0.0);
  const ObjectInstance& wall = problem.objects.at(0);
  EXPECT_EQ(wall.role, ObjectRole::Movable);  // it has a mass and the planner simulates
  EXPECT_NEAR(wall.model.links[0].inertial.inertia(2, 2), 2.0 / 12.0 * (9.0 + 0.25), 1e-9);
  EXPECT_EQ(warnings.count("long_wall.urdf: link 'base': its inertia"), 1);
  // The block (its mesh's bottom at y... z = -0.03) floated 10 cm up: it starts on the ground.
  const ObjectInstance& block = problem.objects.at(1);
  EXPECT_NEAR(boundsAtHome(block).min().z(), 0.0, 1e-6);
  EXPECT_EQ(warnings.count("object 'iv_block' starts 0.100 m above Kautham's ground"), 1);
}

TEST(KauthamOdeDemo, AGeometricKauthamPlannerKeepsEveryObjectFixed) {
  const Problem problem = loadProblem(compatFile("mobile_base.xml"));
  EXPECT_FALSE(problem.groundHeight.has_value());
  for (const ObjectInstance& object : problem.objects) EXPECT_EQ(object.role, ObjectRole::Fixed);
}

// ----- a start a person can write -----

TEST(InitJoints, InitByJointNameInRadiansAndTheMimicJointFollows) {
  const Problem problem = loadProblem(compatFile("init_joints.xml"));
  const std::vector<double> start = problem.initialJointValues(problem.queries.at(0));
  ASSERT_EQ(start.size(), 2u);
  EXPECT_DOUBLE_EQ(start[0], 0.8);
  EXPECT_DOUBLE_EQ(start[1], 0.4);
}

TEST(InitJoints, AValueOutsideTheJointsLimitsNamesTheLineAndTheLimits) {
  try {
    loadProblem(compatFile("init_joint_outside.xml"));
    FAIL() << "loaded";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.where().line, 19);
    EXPECT_NE(message.find("joint 'shoulder' = 1.500000 is outside its limits [-1.000000, "
                           "1.000000] rad"),
              std::string::npos)
        << message;
  }
}

// ----- Kautham's mobile base -----

TEST(KauthamMobileBase, LimitsAreInTheWorldAPinnedAxisStaysAtHomeAndX3Turns) {
  Warnings warnings;
  const Problem problem = loadProblem(compatFile("mobile_base.xml"));
  const KinematicModel& model = problem.robot.model;
  std::vector<std::string> joints;
  for (int j : model.movableJoints()) joints.push_back(model.joints[j].name);
  EXPECT_EQ(joints, (std::vector<std::string>{"base_X", "base_Y", "base_X3"}));
  EXPECT_EQ(problem.robot.controls.names,
            (std::vector<std::string>{"mover/x", "mover/y", "mover/x3"}));
  // Init (0.5, 0.25, 0.5): x = 0, y = 0.5 in the world (Home's 5, 5 does not add), z at Home's
  // 0.03 (Z is pinned), turned by 2 pi * 0.25.
  const std::vector<double> start = problem.initialJointValues(problem.queries.at(0));
  const auto poses = model.linkPoses(problem.robot.home.isometry(), start);
  const Eigen::Isometry3d body = poses[static_cast<std::size_t>(*model.findLink("body"))];
  EXPECT_TRUE(body.translation().isApprox(Eigen::Vector3d(0.0, 0.5, 0.03), 1e-9))
      << body.translation().transpose();
  EXPECT_TRUE((body.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-9));
  // The goal (0.75, 0.5, 0.5): x = 0.5, y = 1.
  EXPECT_TRUE(
      problem.goalPosition(problem.queries[0].goal).isApprox(Eigen::Vector3d(0.5, 1, 0.03)));
  // GUI-only elements: one warning each. The second robot stands still as a fixed obstacle.
  EXPECT_EQ(warnings.count("<WeightSE3> is used by Kautham's GUI"), 1);
  EXPECT_EQ(warnings.count("<ViewLink> is used by Kautham's GUI"), 1);
  EXPECT_EQ(warnings.count("<InvKinematic> is used by Kautham's GUI"), 1);
  EXPECT_EQ(warnings.count("<Problem topology> is used by Kautham's GUI"), 1);
  EXPECT_EQ(warnings.count("only the first <Robot> ('mover') is planned for; robot 'my_arm'"), 1);
  ASSERT_TRUE(problem.findObject("my_arm"));
  const ObjectInstance& arm =
      problem.objects[static_cast<std::size_t>(*problem.findObject("my_arm"))];
  EXPECT_EQ(arm.role, ObjectRole::Fixed);
  EXPECT_TRUE(arm.model.movableJoints().empty());
}

TEST(KauthamMobileBase, TurningWithX3NeedsX1AtZero) {
  const std::string text = "";
  try {
    loadProblem(compatFile("tilting_base.xml"));
    FAIL() << "loaded";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("tilting_base.cntr"), std::string::npos) << message;
    EXPECT_NE(message.find("a control moves X3, the base's turn, but X1's offset is not 0"),
              std::string::npos)
        << message;
  }
}

TEST(KauthamMobileBase, ABaseDofWithoutLimitsIsAnErrorNamingTheFix) {
  try {
    loadProblem(compatFile("no_limits_base.xml"));
    FAIL() << "loaded";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("no_limits.cntr:2: the robot has no movable joint for this control set "
                           "to move (a base DOF X, Y or Z moves only with <Limits"),
              std::string::npos)
        << message;
  }
}

TEST(KauthamControlDimensions, ThePlannerDrivesTheFirstControlsAndTheOthersStayPut) {
  Warnings warnings;
  const Problem problem = loadProblem(compatFile("control_dimensions.xml"));
  EXPECT_EQ(problem.robot.controls.names, (std::vector<std::string>{"mover/x", "mover/y"}));
  EXPECT_EQ(warnings.count("control_dimensions.xml:19: Kautham's 'Control Dimensions' 2: its "
                           "planner drives the first 2 of the 3 controls; 'mover/x3' stays where "
                           "the queries put it"),
            1);
  const KinematicModel& model = problem.robot.model;
  ASSERT_EQ(model.movableJoints().size(), 3u);
  EXPECT_FALSE(problem.robot.controls.moves(2));  // base_X3: held, no control turns it
  // The start is where the three controls put it: x = 0, y = 0.5, turned by 2 pi (0.25 + 0.25).
  const Query& query = problem.queries.at(0);
  EXPECT_EQ(query.init.size(), 2u);
  EXPECT_EQ(query.goal.controls.size(), 2u);
  const std::vector<double> start = problem.initialJointValues(query);
  const auto poses = model.linkPoses(problem.robot.home.isometry(), start);
  const Eigen::Isometry3d body = poses[static_cast<std::size_t>(*model.findLink("body"))];
  EXPECT_TRUE(body.translation().isApprox(Eigen::Vector3d(0.0, 0.5, 0.03), 1e-9))
      << body.translation().transpose();
  EXPECT_TRUE((body.linear() * Eigen::Vector3d::UnitX()).isApprox(-Eigen::Vector3d::UnitX(), 1e-9));
  EXPECT_TRUE(problem.goalPosition(query.goal).isApprox(Eigen::Vector3d(0.5, 1, 0.03)));
}

TEST(KauthamControlDimensions, AControlTheQueriesMoveIsPlannedWithAWarning) {
  Warnings warnings;
  const Problem problem = loadProblem(compatFile("control_dimensions_moved.xml"));
  EXPECT_EQ(problem.robot.controls.size(), 3u);
  EXPECT_EQ(problem.queries.at(0).goal.controls.size(), 3u);
  EXPECT_EQ(warnings.count("Kautham's 'Control Dimensions' 2 would hold control 'mover/x3' still, "
                           "but the queries move it: all 3 controls are planned"),
            1);
}

TEST(KauthamFinalLinkGoal, TheGoalIsWhereTheGoalConfigurationPutsTheChainsEnd) {
  Warnings warnings;
  const Problem problem = loadProblem(compatFile("planar_chain.xml"));
  const GoalRegion& goal = problem.queries.at(0).goal;
  ASSERT_FALSE(goal.isConfiguration());
  EXPECT_EQ(goal.link, "hand");  // where the fingers branch, not the last finger in the file
  EXPECT_TRUE(goal.relativeTo.empty());
  EXPECT_DOUBLE_EQ(goal.tolerance, 0.05);
  // The shoulder at 0.75 of [-1.5, 1.5] (0.75 rad), the elbow straight: the hand 0.2 m out.
  EXPECT_TRUE(
      goal.offset.isApprox(Eigen::Vector3d(0.2 * std::cos(0.75), 0.2 * std::sin(0.75), 0.33), 1e-9))
      << goal.offset.transpose();
  EXPECT_EQ(warnings.count("planar_chain.xml:14: Kautham's 'only final link position?' 1: query "
                           "'query0' ends when 'hand' is within 0.050 m of (0.146, 0.136, 0.330)"),
            1);
  // Only the goal configuration moved the finger: 'Control Dimensions' 2 now holds it.
  EXPECT_EQ(problem.robot.controls.names, (std::vector<std::string>{"arm", "hand"}));
}

TEST(KauthamLinkInertia, AnInertiaNoMassInsideTheLinkCanHaveIsThatOfItsSolidBox) {
  Warnings warnings;
  const Problem problem = loadProblem(compatFile("planar_chain.xml"));
  const KinematicModel& model = problem.robot.model;
  const Link& arm = model.links.at(static_cast<std::size_t>(*model.findLink("arm")));
  // 0.1 kg in a 0.2 x 0.02 x 0.02 m box: at most 0.1 (0.2^2 + 0.02^2) = 0.00404 kg m^2.
  EXPECT_TRUE(arm.inertial.inertia.diagonal().isApprox(
      Eigen::Vector3d(0.1 / 12 * 0.0008, 0.1 / 12 * 0.0404, 0.1 / 12 * 0.0404), 1e-9))
      << arm.inertial.inertia.diagonal().transpose();
  EXPECT_EQ(warnings.count("link 'arm': its inertia (1, 1, 1) is more than a 0.1 kg body of its "
                           "size can have"),
            1);
  // Plausible inertias stay as written, and are not mentioned.
  const Link& hand = model.links.at(static_cast<std::size_t>(*model.findLink("hand")));
  EXPECT_DOUBLE_EQ(hand.inertial.inertia(0, 0), 0.000004);
  EXPECT_EQ(warnings.count("link 'hand'"), 0);
}

// ----- Kautham's own demos (../shared/kautham-demos), when they are there -----

TEST(KauthamDemos, EveryProblemFileLoads) {
  const fs::path demos = repoFile("../shared/kautham-demos");
  std::error_code ignored;
  if (!fs::is_directory(demos, ignored))
    GTEST_SKIP() << "Kautham's demos are not at " << demos << " (test data outside the project)";
  Warnings quiet;
  int problems = 0;
  for (const auto& entry : fs::recursive_directory_iterator(demos)) {
    if (entry.path().extension() != ".xml" ||
        entry.path().string().find("/models/") != std::string::npos)
      continue;
    std::ifstream in(entry.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.find("<Problem name") == std::string::npos) continue;  // benchmarks, synergy trees
    ++problems;
    EXPECT_NO_THROW(loadProblem(entry.path())) << entry.path();
  }
  EXPECT_GT(problems, 0);
}

}  // namespace
}  // namespace kautham::core
