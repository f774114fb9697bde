// Tests of the problem loader on the shipped problems, on variants of them written to a
// temporary folder, and on the malformed files of tests/data/malformed/.

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

#include "TestPaths.h"
#include "kautham/core/InputError.h"
#include "kautham/core/ProblemLoader.h"

namespace kautham::core {
namespace {

namespace fs = std::filesystem;
using test::repoFile;

// ----- helpers -----

std::string readText(const fs::path& file) {
  std::ifstream in(file);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Replaces the only occurrence of `from` in `text`; fails the test if it is not there once.
std::string replaceOnce(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "'" << from << "' is not in the text";
  if (at == std::string::npos) return text;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << "'" << from << "' is there twice";
  return text.replace(at, from.size(), to);
}

/// Replaces the whole element that starts with `start` (e.g. "<Physics ") up to its "/>".
std::string replaceElement(const std::string& text, const std::string& start,
                           const std::string& element) {
  const auto begin = text.find(start);
  EXPECT_NE(begin, std::string::npos) << start;
  if (begin == std::string::npos) return text;
  const auto end = text.find("/>", begin) + 2;
  return text.substr(0, begin) + element + text.substr(end);
}

/// 1-based line of the first occurrence of `needle`, 0 if it is not there.
int lineOf(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  if (at == std::string::npos) return 0;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
}

std::string textOfCans5() { return readText(repoFile("problems/pusher_cans_5.xml")); }

/// Writes problem variants to a temporary folder of its own; models come from models/.
class ProblemVariant : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    folder_ = fs::temp_directory_path() / ("kautham_core_tests_" + std::string(info->name()) + "_" +
                                           std::to_string(::getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(folder_, ignored);
  }

  fs::path write(const std::string& text, const std::string& name = "variant.xml") const {
    const fs::path file = folder_ / name;
    std::ofstream(file) << text;
    return file;
  }
  Problem load(const std::string& text) const {
    return loadProblem(write(text), {repoFile("models")});
  }

  fs::path folder_;
};

// ----- every shipped problem loads -----

std::vector<fs::path> shippedProblems() {
  std::vector<fs::path> files;
  std::error_code ignored;
  for (fs::recursive_directory_iterator it(repoFile("problems"), ignored), end; it != end; ++it)
    if (it->is_regular_file() && it->path().extension() == ".xml") files.push_back(it->path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(ShippedProblems, TheGlobFindsTheDefaultProblem) {
  const std::vector<fs::path> files = shippedProblems();
  ASSERT_FALSE(files.empty()) << "no *.xml under " << repoFile("problems");
  EXPECT_NE(std::find(files.begin(), files.end(), repoFile("problems/pusher_cans_5.xml")),
            files.end());
}

class ShippedProblem : public ::testing::TestWithParam<fs::path> {};

/// The folder of outside test data (../shared, beside the project) a shipped problem names,
/// if it names one: such a problem loads only where that data lies.
std::optional<fs::path> outsideDataOf(const fs::path& file) {
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string marker = "../shared/";
  const std::size_t at = text.find(marker);
  if (at == std::string::npos) return std::nullopt;
  const std::size_t end = text.find('/', at + marker.size());
  return repoFile(text.substr(at, end - at));
}

TEST_P(ShippedProblem, Loads) {
  const fs::path& file = GetParam();
  if (const auto outside = outsideDataOf(file); outside && !fs::is_directory(*outside))
    GTEST_SKIP() << file << " uses test data outside the project, not at " << *outside;
  try {
    // No model folders given: problems/ finds its models by the ../models rule.
    const Problem problem = loadProblem(file);
    EXPECT_EQ(problem.file, file);
    EXPECT_FALSE(problem.name.empty());
    EXPECT_FALSE(problem.robot.model.movableJoints().empty());
    // Kautham's own files (problems/kautham/) give no roles, so they have no target.
    const bool kauthamForm = file.parent_path().filename() == "kautham";
    EXPECT_EQ(problem.hasTarget(), !kauthamForm);
    EXPECT_FALSE(problem.planner.name.empty());
    ASSERT_FALSE(problem.queries.empty());
    for (const Query& query : problem.queries)
      EXPECT_TRUE(problem.workspace.contains(problem.goalPosition(query.goal))) << query.name;
  } catch (const InputError& error) {
    FAIL() << error.what();
  }
}

std::string testNameOf(const ::testing::TestParamInfo<fs::path>& info) {
  std::string name = fs::relative(info.param, repoFile("problems")).replace_extension().string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Problems, ShippedProblem, ::testing::ValuesIn(shippedProblems()),
                         testNameOf);

// ----- the content of pusher_cans_5.xml -----

class PusherCans5 : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    problem_ = new Problem(loadProblem(repoFile("problems/pusher_cans_5.xml")));
  }
  static void TearDownTestSuite() {
    delete problem_;
    problem_ = nullptr;
  }
  const Problem& problem() const { return *problem_; }

 private:
  static Problem* problem_;
};
Problem* PusherCans5::problem_ = nullptr;

TEST_F(PusherCans5, NameAndFile) {
  EXPECT_EQ(problem().name, "pusher_cans_5");
  EXPECT_EQ(problem().file, repoFile("problems/pusher_cans_5.xml"));
}

TEST_F(PusherCans5, Robot) {
  const RobotInstance& robot = problem().robot;
  EXPECT_EQ(robot.name, "pusher");
  EXPECT_EQ(robot.model.name, "planar_pusher");
  EXPECT_EQ(robot.urdf.filename(), "planar_pusher.urdf");
  EXPECT_TRUE(fs::is_regular_file(robot.urdf));
  const std::vector<int> movable = robot.model.movableJoints();
  ASSERT_EQ(movable.size(), 3u);
  EXPECT_EQ(robot.model.joints[movable[0]].name, "x");
  EXPECT_EQ(robot.model.joints[movable[1]].name, "y");
  EXPECT_EQ(robot.model.joints[movable[2]].name, "yaw");
  EXPECT_TRUE(robot.model.findLink("gripper").has_value());
  EXPECT_TRUE(robot.home.position.isApprox(Eigen::Vector3d(0.0, -0.3, 0.775)));
  EXPECT_TRUE(robot.home.orientation.isApprox(Eigen::Quaterniond::Identity()));
  EXPECT_EQ(robot.where.line, lineOf(textOfCans5(), "<Robot "));
  EXPECT_EQ(robot.initialJoints.size(), 3u);
}

TEST_F(PusherCans5, ObjectsAndRoles) {
  const std::vector<std::pair<std::string, ObjectRole>> expected = {
      {"table", ObjectRole::Fixed},  {"glass", ObjectRole::Target}, {"can1", ObjectRole::Movable},
      {"can2", ObjectRole::Movable}, {"can3", ObjectRole::Movable}, {"can4", ObjectRole::Movable},
      {"can5", ObjectRole::Movable}};
  ASSERT_EQ(problem().objects.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    SCOPED_TRACE(expected[i].first);
    EXPECT_EQ(problem().objects[i].name, expected[i].first);
    EXPECT_EQ(problem().objects[i].role, expected[i].second);
    EXPECT_EQ(problem().findObject(expected[i].first), static_cast<int>(i));
  }
  EXPECT_EQ(problem().objects[2].urdf.filename(), "can.urdf");
  EXPECT_TRUE(problem().objects[4].home.position.isApprox(Eigen::Vector3d(0.08, 0.09, 0.811)));
  EXPECT_FALSE(problem().findObject("can6").has_value());
}

TEST_F(PusherCans5, ExactlyOneTargetNamedGlass) {
  const auto targets = std::count_if(problem().objects.begin(), problem().objects.end(),
                                     [](const auto& o) { return o.role == ObjectRole::Target; });
  EXPECT_EQ(targets, 1);
  EXPECT_EQ(problem().target().name, "glass");
  EXPECT_TRUE(problem().target().home.position.isApprox(Eigen::Vector3d(0.0, 0.22, 0.825)));
}

TEST_F(PusherCans5, Physics) {
  const PhysicsSettings& physics = problem().physics;
  EXPECT_DOUBLE_EQ(physics.stepSize, 0.01);
  EXPECT_TRUE(physics.gravity.isApprox(Eigen::Vector3d(0, 0, -9.81)));
  EXPECT_EQ(physics.maxContacts, 8);
  EXPECT_EQ(physics.solverIterations, 20);
  EXPECT_DOUBLE_EQ(physics.overRelaxation, 1.3);
  EXPECT_DOUBLE_EQ(physics.friction, 0.5);
  EXPECT_DOUBLE_EQ(physics.erp, 0.2);
  EXPECT_DOUBLE_EQ(physics.cfm, 1e-5);
  EXPECT_EQ(physics.where.line, lineOf(textOfCans5(), "<Physics "));
}

TEST_F(PusherCans5, Interaction) {
  const InteractionConstraints& interaction = problem().interaction;
  EXPECT_EQ(interaction.supportObject, "table");
  EXPECT_DOUBLE_EQ(interaction.maxObjectSpeed, 1.0);
  EXPECT_DOUBLE_EQ(interaction.maxDisplacement, 0.3);
  EXPECT_DOUBLE_EQ(interaction.maxTilt, 0.35);
  EXPECT_DOUBLE_EQ(interaction.targetTolerance, 0.005);
  EXPECT_EQ(problem().supportObject(), problem().findObject("table"));
}

TEST_F(PusherCans5, Workspace) {
  EXPECT_TRUE(problem().workspace.min().isApprox(Eigen::Vector3d(-0.45, -0.36, 0.76)));
  EXPECT_TRUE(problem().workspace.max().isApprox(Eigen::Vector3d(0.45, 0.36, 0.79)));
}

TEST_F(PusherCans5, PlannerAndItsParameters) {
  const PlannerSpec& planner = problem().planner;
  EXPECT_EQ(planner.name, "KPIECE");
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"_Max Planning Time", "60"},
      {"PropagationStepSize", "0.05"},
      {"Min Control Steps", "2"},
      {"Max Control Steps", "20"},
      {"Goal Bias", "0.05"}};
  ASSERT_EQ(planner.parameters.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(planner.parameters[i].name, expected[i].first);
    EXPECT_EQ(planner.parameters[i].value, expected[i].second);
    EXPECT_EQ(planner.parameters[i].where.line,
              lineOf(textOfCans5(), "<Parameter name=\"" + expected[i].first + "\">"));
  }
}

TEST_F(PusherCans5, OneQueryWithInitAndGoalRegion) {
  ASSERT_EQ(problem().queries.size(), 1u);
  const Query& query = problem().queries[0];
  EXPECT_EQ(query.name, "pregrasp");
  EXPECT_EQ(query.init, (std::vector<double>{0.5, 0.125, 0.5}));
  EXPECT_EQ(query.goal.link, "gripper");
  EXPECT_EQ(query.goal.relativeTo, "glass");
  EXPECT_TRUE(query.goal.offset.isApprox(Eigen::Vector3d(0, -0.09, -0.05)));
  EXPECT_DOUBLE_EQ(query.goal.tolerance, 0.03);
  EXPECT_EQ(query.goal.where.line, lineOf(textOfCans5(), "<GoalRegion "));
  // The goal is the glass's home plus the offset, and lies in the workspace.
  const Eigen::Vector3d goal = problem().goalPosition(query.goal);
  EXPECT_TRUE(goal.isApprox(Eigen::Vector3d(0.0, 0.13, 0.775))) << goal.transpose();
  EXPECT_TRUE(problem().workspace.contains(goal));
  // Init maps [0,1] onto each joint's limits: x in [-0.5,0.5], y in [0,0.7], yaw in [-1.57,1.57].
  const std::vector<double> joints = problem().initialJointValues(query);
  ASSERT_EQ(joints.size(), 3u);
  EXPECT_NEAR(joints[0], 0.0, 1e-12);
  EXPECT_NEAR(joints[1], 0.0, 1e-12);
  EXPECT_NEAR(joints[2], 0.0, 1e-12);
}

// ----- variants of pusher_cans_5 -----

TEST_F(ProblemVariant, KauthamPhysicsParameterNamesSetThePhysicsBlock) {
  const std::string text = replaceOnce(textOfCans5(), "      <Parameter name=\"Goal Bias\">",
                                       "      <Parameter name=\"Max Contacts\">12</Parameter>\n"
                                       "      <Parameter name=\"Error Reduction Parameter\">0.4"
                                       "</Parameter>\n"
                                       "      <Parameter name=\"Constraint Force Mixing\">1e-4"
                                       "</Parameter>\n"
                                       "      <Parameter name=\"Goal Bias\">");
  const Problem problem = load(text);
  EXPECT_EQ(problem.physics.maxContacts, 12);
  // Kautham's values are for its steps of PropagationStepSize (0.05 s): the same spring
  // (0.4 / (0.05 * 1e-4) = 80000 N/m) and damper (0.6 / 1e-4 = 6000 N s/m) at <Physics
  // stepSize> 0.01 s are ERP 800 / 6800 and CFM 1 / 6800.
  EXPECT_NEAR(problem.physics.erp, 800.0 / 6800.0, 1e-12);
  EXPECT_NEAR(problem.physics.cfm, 1.0 / 6800.0, 1e-12);
  // They are physics, not planner parameters.
  EXPECT_EQ(problem.planner.parameters.size(), 5u);
  for (const PlannerParameter& p : problem.planner.parameters) {
    EXPECT_NE(p.name, "Max Contacts");
    EXPECT_NE(p.name, "Error Reduction Parameter");
    EXPECT_NE(p.name, "Constraint Force Mixing");
  }
}

TEST_F(ProblemVariant, KauthamPhysicsParametersAreCheckedLikeThePhysicsBlock) {
  const std::string anchor = "      <Parameter name=\"Goal Bias\">";
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"Max Contacts", "2.5"},
      {"Max Contacts", "4 5"},
      {"Error Reduction Parameter", "1.5"},
      {"Constraint Force Mixing", "-1"},
      {"Constraint Force Mixing", "abc"}};
  for (const auto& [name, value] : bad) {
    SCOPED_TRACE(name + " = " + value);
    const std::string text =
        replaceOnce(textOfCans5(), anchor,
                    "<Parameter name=\"" + name + "\">" + value + "</Parameter>" + anchor);
    try {
      load(text);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& error) {
      EXPECT_EQ(error.where().line, lineOf(text, "\"" + name + "\""));
      EXPECT_NE(std::string(error.what()).find(value), std::string::npos) << error.what();
    }
  }
}

