// `kautham generate clutter` as a user runs it: the file it writes, loaded by the real loader
// and checked by `kautham check` (the real physics), its reproducibility and its refusals.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "TestPaths.h"
#include "apps/CommandTestSupport.h"
#include "kautham/core/ApproachCorridor.h"
#include "kautham/core/ProblemLoader.h"

namespace kautham::apps {
namespace {

namespace fs = std::filesystem;

using test::CommandRun;
using test::kautham;
using test::readFile;

constexpr double kCanRadius = 0.033;  // models/objects/can.urdf
constexpr double kCanTop = 0.75 + 0.122;
constexpr double kGap = 0.01;  // the generator's default least distance between objects

using GenerateCommandTest = test::TemporaryFolderTest;

CommandRun generate(const std::string& arguments) {
  return kautham("generate clutter " + arguments);
}

/// The earlier top-down layout (kuka_cans_N), which the tests below the side layout's check.
CommandRun generateTop(const std::string& arguments) {
  return generate("--layout top " + arguments);
}

core::Problem load(const fs::path& file) {
  return core::loadProblem(file, {fs::path(KAUTHAM_SOURCE_DIR) / "models"});
}

std::vector<const core::ObjectInstance*> withRole(const core::Problem& problem,
                                                  core::ObjectRole role) {
  std::vector<const core::ObjectInstance*> found;
  for (const core::ObjectInstance& object : problem.objects)
    if (object.role == role) found.push_back(&object);
  return found;
}

double planarDistance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return (a.head<2>() - b.head<2>()).norm();
}

/// Distance in x and y from a point to a box seen from above (0 inside it).
double planarDistance(const Eigen::Vector3d& p, const Eigen::AlignedBox3d& box) {
  const double dx = std::max({box.min().x() - p.x(), 0.0, p.x() - box.max().x()});
  const double dy = std::max({box.min().y() - p.y(), 0.0, p.y() - box.max().y()});
  return std::hypot(dx, dy);
}

/// Everything the rules of docs/scenes.md promise about a generated scene, on the loaded file.
void expectValidScene(const fs::path& file, int objects) {
  SCOPED_TRACE(file.string());
  const core::Problem problem = load(file);
  const auto cans = withRole(problem, core::ObjectRole::Movable);
  ASSERT_EQ(cans.size(), static_cast<std::size_t>(objects));
  ASSERT_EQ(withRole(problem, core::ObjectRole::Target).size(), 1u);
  const core::ObjectInstance& glass = problem.target();
  EXPECT_EQ(glass.name, "glass");

  const Eigen::AlignedBox3d table = core::boundsAtHome(problem.objects[*problem.supportObject()]);
  for (std::size_t i = 0; i < cans.size(); ++i) {
    const Eigen::Vector3d p = cans[i]->home.position;
    // On the table top, whole, and upright.
    EXPECT_NEAR(p.z(), 0.811, 1e-9) << cans[i]->name;
    EXPECT_GE(p.x() - kCanRadius, table.min().x()) << cans[i]->name;
    EXPECT_LE(p.x() + kCanRadius, table.max().x()) << cans[i]->name;
    EXPECT_GE(p.y() - kCanRadius, table.min().y()) << cans[i]->name;
    EXPECT_LE(p.y() + kCanRadius, table.max().y()) << cans[i]->name;
    EXPECT_GE(planarDistance(p, glass.home.position), kCanRadius + 0.04 + kGap) << cans[i]->name;
    for (std::size_t j = i + 1; j < cans.size(); ++j)
      EXPECT_GE(planarDistance(p, cans[j]->home.position), 2 * kCanRadius + kGap - 1e-9)
          << cans[i]->name << " and " << cans[j]->name;
  }

  // Clear of every part of the robot that is less than 15 cm above the cans at the start (the
  // base, and the gripper over the table), by the real kinematics of the URDF.
  const core::Query& query = problem.queries.at(0);
  const core::RobotInstance& robot = problem.robot;
  const auto poses =
      robot.model.linkPoses(robot.home.isometry(), problem.initialJointValues(query));
  int lowShapes = 0;
  for (std::size_t l = 0; l < robot.model.links.size(); ++l)
    for (const core::CollisionShape& shape : robot.model.links[l].collisions) {
      const Eigen::AlignedBox3d box = core::boundingBox(shape.shape, poses[l] * shape.origin);
      if (box.min().z() > kCanTop + 0.15) continue;
      ++lowShapes;
      for (const core::ObjectInstance* can : cans)
        EXPECT_GE(planarDistance(can->home.position, box), kCanRadius + kGap)
            << can->name << " and " << robot.model.links[l].name;
    }
  EXPECT_GE(lowShapes, 2);  // the base and at least one gripper

  // The goal: kept clear with few objects, blocked with many.
  const Eigen::Vector3d goal = problem.goalPosition(query.goal);
  double nearest = 1e9;
  for (const core::ObjectInstance* can : cans)
    nearest = std::min(nearest, planarDistance(can->home.position, goal));
  if (objects >= 10)
    EXPECT_LE(nearest, 0.02);
  else
    EXPECT_GE(nearest, kCanRadius + 0.05);
}

TEST_F(GenerateCommandTest, SameSeedGivesTheSameBytesAnotherSeedAnotherScene) {
  fs::create_directories(folder / "a");
  fs::create_directories(folder / "b");
  fs::create_directories(folder / "c");
  const std::string arguments = "--robot kuka --objects 12 --seed 7 -o ";
  ASSERT_EQ(generateTop(arguments + (folder / "a" / "scene.xml").string()).exitCode, 0);
  // Short options, and the same options in another order, are the same arguments.
  ASSERT_EQ(
      generate("-s 7 -n 12 -r kuka -l top -o " + (folder / "b" / "scene.xml").string()).exitCode,
      0);
  ASSERT_EQ(
      generateTop("--robot kuka --objects 12 --seed 8 -o " + (folder / "c" / "scene.xml").string())
          .exitCode,
      0);
  const std::string a = readFile(folder / "a" / "scene.xml");
  EXPECT_EQ(a, readFile(folder / "b" / "scene.xml"));

  // Another seed moves the cans, and nothing else.
  const core::Problem first = load(folder / "a" / "scene.xml");
  const core::Problem other = load(folder / "c" / "scene.xml");
  ASSERT_EQ(first.objects.size(), other.objects.size());
  int moved = 0;
  for (std::size_t i = 0; i < first.objects.size(); ++i) {
    EXPECT_EQ(first.objects[i].name, other.objects[i].name);
    if (first.objects[i].role != core::ObjectRole::Movable) {
      EXPECT_EQ(first.objects[i].home.position, other.objects[i].home.position);
      continue;
    }
    moved += !first.objects[i].home.position.isApprox(other.objects[i].home.position);
  }
  EXPECT_GE(moved, 10);
}

TEST_F(GenerateCommandTest, HeaderRecordsTheCommandThatRemakesTheFile) {
  const fs::path file = folder / "kuka_cans_10.xml";
  ASSERT_EQ(generateTop("--robot kuka --objects 10 --seed 3 -o " + file.string()).exitCode, 0);
  const std::string text = readFile(file);
  const std::string line =
      "Made by: kautham generate clutter -r kuka -n 10 -s 3 -l top -o kuka_cans_10.xml";
  EXPECT_NE(text.find(line), std::string::npos) << text;
  EXPECT_NE(text.find("<Problem name=\"kuka_cans_10\">"), std::string::npos);
  // "--" may not appear inside an XML comment.
  for (std::size_t open = text.find("<!--"); open != std::string::npos;
       open = text.find("<!--", open + 4)) {
    const std::size_t close = text.find("-->", open + 4);
    ASSERT_NE(close, std::string::npos);
    EXPECT_EQ(text.substr(open + 4, close - open - 4).find("--"), std::string::npos);
  }
  // The recorded command, run in another folder, writes the same bytes.
  fs::create_directories(folder / "again");
  const CommandRun again = test::run("cd '" + (folder / "again").string() + "' && '" +
                                     KAUTHAM_BINARY + "' " + line.substr(17) + " 2>&1");
  ASSERT_EQ(again.exitCode, 0) << again.output;
  EXPECT_EQ(readFile(folder / "again" / "kuka_cans_10.xml"), text);
}

TEST_F(GenerateCommandTest, ScenesFollowThePlacementRulesAndPassTheStartCheck) {
  for (const char* robot : {"kuka", "yumi"})
    for (int objects : {0, 5, 10, 25, 40}) {
      const fs::path file = folder / (std::string(robot) + "_" + std::to_string(objects) + ".xml");
      const CommandRun made =
          generateTop(std::string("--robot ") + robot + " --objects " + std::to_string(objects) +
                      " --seed 11 -o " + file.string());
      ASSERT_EQ(made.exitCode, 0) << made.output;
      expectValidScene(file, objects);
      // The start state, in the real physics: nothing interpenetrates, every rule holds.
      const CommandRun check = kautham("check " + file.string() + " --model-dir models");
      EXPECT_EQ(check.exitCode, 0) << file << "\n" << check.output;
      EXPECT_NE(check.output.find("start valid"), std::string::npos) << check.output;
    }
}

TEST_F(GenerateCommandTest, TooManyObjectsExitsTwoSayingHowManyFit) {
  const fs::path file = folder / "crowded.xml";
  const CommandRun run = generateTop("--robot yumi --objects 40 --gap 0.15 -o " + file.string());
  EXPECT_EQ(run.exitCode, 2) << run.output;
  const std::regex message("only ([0-9]+) of 40 objects fit");
  std::smatch match;
  ASSERT_TRUE(std::regex_search(run.output, match, message)) << run.output;
  EXPECT_LT(std::stoi(match[1]), 40);
  EXPECT_GT(std::stoi(match[1]), 0);
  EXPECT_FALSE(fs::exists(file));
}

TEST_F(GenerateCommandTest, TooFewBlockersSayHowManyObjectsNeedNoMore) {
  // 40 objects need 8 blockers on the YuMi's approach; only some fit at this gap.
  const fs::path file = folder / "crowded.xml";
  const CommandRun run = generate("--robot yumi --objects 40 -o " + file.string());
  ASSERT_EQ(run.exitCode, 2) << run.output;
  const std::regex message(
      "only ([0-9]+) of the 8 blockers that 40 objects need fit on the yumi's approach \\(at "
      "least 0.01 m apart\\); use a smaller --gap, or at most ([0-9]+) objects \\(they need at "
      "most ([0-9]+) blockers?\\)");
  std::smatch match;
  ASSERT_TRUE(std::regex_search(run.output, match, message)) << run.output;
  const int fitted = std::stoi(match[1]);
  const int most = std::stoi(match[2]);
  EXPECT_EQ(std::stoi(match[3]), fitted);
  EXPECT_GT(fitted, 1);  // so the hint is not the "fewer than 10" of a scene without blockers
  EXPECT_EQ(most, 5 * fitted);  // ceil(N / 5) blockers from 10 objects on
  // The hint holds: that many objects get their blockers placed (and one more would not).
  const CommandRun fewer = generate("--robot yumi --objects " + std::to_string(most) + " -o " +
                                    (folder / "fewer.xml").string());
  EXPECT_EQ(fewer.output.find("blockers that"), std::string::npos) << fewer.output;
  const CommandRun oneMore = generate("--robot yumi --objects " + std::to_string(most + 1) +
                                      " -o " + (folder / "more.xml").string());
  EXPECT_NE(oneMore.output.find("blockers that"), std::string::npos) << oneMore.output;
}

TEST_F(GenerateCommandTest, ExistingFileIsKeptWithoutForce) {
  const fs::path file = folder / "scene.xml";
  test::writeFile(file, "mine");
  const CommandRun refused = generate("--robot kuka --objects 5 -o " + file.string());
  EXPECT_EQ(refused.exitCode, 2);
  EXPECT_NE(refused.output.find("--force"), std::string::npos) << refused.output;
  EXPECT_EQ(readFile(file), "mine");

  const CommandRun forced = generate("--robot kuka --objects 5 --force -o " + file.string());
  EXPECT_EQ(forced.exitCode, 0) << forced.output;
  EXPECT_NE(readFile(file).find("<Problem"), std::string::npos);
}

TEST_F(GenerateCommandTest, BadArgumentsExitTwo) {
  const std::string output = " -o " + (folder / "x.xml").string();
  for (const char* arguments :
       {"--robot pr2 --objects 5", "--robot kuka --objects 61", "--robot kuka --objects -1",
        "--robot kuka --objects five", "--robot kuka --objects 5 --target cup",
        "--robot kuka --objects 5 --gap -0.01", "--objects 5"}) {
    const CommandRun run = generate(arguments + output);
    EXPECT_EQ(run.exitCode, 2) << arguments << "\n" << run.output;
  }
  EXPECT_FALSE(fs::exists(folder / "x.xml"));
  EXPECT_EQ(generate("--robot kuka --objects 5").exitCode, 2);  // no output file
  EXPECT_EQ(kautham("generate").exitCode, 2);                   // no kind of scene
}

/// The start of a side scene has the gripper pointing at the target, as docs/scenes.md says:
/// `check` prints the goal link's +z (its approach axis) at the start. (The YuMi's start once
/// pointed it back at the robot, and every plan began with a half turn of the wrist.)
void expectStartPointsAlongTheApproach(const std::string& checkOutput,
                                       const Eigen::Vector3d& approach, const std::string& name) {
  const std::regex axis(
      R"(start +\S+: \S+ at \([^)]*\), its \+z along \(([-0-9.]+), ([-0-9.]+), ([-0-9.]+)\))");
  std::smatch match;
  ASSERT_TRUE(std::regex_search(checkOutput, match, axis)) << name << "\n" << checkOutput;
  const Eigen::Vector3d startAxis(std::stod(match[1]), std::stod(match[2]), std::stod(match[3]));
  EXPECT_GT(startAxis.normalized().dot(approach.normalized()), std::cos(0.3))
      << name << ": the gripper points along " << startAxis.transpose() << " at the start";
}

/// The dense suite's promises (docs/scenes.md): the same bytes for the same arguments, objects
/// apart, ceil(N/5) blockers from 10 objects on as `kautham check` counts them
/// (core::approachBlockers, the goal's corridor and free space), and a valid start.
TEST_F(GenerateCommandTest, SideScenesAreReproducibleAndBlockTheApproach) {
  for (const char* robot : {"kuka", "yumi"})
    for (int objects : {5, 10, 20, 30}) {
      const std::string name = std::string(robot) + "_" + std::to_string(objects) + ".xml";
      fs::create_directories(folder / "again");
      const std::string arguments =
          std::string("-r ") + robot + " -n " + std::to_string(objects) + " -s 4 -o ";
      const CommandRun made = generate(arguments + (folder / name).string());
      ASSERT_EQ(made.exitCode, 0) << made.output;
      ASSERT_EQ(generate(arguments + (folder / "again" / name).string()).exitCode, 0);
      EXPECT_EQ(readFile(folder / name), readFile(folder / "again" / name)) << name;

      const core::Problem problem = load(folder / name);
      const auto movable = withRole(problem, core::ObjectRole::Movable);
      ASSERT_EQ(movable.size(), static_cast<std::size_t>(objects));
      for (std::size_t i = 0; i < movable.size(); ++i)
        for (std::size_t j = i + 1; j < movable.size(); ++j)
          EXPECT_GE(planarDistance(movable[i]->home.position, movable[j]->home.position),
                    2 * kCanRadius + kGap - 1e-9)
              << name << ": " << movable[i]->name << " and " << movable[j]->name;
      const core::GoalRegion& goal = problem.queries.at(0).goal;
      ASSERT_TRUE(goal.freeSpace && goal.levelAxis && goal.approach) << name;
      EXPECT_LE(goal.tolerance, 0.02);
      EXPECT_LE(goal.approachTolerance, 0.3);
      const auto blockers = core::approachBlockers(problem, goal);
      if (objects >= 10) {
        EXPECT_GE(blockers.size(), static_cast<std::size_t>((objects + 4) / 5));
      }

      const CommandRun check = kautham("check " + (folder / name).string() + " --model-dir models");
      ASSERT_EQ(check.exitCode, 0) << name << "\n" << check.output;
      EXPECT_NE(check.output.find("start valid"), std::string::npos) << check.output;
      expectStartPointsAlongTheApproach(check.output, *goal.approach, name);
      EXPECT_NE(check.output.find("blockers    " + std::to_string(blockers.size()) + " of " +
                                  std::to_string(objects) + " movable objects"),
                std::string::npos)
          << check.output;
    }
}

/// Each arm's dense scenes ask QuickStep for what its pushes were measured to need
/// (docs/physics.md, "Over-relaxation"): the KUKA's 40 plain iterations, the YuMi's 20
/// over-relaxed at 1.7; the top-down scenes keep ODE's defaults at 20.
TEST_F(GenerateCommandTest, EachArmsSceneAsksForItsSolverSettings) {
  struct Expected {
    const char* arguments;
    int iterations;
    double overRelaxation;
  };
  for (const Expected& e : {Expected{"-r kuka -n 5", 40, 1.3}, Expected{"-r yumi -n 5", 20, 1.7},
                            Expected{"-r kuka -n 5 --layout top", 20, 1.3}}) {
    const fs::path file = folder / "solver.xml";
    ASSERT_EQ(generate(std::string(e.arguments) + " --force -o " + file.string()).exitCode, 0);
    const core::Problem problem = load(file);
    EXPECT_EQ(problem.physics.solverIterations, e.iterations) << e.arguments;
    EXPECT_DOUBLE_EQ(problem.physics.overRelaxation, e.overRelaxation) << e.arguments;
  }
}

/// `generate` and `check` count the same blockers, boxes (whose circumscribed circle is wider
/// than their footprint) included.
TEST_F(GenerateCommandTest, GenerateAndCheckCountTheSameBlockers) {
  for (const std::string arguments : {"-r kuka -n 20 --mix", "-r kuka -n 25", "-r yumi -n 20"})
    for (int seed : {1, 2, 3}) {
      const fs::path file = folder / ("scene" + std::to_string(seed) + ".xml");
      const CommandRun made =
          generate(arguments + " -s " + std::to_string(seed) + " --force -o " + file.string());
      ASSERT_EQ(made.exitCode, 0) << made.output;
      std::smatch said;
      ASSERT_TRUE(std::regex_search(made.output, said, std::regex("\\(([0-9]+) on the approach")))
          << made.output;
      const core::Problem problem = load(file);
      const auto counted = core::approachBlockers(problem, problem.queries.at(0).goal);
      EXPECT_EQ(std::to_string(counted.size()), said[1].str()) << arguments << " -s " << seed;
    }
}

TEST_F(GenerateCommandTest, MixedSceneHasABottleBoxesAndCans) {
  const fs::path file = folder / "mixed.xml";
  ASSERT_EQ(generate("-r kuka -n 9 --mix -o " + file.string()).exitCode, 0);
  const std::string text = readFile(file);
  EXPECT_NE(text.find("objects/bottle.urdf"), std::string::npos);
  EXPECT_NE(text.find("<KauthamName name=\"box4\"/>"), std::string::npos);
  EXPECT_NE(text.find("<KauthamName name=\"can4\"/>"), std::string::npos);
  EXPECT_EQ(kautham("check " + file.string() + " --model-dir models").exitCode, 0);
  EXPECT_EQ(generate("-r kuka -n 9 --mix --layout top -o " + (folder / "x.xml").string()).exitCode,
            2);
  EXPECT_EQ(generate("-r yumi -n 9 --mix -o " + (folder / "x.xml").string()).exitCode, 2);
}

/// Every shipped scene is what its recorded command writes today: none was edited by hand or
/// left behind by a change of the generator.
TEST_F(GenerateCommandTest, ShippedScenesAreUpToDate) {
  int scenes = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(KAUTHAM_SOURCE_DIR) / "problems")) {
    const std::string name = entry.path().filename().string();
    if (!std::regex_match(name, std::regex("(kuka|yumi)_(cans|clutter)_[0-9a-z]+\\.xml"))) continue;
    ++scenes;
    const std::string text = readFile(entry.path());
    std::smatch made;
    ASSERT_TRUE(std::regex_search(
        text, made, std::regex("Made by: kautham (generate clutter [-a-z0-9_. ]*[.]xml) -->")))
        << name;
    const CommandRun run = test::run("cd '" + folder.string() + "' && '" + KAUTHAM_BINARY + "' " +
                                     made[1].str() + " 2>&1");
    ASSERT_EQ(run.exitCode, 0) << name << "\n" << run.output;
    EXPECT_EQ(readFile(folder / name), text) << name << " differs from what its command writes";
  }
  EXPECT_EQ(scenes, 4 + 18);  // kuka/yumi_cans_5/10; the dense suite N = 5..40 and two demos
}

}  // namespace
}  // namespace kautham::apps
