// The `kautham` program as a user runs it: exit codes, messages, the plan file.

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestPaths.h"
#include "apps/CommandTestSupport.h"

namespace kautham::apps {
namespace {

namespace fs = std::filesystem;

using test::CommandRun;
using test::kautham;

nlohmann::json readJson(const fs::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

using PlanCommandTest = test::TemporaryFolderTest;

TEST_F(PlanCommandTest, DefaultProblemSolvesAndWritesAPlan) {
  const fs::path planFile = folder / "plan.json";
  const CommandRun run =
      kautham("plan problems/pusher_cans_5.xml --seed 1 -o " + planFile.string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("solved    yes"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("reaches the goal"), std::string::npos) << run.output;

  const nlohmann::json plan = readJson(planFile);
  EXPECT_EQ(plan["format"], "kautham-plan");
  EXPECT_EQ(plan["planner"]["name"], "KPIECE");
  EXPECT_EQ(plan["seed"], 1);
  EXPECT_TRUE(plan["result"]["solved"].get<bool>());
  EXPECT_TRUE(plan["result"]["replay"]["reached_goal"].get<bool>());
  EXPECT_FALSE(plan["result"]["replay"]["moved_objects"].empty());
  EXPECT_FALSE(plan["controls"].empty());
  // One pose per body per frame, frames one propagation step apart.
  const std::size_t bodies = plan["bodies"].size();
  EXPECT_EQ(bodies, 9u);
  std::size_t framesWithContact = 0;
  for (const auto& frame : plan["frames"]) {
    EXPECT_EQ(frame["poses"].size(), bodies);
    framesWithContact += !frame["touched"].empty();
    for (const auto& b : frame["touched"]) EXPECT_NE(plan["bodies"][b.get<int>()]["role"], "robot");
  }
  EXPECT_GT(framesWithContact, 0u);  // it pushed
  // The robot's joint positions in every frame, named once: the pusher's x and y joints moved.
  const std::size_t joints = plan["joint_names"].size();
  ASSERT_GT(joints, 0u);
  for (const auto& frame : plan["frames"]) EXPECT_EQ(frame["joints"].size(), joints);
  EXPECT_NE(plan["frames"].front()["joints"], plan["frames"].back()["joints"]);
  EXPECT_GT(plan["statistics"]["physics_steps"].get<long>(), 0);
  // Every collision shape, for viewers: 3 gripper boxes, the table, the glass, 5 cans.
  EXPECT_EQ(plan["shapes"].size(), 10u);
}

// Kautham's own format (problems/kautham/): no roles, no target, configuration goals.
TEST_F(PlanCommandTest, KauthamFormProblemsLoadAndPlan) {
  for (const std::string name : {"sphere_cubes", "kuka_table"}) {
    SCOPED_TRACE(name);
    const std::string problem = "problems/kautham/" + name + ".xml";
    const CommandRun check = kautham("check " + problem);
    ASSERT_EQ(check.exitCode, 0) << check.output;
    EXPECT_NE(check.output.find("start valid"), std::string::npos) << check.output;
    const fs::path planFile = folder / (name + ".json");
    const CommandRun run =
        kautham("plan " + problem + " --seed 1 --time 20 -o " + planFile.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("solved    yes"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("reaches the goal"), std::string::npos) << run.output;
    const nlohmann::json plan = readJson(planFile);
    EXPECT_EQ(plan["planner"]["name"], "KPIECE");
    EXPECT_TRUE(plan["result"]["solved"].get<bool>());
    EXPECT_TRUE(plan["result"]["replay"]["reached_goal"].get<bool>());
    EXPECT_FALSE(plan["controls"].empty());
  }
  // The sphere cannot pass the cubes without pushing them.
  const nlohmann::json sphere = readJson(folder / "sphere_cubes.json");
  EXPECT_FALSE(sphere["result"]["replay"]["moved_objects"].empty());
}

TEST_F(PlanCommandTest, SameCommandTwiceGivesTheSamePlanFile) {
  const fs::path a = folder / "a.json";
  const fs::path b = folder / "b.json";
  ASSERT_EQ(kautham("plan problems/pusher_cans_5.xml --seed 2 -o " + a.string()).exitCode, 0);
  ASSERT_EQ(kautham("plan problems/pusher_cans_5.xml --seed 2 -o " + b.string()).exitCode, 0);
  nlohmann::json first = readJson(a);
  nlohmann::json second = readJson(b);
  first.erase("timing");
  second.erase("timing");
  EXPECT_EQ(first, second);
}

TEST_F(PlanCommandTest, MalformedProblemExitsTwoNamingFileAndLine) {
  const CommandRun run = kautham("plan tests/data/malformed/unknown_role.xml --model-dir models");
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.output.find("unknown_role.xml:"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("unknown role"), std::string::npos) << run.output;
}

TEST_F(PlanCommandTest, InterpenetratingObjectsExitTwoNamingThem) {
  const CommandRun run = kautham("plan tests/data/overlap_can_in_glass.xml --model-dir models");
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.output.find("overlap_can_in_glass.xml:"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("can1"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("interpenetrate"), std::string::npos) << run.output;
}

TEST_F(PlanCommandTest, OutputFolderIsCreated) {
  const fs::path planFile = folder / "new" / "folder" / "plan.json";
  ASSERT_EQ(kautham("plan problems/pusher_free.xml --seed 1 -o " + planFile.string()).exitCode, 0);
  EXPECT_TRUE(fs::is_regular_file(planFile));
}

TEST_F(PlanCommandTest, AGoalMarginNoPlanCouldMeetExitsTwoSayingTheRange) {
  // goal_margin 0 would ask a plan to end exactly on the goal point: no plan ever could.
  const CommandRun run =
      kautham("plan problems/yumi_clutter_5.xml --set uncertainty=0 --set goal_margin=0");
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.output.find("'goal_margin' must be in [0.05, 1]"), std::string::npos) << run.output;
}

TEST_F(PlanCommandTest, MissingProblemFileExitsTwo) {
  const CommandRun run = kautham("plan no/such/problem.xml");
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.output.find("no/such/problem.xml"), std::string::npos) << run.output;
}

TEST_F(PlanCommandTest, UnknownParameterOrPlannerExitsTwo) {
  EXPECT_EQ(kautham("plan problems/pusher_free.xml --set goal_bais=0.1").exitCode, 2);
  EXPECT_EQ(kautham("plan problems/pusher_free.xml --set goal_bias=7").exitCode, 2);
  EXPECT_EQ(kautham("plan problems/pusher_free.xml --planner NoSuchPlanner").exitCode, 2);
  EXPECT_EQ(kautham("plan problems/pusher_free.xml --no-such-flag").exitCode, 2);
}

TEST_F(PlanCommandTest, ASeedOutOfRangeSaysWhatASeedMustBe) {
  // plan and bench seed 32-bit streams; validate and generate 64-bit ones.
  const std::string max32 = "4294967295";
  const std::string max64 = "18446744073709551615";
  const std::pair<std::string, std::string> cases[] = {
      {"plan problems/pusher_free.xml --seed 4294967296", max32},
      {"plan problems/pusher_free.xml --seed -1", max32},
      {"plan problems/pusher_free.xml --seed 1.5", max32},
      {"bench problems/pusher_free.xml --planner RRT --seed 4294967296 -o " +
           (folder / "bench").string(),
       max32},
      {"validate problems/pusher_free.xml no_plan.json --runs 1 --seed 18446744073709551616",
       max64},
      {"generate clutter -r kuka -n 1 --seed 18446744073709551616 -o " +
           (folder / "g.xml").string(),
       max64},
  };
  for (const auto& [command, max] : cases) {
    const CommandRun run = kautham(command);
    EXPECT_EQ(run.exitCode, 2) << command << "\n" << run.output;
    EXPECT_NE(run.output.find("the seed must be an integer in [0, " + max + "], got '"),
              std::string::npos)
        << command << "\n"
        << run.output;
    EXPECT_EQ(run.output.find("Could not convert"), std::string::npos) << run.output;
  }
  EXPECT_FALSE(fs::exists(folder / "g.xml"));
}

TEST_F(PlanCommandTest, AWordOrANegativeWhereANumberBelongsSaysWhatTheOptionTakes) {
  // CLI11 alone said "Value abc not in range" for a word, and wrapped --query -1 round to
  // 18446744073709551615 before the command named the problem's queries.
  const std::pair<std::string, std::string> cases[] = {
      {"plan problems/pusher_free.xml --time abc",
       "--time: expected a number in [0.01, 86400], got 'abc'"},
      {"plan problems/pusher_free.xml --time nan",
       "--time: expected a number in [0.01, 86400], got 'nan'"},
      {"plan problems/pusher_free.xml --query -1",
       "--query: expected an integer in [0, 4294967295], got '-1'"},
      {"view problems/pusher_free.xml --query x -o " + (folder / "v.html").string(),
       "--query: expected an integer in [0, 4294967295], got 'x'"},
      {"validate problems/pusher_free.xml no_plan.json --runs many",
       "--runs: expected an integer in [1, 100000000], got 'many'"},
      {"generate clutter -r kuka -n ten -o " + (folder / "g.xml").string(),
       "--objects: expected an integer in [0, 60], got 'ten'"},
      {"generate clutter -r kuka -n 3 --gap 1cm -o " + (folder / "g.xml").string(),
       "--gap: expected a number in [0, 0.2], got '1cm'"},
      {"plan problems/pusher_free.xml --threads two",
       "--threads: expected an integer in [1, 64], got 'two'"},
      {"bench problems/pusher_free.xml --planner RRT --runs abc -o " + (folder / "b").string(),
       "--runs: expected an integer in [1, 4294967295], got 'abc'"},
      {"bench problems/pusher_free.xml --planner RRT --time 1min -o " + (folder / "b").string(),
       "--time: expected a number in [0.01, 86400], got '1min'"},
      {"bench problems/pusher_free.xml --planner RRT --jobs 0 -o " + (folder / "b").string(),
       "--jobs: expected an integer in [1, 256], got '0'"},
  };
  for (const auto& [command, message] : cases) {
    const CommandRun run = kautham(command);
    EXPECT_EQ(run.exitCode, 2) << command << "\n" << run.output;
    EXPECT_NE(run.output.find(message), std::string::npos) << command << "\n" << run.output;
    EXPECT_EQ(run.output.find("not in range"), std::string::npos) << run.output;
  }
  EXPECT_FALSE(fs::exists(folder / "g.xml"));
  EXPECT_FALSE(fs::exists(folder / "v.html"));
  EXPECT_FALSE(fs::exists(folder / "b"));
}

TEST_F(PlanCommandTest, ASetValueBeyondADoubleSaysOutOfRange) {
  for (const char* set : {"time_limit=1e400", "goal_bias=-1e400", "propagation_step_size=2e308"}) {
    const CommandRun run = kautham(std::string("plan problems/pusher_free.xml --set ") + set);
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_NE(run.output.find("is out of range: "), std::string::npos) << set << "\n" << run.output;
    EXPECT_NE(run.output.find("is beyond the largest number a double holds (about 1.8e308); it "
                              "must be in ["),
              std::string::npos)
        << set << "\n"
        << run.output;
    EXPECT_EQ(run.output.find("expects a number"), std::string::npos) << run.output;
  }
  const CommandRun physics = kautham("plan problems/pusher_free.xml --physics friction=1e999");
  EXPECT_EQ(physics.exitCode, 2) << physics.output;
  EXPECT_NE(physics.output.find("--physics friction=1e999: out of range: 1e999 is beyond the "
                                "largest number a double holds"),
            std::string::npos)
      << physics.output;
}

TEST_F(PlanCommandTest, UnsolvedWithinTheTimeLimitExitsOne) {
  const CommandRun run = kautham("plan problems/pusher_cans_5.xml --seed 1 --time 0.01");
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("solved    no"), std::string::npos) << run.output;
}

// An output that cannot be a file is refused before planning (exit 2), and nothing is replaced:
// not a folder, not a device, not a link to nothing; no temporary file is left behind.
TEST_F(PlanCommandTest, AnOutputThatCannotBeAFileIsRefusedBeforePlanning) {
  const fs::path aFile = folder / "a_file";
  std::ofstream(aFile) << "kept\n";
  const fs::path dangling = folder / "dangling";
  fs::create_symlink(folder / "nothing_there", dangling);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"-o " + folder.string(), "is a folder"},
      {"-o " + (aFile / "plan.json").string(), "is not a folder"},
      {"--html /dev/null", "the system's devices"},
      {"-o " + dangling.string(), "a link to nothing"}};
  for (const auto& [option, phrase] : cases) {
    SCOPED_TRACE(option);
    const CommandRun run = kautham("plan problems/pusher_cans_5.xml --seed 1 " + option);
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_NE(run.output.find(phrase), std::string::npos) << run.output;
    EXPECT_EQ(run.output.find("solved"), std::string::npos) << run.output;  // nothing planned
  }
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dangling)));
  std::ifstream kept(aFile);
  std::string line;
  std::getline(kept, line);
  EXPECT_EQ(line, "kept");
  for (const auto& entry : fs::directory_iterator(folder))
    EXPECT_NE(entry.path().extension(), ".tmp") << entry.path();
}