TEST_F(ProblemVariant, ElementOrderDoesNotMatter) {
  // Kautham files may give the planner first; <Init> is still checked against the robot, and
  // Kautham's "Max Contacts" wins over a <Physics> block that comes after it.
  std::string text = textOfCans5();
  const auto begin = text.find("  <Planner>");
  const auto end = text.find("</Problem>");
  ASSERT_NE(begin, std::string::npos);
  const std::string planner =
      replaceOnce(text.substr(begin, end - begin), "      <Parameter name=\"Goal Bias\">",
                  "      <Parameter name=\"Max Contacts\">12</Parameter>\n"
                  "      <Parameter name=\"Goal Bias\">");
  text = replaceOnce(text.substr(0, begin) + text.substr(end), "  <Robot ", planner + "  <Robot ");
  ASSERT_LT(text.find("<Planner>"), text.find("<Robot "));
  ASSERT_LT(text.find("<Planner>"), text.find("<Physics "));
  const Problem problem = load(text);
  ASSERT_EQ(problem.queries.size(), 1u);
  EXPECT_EQ(problem.queries[0].init, (std::vector<double>{0.5, 0.125, 0.5}));
  EXPECT_EQ(problem.physics.maxContacts, 12);
  EXPECT_EQ(problem.planner.name, "KPIECE");
}

