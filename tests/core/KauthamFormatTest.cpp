// Kautham's own problem format: control sets (.cntr), mobile bases (<Limits>), configuration
// goals (<Goal>, <RobotControl>), the defaults for files without roles or <Workspace>, and
// Kautham's planner parameter names. Real files: problems/kuka_cans_5.xml, problems/kautham/,
// and variants of them written to a temporary folder.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>

#include "TestPaths.h"
#include "kautham/core/ControlSet.h"
#include "kautham/core/InputError.h"
#include "kautham/core/Log.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/planners/PlanRequest.h"

namespace kautham::core {
namespace {

namespace fs = std::filesystem;
using test::repoFile;

std::string readText(const fs::path& file) {
  std::ifstream in(file);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string replaceOnce(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "'" << from << "' is not in the text";
  if (at == std::string::npos) return text;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << "'" << from << "' is there twice";
  return text.replace(at, from.size(), to);
}

int lineOf(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  if (at == std::string::npos) return 0;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
}

std::vector<std::string> jointNames(const KinematicModel& model) {
  std::vector<std::string> names;
  for (int j : model.movableJoints()) names.push_back(model.joints[j].name);
  return names;
}

/// Normalized value of a joint value, given its URDF limits.
double normalized(const Joint& joint, double value) {
  return (value - joint.lower) / (joint.upper - joint.lower);
}

const char* const kKuka = "problems/kuka_cans_5.xml";
const char* const kSphere = "problems/kautham/sphere_cubes.xml";
const char* const kKukaTable = "problems/kautham/kuka_table.xml";

/// Writes variants (problems and .cntr files) to a temporary folder; models come from models/.
class KauthamVariant : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    folder_ = fs::temp_directory_path() / ("kautham_format_tests_" + std::string(info->name()) +
                                           "_" + std::to_string(::getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(folder_, ignored);
  }

  fs::path write(const std::string& text, const std::string& name) const {
    const fs::path file = folder_ / name;
    std::ofstream(file) << text;
    return file;
  }
  Problem load(const std::string& text) const {
    return loadProblem(write(text, "variant.xml"), {repoFile("models")});
  }
  /// kuka_cans_5.xml with its control set replaced by `cntr` (written beside the problem).
  Problem loadKukaWithControls(const std::string& cntr, const std::string& init) const {
    write(cntr, "test.cntr");
    std::string text = readText(repoFile(kKuka));
    text = replaceOnce(text, "robots/controls/kuka_lwr4_arm.cntr", "test.cntr");
    text = replaceOnce(text, "<Init>0.5 0.6667 0.5 0.125 0.5 0.7083 0.5</Init>",
                       "<Init>" + init + "</Init>");
    return load(text);
  }

  fs::path folder_;
};

// ----- control sets (.cntr) -----

TEST(ControlSetFile, KukaArmSetHasOneControlPerArmJointAndHoldsTheFingers) {
  const Problem problem = loadProblem(repoFile(kKuka));
  const ControlSet& set = problem.robot.controls;
  EXPECT_EQ(set.names, (std::vector<std::string>{"A1", "A2", "A3", "A4", "A5", "A6", "A7"}));
  EXPECT_EQ(set.file, repoFile("models/robots/controls/kuka_lwr4_arm.cntr"));
  EXPECT_EQ(set.where.line, lineOf(readText(repoFile(kKuka)), "<Controls "));
  ASSERT_EQ(set.matrix.rows(), 9);
  ASSERT_EQ(set.matrix.cols(), 7);
  // Rows follow movableJoints(): the seven arm joints, then the two fingers.
  const std::vector<std::string> joints = jointNames(problem.robot.model);
  EXPECT_EQ(joints[0], "kuka_joint_1");
  EXPECT_EQ(joints[7], "kuka_finger_left_joint");
  EXPECT_EQ(joints[8], "kuka_finger_right_joint");
  EXPECT_TRUE(set.matrix.topRows(7).isApprox(Eigen::MatrixXd::Identity(7, 7)));
  EXPECT_TRUE(set.matrix.bottomRows(2).isZero());
  for (std::size_t dof = 0; dof < 7; ++dof) EXPECT_TRUE(set.moves(dof)) << dof;
  EXPECT_FALSE(set.moves(7));
  EXPECT_FALSE(set.moves(8));
  EXPECT_TRUE(set.offset.isApprox(Eigen::VectorXd::Constant(9, 0.5)));
}

TEST(ControlSetFile, KukaInitMapsThroughKAndTheOffsetOntoTheJointLimits) {
  const Problem problem = loadProblem(repoFile(kKuka));
  const Query& query = problem.queries.at(0);
  ASSERT_EQ(query.init.size(), 7u);  // one per control, not one per joint (9)
  const std::vector<double> joints = problem.initialJointValues(query);
  ASSERT_EQ(joints.size(), 9u);
  const KinematicModel& model = problem.robot.model;
  const std::vector<int> movable = model.movableJoints();
  // K = I on the arm, o = 0.5: q = c, then [0, 1] onto [lower, upper].
  for (std::size_t i = 0; i < 7; ++i) {
    const Joint& joint = model.joints[movable[i]];
    EXPECT_NEAR(joints[i], joint.lower + query.init[i] * (joint.upper - joint.lower), 1e-12)
        << joint.name;
  }
  EXPECT_NEAR(joints[0], 0.0, 1e-12);                 // A1 mid-range
  EXPECT_NEAR(joints[1], 40.0 * M_PI / 180.0, 1e-3);  // A2 = +40 deg
  EXPECT_NEAR(joints[3], -M_PI / 2.0, 1e-3);          // A4 = -90 deg
  EXPECT_NEAR(joints[5], 50.0 * M_PI / 180.0, 1e-3);  // A6 = +50 deg
  // The fingers end at their offset, whatever the controls say.
  EXPECT_NEAR(joints[7], 0.0225, 1e-12);
  EXPECT_NEAR(joints[8], 0.0225, 1e-12);
  const std::vector<double> extreme =
      problem.jointValuesFromControls({0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0});
  EXPECT_NEAR(extreme[7], 0.0225, 1e-12);
  EXPECT_NEAR(extreme[0], model.joints[movable[0]].lower, 1e-12);
  EXPECT_NEAR(extreme[1], model.joints[movable[1]].upper, 1e-12);
}

TEST_F(KauthamVariant, EigValueScalesAControlsColumnAndTheOffsetShiftsIt) {
  // DOF names: "robot/child link", the bare child link, and the joint name all work.
  const Problem problem = loadKukaWithControls(
      R"(<ControlSet>
  <Offset>
    <DOF name="kuka/kuka_link_1" value="0.25"/>
    <DOF name="kuka_finger_left_joint" value="1"/>
  </Offset>
  <Control name="shoulder" eigValue="0.5">
    <DOF name="kuka/kuka_link_1" value="1"/>
    <DOF name="kuka_link_2" value="-0.5"/>
  </Control>
  <Control name="wrist" eigValue="3">
    <DOF name="kuka_joint_7" value="1"/>
  </Control>
</ControlSet>)",
      "0.5 0.5");
  const ControlSet& set = problem.robot.controls;
  EXPECT_EQ(set.names, (std::vector<std::string>{"shoulder", "wrist"}));
  ASSERT_EQ(set.matrix.rows(), 9);
  ASSERT_EQ(set.matrix.cols(), 2);
  EXPECT_DOUBLE_EQ(set.matrix(0, 0), 0.5);
  EXPECT_DOUBLE_EQ(set.matrix(1, 0), -0.25);
  EXPECT_DOUBLE_EQ(set.matrix(6, 1), 3.0);
  EXPECT_DOUBLE_EQ(set.matrix.cwiseAbs().sum(), 3.75);  // nothing else
  EXPECT_DOUBLE_EQ(set.offset[0], 0.25);
  EXPECT_DOUBLE_EQ(set.offset[7], 1.0);
  EXPECT_DOUBLE_EQ(set.offset[1], 0.5);  // not in <Offset>: the middle

  // q = clip(K (c - 0.5) + o, 0, 1), checked by hand for c = (0.9, 0.6).
  const Eigen::VectorXd q = set.normalizedConfiguration({0.9, 0.6});
  EXPECT_NEAR(q[0], 0.5 * 0.4 + 0.25, 1e-12);
  EXPECT_NEAR(q[1], -0.25 * 0.4 + 0.5, 1e-12);
  EXPECT_NEAR(q[6], 3.0 * 0.1 + 0.5, 1e-12);
  EXPECT_NEAR(q[7], 1.0, 1e-12);
  EXPECT_NEAR(q[8], 0.5, 1e-12);
  // Clipping: the wrist's 3 * 0.4 + 0.5 = 1.7 stops at 1, and 3 * (-0.5) + 0.5 at 0.
  EXPECT_NEAR(set.normalizedConfiguration({0.5, 0.9})[6], 1.0, 1e-12);
  EXPECT_NEAR(set.normalizedConfiguration({0.5, 0.0})[6], 0.0, 1e-12);
  EXPECT_NEAR(set.normalizedConfiguration({0.5, 0.55})[6], 0.65, 1e-12);

  // Joint values: normalized onto the URDF limits.
  const KinematicModel& model = problem.robot.model;
  const std::vector<int> movable = model.movableJoints();
  const std::vector<double> joints = problem.jointValuesFromControls({0.9, 0.6});
  for (std::size_t i = 0; i < joints.size(); ++i)
    EXPECT_NEAR(normalized(model.joints[movable[i]], joints[i]), q[static_cast<Eigen::Index>(i)],
                1e-12)
        << i;
  EXPECT_NEAR(joints[7], 0.045, 1e-12);  // left finger fully open
}

TEST_F(KauthamVariant, TheSameDofNamedThreeWaysIsOneRow) {
  for (const std::string name : {"kuka/kuka_link_3", "kuka_link_3", "kuka_joint_3"}) {
    SCOPED_TRACE(name);
    const Problem problem =
        loadKukaWithControls("<ControlSet><Control name=\"c\"><DOF name=\"" + name +
                                 "\" value=\"1\"/></Control></ControlSet>",
                             "0.5");
    ASSERT_EQ(problem.robot.controls.matrix.cols(), 1);
    EXPECT_DOUBLE_EQ(problem.robot.controls.matrix(2, 0), 1.0);
    EXPECT_DOUBLE_EQ(problem.robot.controls.matrix.cwiseAbs().sum(), 1.0);
  }
}

TEST(ControlSetFile, WithoutAControlsElementThereIsOneControlPerJoint) {
  const Problem problem = loadProblem(repoFile("problems/pusher_cans_5.xml"));
  const ControlSet& set = problem.robot.controls;
  EXPECT_EQ(set.names, (std::vector<std::string>{"x", "y", "yaw"}));
  EXPECT_TRUE(set.matrix.isApprox(Eigen::MatrixXd::Identity(3, 3)));
  EXPECT_TRUE(set.offset.isApprox(Eigen::VectorXd::Constant(3, 0.5)));
  EXPECT_TRUE(set.file.empty());
}

// ----- <Limits name="X|Y|Z">: a mobile base -----

TEST(MobileBase, LimitsXAndYAddPrismaticBaseJointsFirst) {
  const Problem problem = loadProblem(repoFile(kSphere));
  const KinematicModel& model = problem.robot.model;
  EXPECT_EQ(jointNames(model), (std::vector<std::string>{"base_X", "base_Y"}));
  const std::vector<int> movable = model.movableJoints();
  const Joint& x = model.joints[movable[0]];
  const Joint& y = model.joints[movable[1]];
  EXPECT_EQ(x.type, JointType::Prismatic);
  EXPECT_EQ(y.type, JointType::Prismatic);
  EXPECT_TRUE(x.axis.isApprox(Eigen::Vector3d::UnitX()));
  EXPECT_TRUE(y.axis.isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_DOUBLE_EQ(x.lower, -0.3);
  EXPECT_DOUBLE_EQ(x.upper, 0.3);
  EXPECT_DOUBLE_EQ(y.lower, -0.12);
  EXPECT_DOUBLE_EQ(y.upper, 0.12);
  EXPECT_GT(x.maxVelocity, 0.0);
  // The chain: a static mount, the X carriage, then the URDF's root link.
  EXPECT_EQ(model.rootLink, 0);
  EXPECT_EQ(model.links[0].name, "mobile_base_mount");
  EXPECT_EQ(model.links[static_cast<std::size_t>(x.childLink)].name, "mobile_base_X");
  EXPECT_EQ(model.links[static_cast<std::size_t>(y.childLink)].name, "sphere");
  ASSERT_EQ(problem.robot.baseAxes.size(), 2u);
  // The base joints place the sphere: Init (0.25, 0.5) is x = -0.15, y = 0 in the Home frame.
  const std::vector<double> joints = problem.initialJointValues(problem.queries.at(0));
  ASSERT_EQ(joints.size(), 2u);
  EXPECT_NEAR(joints[0], -0.15, 1e-12);
  EXPECT_NEAR(joints[1], 0.0, 1e-12);
  const auto poses = model.linkPoses(problem.robot.home.isometry(), joints);
  EXPECT_TRUE(poses[static_cast<std::size_t>(*model.findLink("sphere"))].translation().isApprox(
      Eigen::Vector3d(-0.15, 0.0, 0.795)));
}

TEST_F(KauthamVariant, RotationalLimitsAreAcceptedAndIgnored) {
  const std::string text =
      replaceOnce(readText(repoFile(kSphere)), "    <Home X=\"0\" Y=\"0\" Z=\"0.795\"",
                  "    <Limits name=\"WX\" min=\"0\" max=\"0\"/>\n"
                  "    <Limits name=\"WY\" min=\"0\" max=\"0\"/>\n"
                  "    <Limits name=\"WZ\" min=\"0\" max=\"1\"/>\n"
                  "    <Limits name=\"TH\" min=\"-3.1416\" max=\"3.1416\"/>\n"
                  "    <Home X=\"0\" Y=\"0\" Z=\"0.795\"");
  const Problem problem = load(text);
  EXPECT_EQ(jointNames(problem.robot.model), (std::vector<std::string>{"base_X", "base_Y"}));
  EXPECT_EQ(problem.robot.baseAxes.size(), 2u);
}

TEST_F(KauthamVariant, LimitsAreUnusedWhenTheControlSetNamesNoBaseDof) {
  std::string text = readText(repoFile(kKuka));
  text = replaceOnce(text, "  <Robot robot=\"robots/kuka_lwr4.urdf\" name=\"kuka\">\n",
                     "  <Robot robot=\"robots/kuka_lwr4.urdf\" name=\"kuka\">\n"
                     "    <Limits name=\"Z\" min=\"-0.1\" max=\"0.1\"/>\n"
                     "    <Limits name=\"X\" min=\"-0.2\" max=\"0.2\"/>\n");
  // As in Kautham: the arm's control set names none of X, Y, Z, X1, X2, X3, so the base stays
  // at <Home> and the limits are unused (with a warning), not joints held at their middle.
  std::vector<std::string> warnings;
  const WarningSink previous =
      setWarningSink([&](const std::string& message) { warnings.push_back(message); });
  const Problem problem = load(text);
  setWarningSink(previous);
  const std::vector<std::string> joints = jointNames(problem.robot.model);
  ASSERT_EQ(joints.size(), 9u);
  EXPECT_EQ(joints[0], "kuka_joint_1");
  bool warned = false;
  for (const std::string& w : warnings)
    warned |= w.find("the <Limits> are unused") != std::string::npos;
  EXPECT_TRUE(warned);
  const std::vector<double> values = problem.initialJointValues(problem.queries.at(0));
  EXPECT_NEAR(values[1], 40.0 * M_PI / 180.0, 1e-3);  // A2 as before
}

// ----- configuration goals: <Goal> and <RobotControl> -----

TEST(ConfigurationGoal, GoalIsNormalizedControlsAndItsLinkIsTheTip) {
  const Problem problem = loadProblem(repoFile(kSphere));
  ASSERT_EQ(problem.queries.size(), 1u);
  const Query& query = problem.queries[0];
  EXPECT_EQ(query.init, (std::vector<double>{0.25, 0.5}));
  ASSERT_TRUE(query.goal.isConfiguration());
  EXPECT_EQ(query.goal.controls, (std::vector<double>{0.75, 0.5}));
  EXPECT_EQ(query.goal.link, "sphere");
  EXPECT_DOUBLE_EQ(query.goal.jointTolerance, 0.05);
  EXPECT_EQ(query.goal.where.line, lineOf(readText(repoFile(kSphere)), "<Goal>"));
  EXPECT_TRUE(problem.goalPosition(query.goal).isApprox(Eigen::Vector3d(0.15, 0.0, 0.795)));
  EXPECT_FALSE(problem.goalApproach(query.goal).has_value());
}

TEST(ConfigurationGoal, AnArmsGoalLinkIsItsToolNotAHeldFinger) {
  const Problem problem = loadProblem(repoFile(kKukaTable));
  const GoalRegion& goal = problem.queries.at(0).goal;
  ASSERT_TRUE(goal.isConfiguration());
  EXPECT_EQ(goal.controls, (std::vector<double>{0.35, 0.75, 0.17}));
  // The reach set moves A1, A2 and A4; the deepest link they move is the tool frame, not a
  // finger (one joint deeper, but held).
  EXPECT_EQ(problem.robot.controls.names, (std::vector<std::string>{"A1", "A2", "A4"}));
  EXPECT_EQ(goal.link, "kuka_tcp");
}

TEST_F(KauthamVariant, RobotControlGivesTheSameQueryAsInitAndGoal) {
  const std::string original = readText(repoFile(kSphere));
  const Problem expected = loadProblem(repoFile(kSphere));
  std::string text = replaceOnce(original, "<Init>0.25 0.5</Init>", "");
  text = replaceOnce(
      text, "<Goal>0.75 0.5</Goal>",
      R"(<RobotControl name="sphere" init="0.25 0.5" goal="0.75 0.5" tolerance="0.02"/>)");
  const Problem problem = load(text);
  const Query& query = problem.queries.at(0);
  const Query& reference = expected.queries.at(0);
  EXPECT_EQ(query.init, reference.init);
  EXPECT_EQ(query.goal.controls, reference.goal.controls);
  EXPECT_EQ(query.goal.link, reference.goal.link);
  EXPECT_EQ(problem.initialJointValues(query), expected.initialJointValues(reference));
  EXPECT_TRUE(problem.goalPosition(query.goal).isApprox(expected.goalPosition(reference.goal)));
  EXPECT_DOUBLE_EQ(query.goal.jointTolerance, 0.02);
  EXPECT_EQ(query.goal.where.line, lineOf(text, "<RobotControl "));
}

TEST_F(KauthamVariant, RobotControlWithoutGoalTakesAGoalRegion) {
  const std::string text =
      replaceOnce(readText(repoFile(kKuka)), "<Init>0.5 0.6667 0.5 0.125 0.5 0.7083 0.5</Init>",
                  R"(<RobotControl name="kuka" init="0.5 0.6667 0.5 0.125 0.5 0.7083 0.5"/>)");
  const Problem problem = load(text);
  const Problem reference = loadProblem(repoFile(kKuka));
  EXPECT_EQ(problem.queries.at(0).init, reference.queries.at(0).init);
  EXPECT_FALSE(problem.queries.at(0).goal.isConfiguration());
  EXPECT_EQ(problem.queries.at(0).goal.link, "kuka_tcp");
}

TEST_F(KauthamVariant, InitAndGoalAcceptAMatchingDim) {
  const std::string text =
      replaceOnce(replaceOnce(readText(repoFile(kSphere)), "<Init>", "<Init dim=\"2\">"), "<Goal>",
                  "<Goal dim=\"2\">");
  EXPECT_EQ(load(text).queries.at(0).goal.controls, (std::vector<double>{0.75, 0.5}));
}

// ----- files without roles, target or workspace -----

TEST(NoRoles, ObjectsWithMassAreMovableAndWithoutAreFixed) {
  const Problem problem = loadProblem(repoFile(kSphere));
  const std::vector<std::pair<std::string, ObjectRole>> expected = {
      {"table", ObjectRole::Fixed},
      {"right_wall", ObjectRole::Fixed},
      {"left_wall", ObjectRole::Fixed},
      {"cube1", ObjectRole::Movable},
      {"cube2", ObjectRole::Movable}};
  ASSERT_EQ(problem.objects.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(problem.objects[i].name, expected[i].first);
    EXPECT_EQ(problem.objects[i].role, expected[i].second) << expected[i].first;
  }
  EXPECT_FALSE(problem.hasTarget());
  EXPECT_FALSE(problem.supportObject().has_value());
}

TEST(NoRoles, KukaTableHasMovableCansAndGlassAndAFixedTable) {
  const Problem problem = loadProblem(repoFile(kKukaTable));
  EXPECT_FALSE(problem.hasTarget());
  int movable = 0;
  for (const ObjectInstance& object : problem.objects) {
    const bool isTable = object.urdf.filename() == "table.urdf";
    EXPECT_EQ(object.role, isTable ? ObjectRole::Fixed : ObjectRole::Movable) << object.name;
    movable += isTable ? 0 : 1;
  }
  EXPECT_GE(movable, 3);
  ASSERT_TRUE(problem.findObject("glass").has_value());
}

TEST(NoRoles, DefaultWorkspaceContainsTheSceneWithRoomAround) {
  for (const char* file : {kSphere, kKukaTable}) {
    SCOPED_TRACE(file);
    const Problem problem = loadProblem(repoFile(file));
    const Eigen::AlignedBox3d& workspace = problem.workspace;
    ASSERT_FALSE(workspace.isEmpty());
    for (const ObjectInstance& object : problem.objects) {
      const Eigen::AlignedBox3d bounds = boundsAtHome(object);
      EXPECT_TRUE(workspace.contains(bounds)) << object.name;
      // 25 cm of room on every side of each object.
      EXPECT_TRUE(workspace.contains(bounds.min() - Eigen::Vector3d::Constant(0.24)))
          << object.name;
      EXPECT_TRUE(workspace.contains(bounds.max() + Eigen::Vector3d::Constant(0.24)))
          << object.name;
    }
    EXPECT_TRUE(workspace.contains(boundsAtHome(problem.robot)));
    const GoalRegion& goal = problem.queries.at(0).goal;
    EXPECT_TRUE(workspace.contains(problem.goalPosition(goal)));
  }
}

TEST_F(KauthamVariant, AWorkspaceElementStillWins) {
  const std::string text =
      replaceOnce(readText(repoFile(kSphere)), "  <Planner>",
                  "  <Workspace min=\"-0.4 -0.2 0.7\" max=\"0.4 0.2 0.9\"/>\n  <Planner>");
  const Problem problem = load(text);
  EXPECT_TRUE(problem.workspace.min().isApprox(Eigen::Vector3d(-0.4, -0.2, 0.7)));
  EXPECT_TRUE(problem.workspace.max().isApprox(Eigen::Vector3d(0.4, 0.2, 0.9)));
}

TEST_F(KauthamVariant, OneRoleAttributeMeansTheFileMustNameATarget) {
  const std::string text =
      replaceOnce(readText(repoFile(kSphere)),
                  "<Obstacle obstacle=\"objects/cube.urdf\" scale=\"1\">\n"
                  "    <Home X=\"0.0\" Y=\"-0.03\"",
                  "<Obstacle obstacle=\"objects/cube.urdf\" role=\"movable\">\n"
                  "    <Home X=\"0.0\" Y=\"-0.03\"");
  try {
    load(text);
    FAIL() << "loaded";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("needs exactly one <Obstacle role=\"target\">"),
              std::string::npos)
        << error.what();
  }
}

// ----- Kautham's planner parameter names -----

TEST_F(KauthamVariant, KauthamParameterNamesAreAcceptedOrIgnored) {
  const std::string parameters =
      "      <Parameter name=\"Max Planning Time\">12</Parameter>\n"
      "      <Parameter name=\"_Speed Factor\">3</Parameter>\n"
      "      <Parameter name=\"Speed Factor\">3</Parameter>\n"
      "      <Parameter name=\"_Incremental (0/1)\">0</Parameter>\n"
      "      <Parameter name=\"Control Dimensions\">2</Parameter>\n"
      "      <Parameter name=\"Max Speed\">1</Parameter>\n"
      "      <Parameter name=\"PropagationStepSize\">0.03</Parameter>\n"
      "      <Parameter name=\"Min Control Steps\">3</Parameter>\n"
      "      <Parameter name=\"Max Control Steps\">17</Parameter>\n"
      "      <Parameter name=\"Goal Bias\">0.2</Parameter>\n"
      "      <Parameter name=\"Max Contacts\">5</Parameter>\n"
      "      <Parameter name=\"Error Reduction Parameter\">0.3</Parameter>\n"
      "      <Parameter name=\"Constraint Force Mixing\">0.001</Parameter>\n";
  std::string text = readText(repoFile(kSphere));
  const auto begin = text.find("      <Parameter ");
  const auto end = text.find("    </Parameters>");
  ASSERT_NE(begin, std::string::npos);
  text = text.substr(0, begin) + parameters + text.substr(end);
  const Problem problem = load(text);
  EXPECT_EQ(problem.physics.maxContacts, 5);
  // Kautham's ERP 0.3 and CFM 0.001 at its 0.03 s steps (PropagationStepSize) are a spring of
  // 0.3 / (0.03 * 0.001) = 10000 N/m and a damper of 0.7 / 0.001 = 700 N s/m; at 0.01 s steps
  // the same contact is ERP 100 / 800, CFM 1 / 800.
  EXPECT_NEAR(problem.physics.erp, 0.125, 1e-12);
  EXPECT_NEAR(problem.physics.cfm, 0.00125, 1e-12);
  const planners::PlanRequest request = planners::makeRequest(problem, std::nullopt, {}, 1);
  EXPECT_EQ(request.planner, "KPIECE");
  EXPECT_DOUBLE_EQ(request.timeLimit(), 12.0);
  EXPECT_DOUBLE_EQ(request.common.real("propagation_step_size"), 0.03);
  EXPECT_EQ(request.common.integer("min_control_steps"), 3);
  EXPECT_EQ(request.common.integer("max_control_steps"), 17);
  EXPECT_DOUBLE_EQ(request.parameters.real("goal_bias"), 0.2);

  // "_Max Planning Time" is the same parameter.
  const Problem underscored =
      load(replaceOnce(text, "name=\"Max Planning Time\">12", "name=\"_Max Planning Time\">7"));
  EXPECT_DOUBLE_EQ(planners::makeRequest(underscored, std::nullopt, {}, 1).timeLimit(), 7.0);
}

TEST_F(KauthamVariant, AMisspelledKauthamParameterIsRejectedOnItsLine) {
  const std::string text =
      replaceOnce(readText(repoFile(kSphere)), "name=\"Goal Bias\"", "name=\"Goal Bais\"");
  const Problem problem = load(text);
  try {
    planners::makeRequest(problem, std::nullopt, {}, 1);
    FAIL() << "accepted";
  } catch (const InputError& error) {
    EXPECT_EQ(error.where().line, lineOf(text, "Goal Bais"));
    EXPECT_NE(std::string(error.what()).find("unknown parameter 'Goal Bais'"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace kautham::core