// Through a symbolic link the file it leads to is written, and the link stays.
TEST_F(PlanCommandTest, APlanWrittenThroughALinkKeepsTheLink) {
  const fs::path target = folder / "target.json";
  std::ofstream(target) << "{}\n";
  const fs::path link = folder / "link.json";
  fs::create_symlink(target, link);
  const CommandRun run = kautham("plan problems/pusher_free.xml --seed 1 -o " + link.string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link)));
  EXPECT_EQ(readJson(target)["format"], "kautham-plan");
}

TEST_F(PlanCommandTest, AValueNotMeasuredYetPrintsAsADash) {
  // Stopped before any candidate reached the goal, p-KPIECE has no goal confidence yet.
  const CommandRun run =
      kautham("plan problems/pusher_cans_5.xml --planner p-KPIECE --seed 1 --time 0.05");
  EXPECT_NE(run.output.find("best_goal_confidence -,"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("nan"), std::string::npos) << run.output;
}

TEST_F(PlanCommandTest, PlannersListsEveryPlannerWithItsParameters) {
  const CommandRun run = kautham("planners");
  EXPECT_EQ(run.exitCode, 0);
  for (const char* text : {"KPIECE", "RRT", "goal_bias", "border_fraction", "cell_size",
                           "time_limit", "propagation_step_size", "Goal Bias"})
    EXPECT_NE(run.output.find(text), std::string::npos) << text << "\n" << run.output;
  // goal-steering takes p-KPIECE's parameters, listed once under p-KPIECE, and one of its own.
  const std::size_t steering = run.output.find("\ngoal-steering: ");
  ASSERT_NE(steering, std::string::npos) << run.output;
  const std::size_t next = run.output.find("\n\n", steering + 1);
  const std::string listing = run.output.substr(steering, next - steering);
  EXPECT_NE(listing.find("the parameters of p-KPIECE (below), and"), std::string::npos) << listing;
  EXPECT_NE(listing.find("    tree "), std::string::npos) << listing;
  EXPECT_EQ(listing.find("    goal_bias "), std::string::npos) << listing;  // under p-KPIECE
}

TEST_F(PlanCommandTest, CheckSummarisesAValidProblem) {
  const CommandRun run = kautham("check problems/pusher_cans_5.xml");
  EXPECT_EQ(run.exitCode, 0) << run.output;
  for (const char* text : {"3 degrees of freedom", "movable: can1, can2, can3, can4, can5",
                           "target: glass", "start valid", "ok"})
    EXPECT_NE(run.output.find(text), std::string::npos) << text << "\n" << run.output;
}

TEST_F(PlanCommandTest, CheckListsSensedEnvironments) {
  const CommandRun run = kautham("check problems/pusher_shelf.xml");
  EXPECT_EQ(run.exitCode, 0) << run.output;
  for (const char* text : {"fixed: table, shelf",
                           "environment shelf (shelf.bt, 0.02 m voxels): 6870 occupied leaves "
                           "merged into 9 boxes",
                           "start valid", "ok"})
    EXPECT_NE(run.output.find(text), std::string::npos) << text << "\n" << run.output;
  EXPECT_EQ(run.output.find("octree type"), std::string::npos) << run.output;  // octomap is quiet
}

TEST_F(PlanCommandTest, CheckRejectsBadProblemsWithExitTwo) {
  const CommandRun overlap = kautham("check tests/data/overlap_can_in_glass.xml");
  EXPECT_EQ(overlap.exitCode, 2) << overlap.output;
  EXPECT_NE(overlap.output.find("interpenetrate"), std::string::npos) << overlap.output;
  const CommandRun malformed =
      kautham("check tests/data/malformed/home_nan.xml --model-dir models");
  EXPECT_EQ(malformed.exitCode, 2) << malformed.output;
  EXPECT_NE(malformed.output.find("home_nan.xml:"), std::string::npos) << malformed.output;
}

TEST_F(PlanCommandTest, HelpExplainsThePlanCommand) {
  const CommandRun run = kautham("plan --help");
  EXPECT_EQ(run.exitCode, 0);
  for (const char* text : {"--planner", "--time", "--seed", "--set", "--output"})
    EXPECT_NE(run.output.find(text), std::string::npos) << text;
}

TEST_F(PlanCommandTest, HelpOfThreadsSaysWhichPlannersUseThem) {
  // CLI11 wraps the help text: compare it with its line breaks and indents taken out.
  for (const char* command : {"plan --help", "bench --help"}) {
    std::string help;
    for (char c : kautham(command).output)
      if (c != '\n' && c != ' ') help += c;
    EXPECT_NE(help.find("p-KPIECE'sparticlesand"), std::string::npos) << command << "\n" << help;
    EXPECT_NE(help.find("whole-planverification"), std::string::npos) << command;
    EXPECT_NE(help.find("theotherplannersruninonethreadandignoreit"), std::string::npos) << command;
  }
}

}  // namespace
}  // namespace kautham::apps