TEST_F(ProblemVariant, ValuesOtherThanTheDefaultsAreRead) {
  std::string text = textOfCans5();
  text = replaceElement(text, "<Physics ",
                        R"(<Physics stepSize="0.005" gravity="0 0 -1.62" maxContacts="6" )"
                        R"(solverIterations="50" overRelaxation="1.6" friction="0.9" erp="0.5" )"
                        R"(cfm="1e-3"/>)");
  text = replaceElement(text, "<Interaction ",
                        R"(<Interaction support="table" maxObjectSpeed="0.5" )"
                        R"(maxDisplacement="0.1" maxTilt="0.2" targetTolerance="0.01"/>)");
  text = replaceOnce(text, R"(<KauthamName name="can1"/>)",
                     R"(<KauthamName name="can1"/><Uncertainty x="0.01" y="0.02" yaw="0.1"/>)");
  text = replaceOnce(text, R"(tolerance="0.03")", R"(tolerance="0.05")");
  const Problem problem = load(text);
  EXPECT_DOUBLE_EQ(problem.physics.stepSize, 0.005);
  EXPECT_TRUE(problem.physics.gravity.isApprox(Eigen::Vector3d(0, 0, -1.62)));
  EXPECT_EQ(problem.physics.maxContacts, 6);
  EXPECT_EQ(problem.physics.solverIterations, 50);
  EXPECT_DOUBLE_EQ(problem.physics.overRelaxation, 1.6);
  EXPECT_DOUBLE_EQ(problem.physics.friction, 0.9);
  EXPECT_DOUBLE_EQ(problem.physics.erp, 0.5);
  EXPECT_DOUBLE_EQ(problem.physics.cfm, 1e-3);
  EXPECT_DOUBLE_EQ(problem.interaction.maxObjectSpeed, 0.5);
  EXPECT_DOUBLE_EQ(problem.interaction.maxDisplacement, 0.1);
  EXPECT_DOUBLE_EQ(problem.interaction.maxTilt, 0.2);
  EXPECT_DOUBLE_EQ(problem.interaction.targetTolerance, 0.01);
  const ObjectInstance& can1 = problem.objects.at(*problem.findObject("can1"));
  EXPECT_DOUBLE_EQ(can1.uncertainty.x, 0.01);
  EXPECT_DOUBLE_EQ(can1.uncertainty.y, 0.02);
  EXPECT_DOUBLE_EQ(can1.uncertainty.yaw, 0.1);
  EXPECT_DOUBLE_EQ(problem.objects.at(*problem.findObject("can2")).uncertainty.x, 0.0);
  EXPECT_DOUBLE_EQ(problem.queries.at(0).goal.tolerance, 0.05);
}

TEST_F(ProblemVariant, WithoutUncertaintyEveryStandardDeviationIsZero) {
  const Problem problem = load(textOfCans5());
  EXPECT_DOUBLE_EQ(problem.uncertainty.friction, 0.0);
  EXPECT_DOUBLE_EQ(problem.uncertainty.erp, 0.0);
  EXPECT_DOUBLE_EQ(problem.uncertainty.cfm, 0.0);
  EXPECT_DOUBLE_EQ(problem.uncertainty.control, 0.0);
  EXPECT_TRUE(problem.defaultPoseUncertainty.isZero());
  for (const ObjectInstance& object : problem.objects)
    EXPECT_TRUE(object.uncertainty.isZero()) << object.name;
}

TEST_F(ProblemVariant, TopLevelUncertaintyIsTheDefaultAndObjectsOverrideIt) {
  std::string text = textOfCans5();
  // After the obstacles, so the default must reach objects read before it.
  text = replaceOnce(text, "  <Physics ",
                     R"(  <Uncertainty x="0.01" y="0.02" yaw="0.1" friction="0.05" erp="0.02" )"
                     R"(cfm="1e-6" control="0.03"/>)"
                     "\n  <Physics ");
  text = replaceOnce(text, R"(<KauthamName name="can1"/>)",
                     R"(<KauthamName name="can1"/><Uncertainty x="0.005" yaw="0"/>)");
  const Problem problem = load(text);
  EXPECT_DOUBLE_EQ(problem.uncertainty.friction, 0.05);
  EXPECT_DOUBLE_EQ(problem.uncertainty.erp, 0.02);
  EXPECT_DOUBLE_EQ(problem.uncertainty.cfm, 1e-6);
  EXPECT_DOUBLE_EQ(problem.uncertainty.control, 0.03);
  EXPECT_EQ(problem.uncertainty.where.line, lineOf(text, "<Uncertainty x=\"0.01\""));
  EXPECT_DOUBLE_EQ(problem.defaultPoseUncertainty.y, 0.02);
  auto object = [&](const char* name) { return problem.objects.at(*problem.findObject(name)); };
  // can1's own attributes win one by one; y comes from the default.
  EXPECT_DOUBLE_EQ(object("can1").uncertainty.x, 0.005);
  EXPECT_DOUBLE_EQ(object("can1").uncertainty.y, 0.02);
  EXPECT_DOUBLE_EQ(object("can1").uncertainty.yaw, 0.0);
  for (const char* name : {"can2", "can5", "glass"}) {  // movable objects and the target
    EXPECT_DOUBLE_EQ(object(name).uncertainty.x, 0.01) << name;
    EXPECT_DOUBLE_EQ(object(name).uncertainty.y, 0.02) << name;
    EXPECT_DOUBLE_EQ(object(name).uncertainty.yaw, 0.1) << name;
  }
  EXPECT_TRUE(object("table").uncertainty.isZero());  // fixed: never uncertain
}

TEST_F(ProblemVariant, ObstacleWithoutRoleIsFixed) {
  const Problem problem =
      load(replaceOnce(textOfCans5(), R"(obstacle="objects/table.urdf" role="fixed")",
                       R"(obstacle="objects/table.urdf")"));
  EXPECT_EQ(problem.objects.at(*problem.findObject("table")).role, ObjectRole::Fixed);
}

TEST_F(ProblemVariant, ModelsAreSearchedInTheGivenFoldersOnlyWhenGiven) {
  const fs::path file = write(textOfCans5());
  // The temporary folder has no models/ beside it: without a model folder, nothing is found.
  try {
    loadProblem(file);
    FAIL() << "loaded without a model folder";
  } catch (const InputError& error) {
    EXPECT_EQ(error.where().line, lineOf(textOfCans5(), "<Robot "));
    EXPECT_NE(std::string(error.what()).find("robots/planar_pusher.urdf' not found"),
              std::string::npos)
        << error.what();
    EXPECT_NE(std::string(error.what()).find((folder_ / "robots/planar_pusher.urdf").string()),
              std::string::npos)
        << error.what();
  }
  EXPECT_EQ(loadProblem(file, {repoFile("models")}).objects.size(), 7u);
}

TEST_F(ProblemVariant, AFolderSearchedTwiceIsListedOnce) {
  // The problem's own folder given again (and once more spelt with "x/.."): a problem one level
  // under the root meets the same, where its layouts' models/ folders are one.
  const fs::path file = write(textOfCans5());
  try {
    loadProblem(file, {folder_, folder_ / "x" / ".."});
    FAIL() << "loaded without a model folder";
  } catch (const InputError& error) {
    const std::string message = error.what();
    const std::string searched = (folder_ / "robots/planar_pusher.urdf").string();
    const std::size_t first = message.find(searched);
    ASSERT_NE(first, std::string::npos) << message;
    EXPECT_EQ(message.find(searched, first + searched.size()), std::string::npos) << message;
  }
}

TEST(ProblemLoader, MissingProblemFileIsAnInputErrorNamingIt) {
  const fs::path file = repoFile("tests/data/malformed/there_is_no_such_problem.xml");
  ASSERT_FALSE(fs::exists(file));
  try {
    loadProblem(file);
    FAIL() << "loaded a file that does not exist";
  } catch (const InputError& error) {
    EXPECT_EQ(error.where().file, file);
    const std::string message = error.what();
    EXPECT_EQ(message.rfind(file.string() + ":", 0), 0u) << message;
    EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
  }
}

// ----- malformed files: each rejected with the file, the line and a helpful phrase -----

struct MalformedCase {
  const char* name;       ///< tests/data/malformed/<name>.xml
  const char* errorFile;  ///< file the error names, when not the problem file (a URDF)
  int line;
  const char* phrase;
};

std::ostream& operator<<(std::ostream& out, const MalformedCase& c) { return out << c.name; }

const MalformedCase kMalformedCases[] = {
    {"xml_unclosed_tag", nullptr, 4,
     "malformed XML: <Robot> is not closed: the next end tag belongs to another element; add "
     "</Robot> where it ends (or write <Robot .../> if it holds nothing)"},
    {"xml_unquoted_attribute", nullptr, 5,
     "malformed XML: a broken attribute in <Home>: write each attribute once, as name=\"value\" "
     "with the quotes"},
    {"xml_content_after_root", nullptr, 32,
     "the file goes on after </Problem> with '<Problem name=\"second\"/>': a file holds one "
     "<Problem>; remove what follows, or move it inside"},
    {"empty_file", nullptr, 1, "the file is empty"},
    {"binary_file", nullptr, 1,
     "not a text file (it holds a NUL byte, at byte 0): expected an XML document"},
    {"wrong_root", nullptr, 3, "expected the root element <Problem>, found <Scene>"},
    {"unknown_element", nullptr, 11, "unexpected element <Obstacles>"},
    {"parameters_unknown_element", nullptr, 21, "unexpected <Paramter> inside <Parameters>"},
    {"query_unknown_element", nullptr, 24, "unexpected <Inti> inside <Query>"},
    {"unknown_attribute", nullptr, 16, "no attribute 'maxDisplacment'; allowed:"},
    {"home_nan", nullptr, 13, "expected a finite number, got 'nan'"},
    {"home_far_target", nullptr, 13,
     "<Home X=\"1e308\"> is beyond +-1000 m: positions are in metres, in the world frame; place "
     "the <Obstacle> in the scene"},
    {"home_far_robot", nullptr, 5, "<Home Y=\"-1e300\"> is beyond +-1000 m"},
    {"home_beyond_double", nullptr, 9,
     "attribute Z: 1e400 is out of range: beyond the largest number a double holds"},
    {"target_outside_workspace", nullptr, 13,
     "object 'glass' stands at (5, 0.22, 0.825), 4.45 m from the <Workspace> (-0.55 -0.4 0.76 to "
     "0.55 0.38 0.79), farther than the goal's offset (0.103 m) reaches, so the goal relative "
     "to it lies outside the workspace; move the object's <Home> where the robot can reach it, "
     "or widen the <Workspace>"},
    {"home_twice", nullptr, 14, "<Home> appears twice inside <Obstacle> (first on line 13)"},
    {"physics_not_a_number", nullptr, 15, "friction: expected a number, got 'high'"},
    {"physics_out_of_range", nullptr, 15, "maxContacts must be in [1, 64]"},
    {"physics_over_relaxation_out_of_range", nullptr, 15,
     "overRelaxation must be above 0 and below 2"},
    {"physics_sleep_not_a_flag", nullptr, 15,
     "attribute sleep must be true or false, got 'sometimes'"},
    {"kautham_max_contacts_out_of_range", nullptr, 21,
     "'Max Contacts' must be one number in [1, 64]"},
    {"unknown_role", nullptr, 11, "unknown role 'goal'; expected fixed, movable or target"},
    {"missing_model", nullptr, 7, "model file 'objects/no_such_table.urdf' not found"},
    {"model_is_a_folder", nullptr, 4, "model file 'robots' is a folder ('"},
    {"urdf_malformed_xml", "broken.urdf", 5, "malformed XML: <collision> is not closed"},
    {"urdf_stray_end_tag", "stray_end_tag.urdf", 11,
     "the file goes on after </robot> with '</robot>': a file holds one <robot>"},
    {"urdf_joint_loop", "joint_loop.urdf", 43,
     "joint 'y': the links carriage_x -> carriage_y -> gripper -> carriage_x form a loop, not "
     "connected to the root link 'base'"},
    {"urdf_absurd_limits", "absurd_limits.urdf", 52,
     "joint 'yaw': <limit lower=\"-1e+300\" upper=\"1e+300\"> is beyond +-1000 (rad or m); give "
     "the joint's real range, or make it type=\"continuous\""},
    {"urdf_negative_effort", "negative_effort.urdf", 46,
     "joint 'y' needs <limit velocity=\"..\" effort=\"..\"/> with positive finite values"},
    {"target_zero_mass", "zero_mass_glass.urdf", 6,
     "link 'glass' has a zero <mass>, so the target object 'glass' has no mass: give the link its "
     "real, positive mass (kg)"},
    {"urdf_mesh", "mesh.urdf", 6, "link 'top': mesh 'table.stl': file not found (looked for"},
    {"mesh_not_a_mesh", "mesh_not_a_mesh.urdf", 6,
     "mesh 'meshes/not_a_mesh.stl': not a readable mesh"},
    {"mesh_no_faces", "mesh_no_faces.urdf", 6,
     "mesh 'meshes/no_faces.obj': the mesh holds no triangles"},
    {"mesh_flat", "mesh_flat.urdf", 6,
     "mesh 'meshes/flat.obj' has no volume, so it cannot be a collision body: the points are flat"},
    {"mesh_package", "mesh_package.urdf", 6,
     "mesh 'package://kautham/meshes/table.stl': package 'kautham' not found (give "
     "--package-path kautham=DIR"},
    {"fixed_with_joint", nullptr, 11, "object 'cabinet' has movable joints"},
    {"goal_unknown_link", nullptr, 25,
     "the robot 'pusher' has no link 'hand'; its links are base, carriage_x, carriage_y, gripper"},
    {"goal_unknown_object", nullptr, 25,
     "relativeTo names no object: 'cup'; the objects are table, glass"},
    {"goal_unknown_link_of_many", nullptr, 47,
     "the robot 'kuka' has no link 'hand'; its links are kuka_base, kuka_link_1, kuka_link_2, "
     "kuka_link_3, kuka_link_4, kuka_link_5, kuka_link_6, kuka_link_7, kuka_flange, kuka_palm "
     "and 3 more"},
    {"goal_outside_workspace", nullptr, 25, "lies outside the <Workspace>"},
    {"duplicate_names", nullptr, 19, "the name 'can' is used twice"},
    {"no_target", nullptr, 3, "needs exactly one <Obstacle role=\"target\">, found none"},
    {"two_targets", nullptr, 19, "a second target 'can2'"},
    {"init_wrong_count", nullptr, 24, "<Init> needs 3 normalized values"},
    {"init_out_of_range", nullptr, 24, "each in [0, 1]"},
    {"no_robot", nullptr, 3, "the problem has no <Robot>"},
    {"support_not_fixed", nullptr, 20, "support 'can' must name a fixed <Obstacle>"},
    {"environment_missing_octree", nullptr, 11,
     "model file 'environments/no_such_scene.bt' not found"},
    {"environment_corrupt_octree", nullptr, 11, "corrupt.bt': corrupt or truncated data"},
    {"environment_not_an_octree", nullptr, 11,
     "not_an_octree.bt': not an OctoMap file: the first line should start with '# Octomap "
     "OcTree binary file'"},
    {"environment_empty_octree", nullptr, 11,
     "empty.bt': the octree is empty: it has no occupied voxel"},
    {"environment_bad_occupancy", nullptr, 11, "occupancy is a probability threshold"},
    {"uncertainty_negative", nullptr, 15, "attribute friction must not be negative"},
    {"uncertainty_unknown_attribute", nullptr, 15, "no attribute 'mu'; allowed:"},
    {"uncertainty_twice", nullptr, 16,
     "<Uncertainty> appears twice inside <Problem> (first on line 15)"},
    {"uncertainty_on_fixed", nullptr, 8,
     "object 'table' is fixed: it cannot be displaced, so it has no pose <Uncertainty>"},
    // Kautham compatibility: control sets, mobile bases, configuration goals.
    {"cntr_unknown_dof", "cntr_unknown_dof.cntr", 6,
     "DOF 'pusher/grippr' names no movable joint of 'planar_pusher'; expected the child link (or "
     "joint) name of one of: carriage_x carriage_y gripper"},
    {"cntr_offset_out_of_range", "cntr_offset_out_of_range.cntr", 5,
     "an offset is a normalized joint value: it must lie in [0, 1]"},
    {"cntr_control_moves_nothing", "cntr_control_moves_nothing.cntr", 5,
     "control 'nothing' moves no degree of freedom"},
    {"cntr_missing", nullptr, 7, "file 'controls/no_such_set.cntr' not found"},
    {"init_wrong_count_for_controls", nullptr, 25,
     "<Init> needs 2 normalized values (one per control), got 3"},
    {"init_dim_mismatch", nullptr, 24, "<Init> says dim=\"2\" but the robot has 3 controls"},
    {"limits_unknown_name", nullptr, 5,
     "unknown <Limits name=\"U\">; expected X, Y, Z (or WX, WY, WZ, TH, which are ignored)"},
    {"limits_min_not_less_than_max", nullptr, 6, "<Limits> needs min <= max"},
    {"goal_and_goal_region", nullptr, 26,
     "a query has one goal: a <Goal> configuration or a <GoalRegion>"},
    {"robot_control_other_robot", nullptr, 24,
     "<RobotControl name=\"kuka\"> names no robot; the robot is 'pusher'"},
    {"approach_tolerance_without_approach", nullptr, 25,
     "approachTolerance needs an approach=\"x y z\" direction"},
};

fs::path malformedFile(const std::string& name) { return repoFile("tests/data/malformed/" + name); }

class MalformedProblem : public ::testing::TestWithParam<MalformedCase> {};

TEST_P(MalformedProblem, IsRejectedWithFileLineAndPhrase) {
  const MalformedCase& c = GetParam();
  const fs::path problemFile = malformedFile(std::string(c.name) + ".xml");
  ASSERT_TRUE(fs::is_regular_file(problemFile)) << problemFile;
  // Model paths are found through the extra model folder; URDF errors name the URDF, as found.
  const fs::path errorFile =
      c.errorFile ? fs::weakly_canonical(malformedFile(c.errorFile)) : problemFile;
  try {
    loadProblem(problemFile, {repoFile("models")});
    FAIL() << problemFile << " loaded";
  } catch (const InputError& error) {
    const std::string message = error.what();
    const std::string prefix = errorFile.string() + ":" + std::to_string(c.line) + ":";
    EXPECT_EQ(message.rfind(prefix, 0), 0u)
        << "expected the prefix " << prefix << "\n got: " << message;
    EXPECT_NE(message.find(c.phrase), std::string::npos)
        << "expected the phrase \"" << c.phrase << "\"\n got: " << message;
    EXPECT_EQ(error.where().file, errorFile);
    EXPECT_EQ(error.where().line, c.line);
  } catch (const std::exception& error) {
    FAIL() << "not an InputError: " << error.what();
  }
}

std::string caseName(const ::testing::TestParamInfo<MalformedCase>& param) {
  return param.param.name;
}

INSTANTIATE_TEST_SUITE_P(Cases, MalformedProblem, ::testing::ValuesIn(kMalformedCases), caseName);

TEST(MalformedProblems, UrdfErrorsAlsoNameTheProblemLineThatLoadedTheModel) {
  try {
    loadProblem(malformedFile("urdf_mesh.xml"), {repoFile("models")});
    FAIL() << "loaded";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("mesh.urdf:6:"), std::string::npos) << message;
    EXPECT_NE(message.find("(model loaded at " + malformedFile("urdf_mesh.xml").string() + ":7)"),
              std::string::npos)
        << message;
  }
}

TEST(MalformedProblems, ControlSetErrorsAlsoNameTheProblemLineThatLoadedTheSet) {
  try {
    loadProblem(malformedFile("cntr_unknown_dof.xml"), {repoFile("models")});
    FAIL() << "loaded";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("(control set loaded at " +
                           malformedFile("cntr_unknown_dof.xml").string() + ":7)"),
              std::string::npos)
        << message;
  }
}

TEST(MalformedProblems, MalformedXmlIsSaidInPlainWordsNotInTinyxml2s) {
  for (const char* name : {"xml_unclosed_tag.xml", "xml_unquoted_attribute.xml"}) {
    try {
      loadProblem(malformedFile(name), {repoFile("models")});
      FAIL() << name << " loaded";
    } catch (const InputError& error) {
      const std::string message = error.what();
      for (const char* raw : {"XML_ERROR", "ErrorID", "XMLElement name="})
        EXPECT_EQ(message.find(raw), std::string::npos) << message;
    }
  }
}

TEST(MalformedProblems, EveryFileInTheFolderHasACase) {
  std::set<std::string> withCase;
  for (const MalformedCase& c : kMalformedCases) withCase.insert(std::string(c.name) + ".xml");
  std::set<std::string> files;
  for (const auto& entry : fs::directory_iterator(malformedFile("")))
    if (entry.path().extension() == ".xml") files.insert(entry.path().filename().string());
  EXPECT_EQ(files, withCase);
  EXPECT_GE(withCase.size(), 12u);
}

}  // namespace
}  // namespace kautham::core
