// `kautham bench` as a user runs it: real plans in child processes, result files, resume,
// shards that merge into the whole run's log, Ctrl-C and crashed children, and logs that
// Debian's ompl_benchmark_statistics turns into a Planner Arena database.

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestPaths.h"
#include "apps/CommandTestSupport.h"

namespace kautham::apps {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::CommandRun;
using test::kautham;

const fs::path kStatistics = "/usr/bin/ompl_benchmark_statistics";

class BenchCommandTest : public test::TemporaryFolderTest {
 protected:
  std::string out(const std::string& name = "out") const {
    return "-o '" + (folder / name).string() + "'";
  }
  json readJson(const fs::path& file) const {
    std::ifstream in(file);
    return json::parse(in);
  }
  /// `sqlite3 DB QUERY`, rows on lines, columns separated by '|'.
  std::string query(const fs::path& db, const std::string& sql) const {
    const CommandRun run = test::run("sqlite3 '" + db.string() + "' \"" + sql + "\" 2>&1");
    EXPECT_EQ(run.exitCode, 0) << run.output;
    return run.output;
  }
  std::size_t countFiles(const fs::path& root, const std::string& ending) const {
    std::size_t n = 0;
    if (!fs::exists(root)) return 0;
    for (const auto& e : fs::recursive_directory_iterator(root)) {
      const std::string name = e.path().filename().string();
      n += name.size() >= ending.size() &&
           name.compare(name.size() - ending.size(), ending.size(), ending) == 0;
    }
    return n;
  }
};

// Two free-space problems' worth of real runs: pusher_free solves in a fraction of a second.
const std::string kFreeRuns = "bench problems/pusher_free.xml --planner KPIECE --runs 2 --time 5 ";

TEST_F(BenchCommandTest, LogBecomesAPlannerArenaDatabase) {
  ASSERT_TRUE(fs::exists(kStatistics)) << "install ompl-demos (scripts/install-deps.sh)";
  // The configurations in the order given: the log's planners come in that order.
  const CommandRun run = kautham(
      "bench problems/pusher_free.xml --config 'KPgb=KPIECE:goal_bias=0.3' --planner KPIECE "
      "--runs 2 --time 5 --validate 3 " +
      out());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("runs      4: 4 made now, 0 resumed; 4 solved, 0 failed"),
            std::string::npos)
      << run.output;
  const fs::path log = folder / "out/logs/pusher_free.log";
  ASSERT_TRUE(fs::exists(log)) << run.output;

  const fs::path db = folder / "bench.db";
  const CommandRun statistics = test::run("'" + kStatistics.string() + "' '" + log.string() +
                                          "' -d '" + db.string() + "' 2>&1");
  ASSERT_EQ(statistics.exitCode, 0) << statistics.output;
  EXPECT_EQ(query(db, "SELECT name, runcount, timelimit, version FROM experiments"),
            "pusher_free|2|5.0|OMPL 1.5.2\n");
  EXPECT_EQ(query(db, "SELECT name FROM plannerConfigs ORDER BY id"), "KPgb\nKPIECE\n");
  // Each configuration's settings are what the planner's OMPL parameter set held: OMPL's own
  // parameters and ours (cell_size, the common ones), with the values the runs used.
  const std::string settings = query(db, "SELECT settings FROM plannerConfigs ORDER BY id");
  for (const char* expected :
       {"goal_bias = 0.3\n;", "goal_bias = 0.05\n;", "border_fraction = 0.8\n;",
        "max_close_samples = 30\n;", "cell_size = 0.05\n;", "time_limit = 5\n;",
        "propagation_step_size = 0.05\n;"})
    EXPECT_NE(settings.find(expected), std::string::npos) << expected << " in " << settings;
  // One row per run, in run order, with OMPL's columns and ours.
  EXPECT_EQ(query(db,
                  "SELECT p.name, r.seed, r.solved, r.status, r.approximate_solution, "
                  "r.correct_solution_strict, r.execution_success, r.objects_moved FROM runs r "
                  "JOIN plannerConfigs p ON p.id = r.plannerid ORDER BY r.id"),
            "KPgb|1|1|6|0|1|1.0|0\nKPgb|2|1|6|0|1|1.0|0\n"
            "KPIECE|1|1|6|0|1|1.0|0\nKPIECE|2|1|6|0|1|1.0|0\n");
  EXPECT_EQ(query(db, "SELECT description FROM enums WHERE name = 'status' AND value = 6"),
            "Exact solution\n");
  EXPECT_EQ(query(db,
                  "SELECT count(*) FROM runs WHERE time > 0 AND memory > 0 AND "
                  "graph_states > 0 AND propagations > 0 AND physics_steps > 0"),
            "4\n");
}

/// A log with what measures the machine blanked: host, date, cpu, total time, and each run's
/// time and memory columns. What is left must not depend on how the runs were split.
std::string withoutMeasurements(const std::string& log) {
  std::istringstream in(log);
  std::ostringstream kept;
  std::vector<std::string> properties;
  std::size_t propertiesLeft = 0;
  int blocks = 0;
  bool inCpuBlock = false;
  for (std::string line; std::getline(in, line);) {
    if (line == "<<<|" && ++blocks == 2) inCpuBlock = true;
    if (inCpuBlock) {
      inCpuBlock = line != "|>>>";
      continue;
    }
    if (line.rfind("Running on", 0) == 0 || line.rfind("Starting at", 0) == 0 ||
        line.find("seconds spent to collect the data") != std::string::npos)
      continue;
    if (line.find(" properties for each run") != std::string::npos) {
      properties.clear();
      propertiesLeft = std::stoul(line);
    } else if (propertiesLeft > 0) {
      properties.push_back(line);
      --propertiesLeft;
    } else if (line.size() >= 2 && line.compare(line.size() - 2, 2, "; ") == 0) {
      std::string blanked;
      std::size_t column = 0, start = 0;
      for (std::size_t end; (end = line.find("; ", start)) != std::string::npos;
           start = end + 2, ++column) {
        const bool measured =
            properties.at(column) == "time REAL" || properties.at(column) == "memory REAL";
        blanked += (measured ? "*" : line.substr(start, end - start)) + "; ";
      }
      line = blanked;
    }
    kept << line << '\n';
  }
  return kept.str();
}

TEST_F(BenchCommandTest, ShardsMergeIntoTheWholeRunsLog) {
  const std::string runs =
      "bench problems/pusher_free.xml --planner KPIECE --config "
      "'KPgb=KPIECE:goal_bias=0.3' --runs 3 --time 5 ";
  ASSERT_EQ(kautham(runs + out("whole")).exitCode, 0);
  const CommandRun first = kautham(runs + "--shard 1/2 " + out("shard1"));
  const CommandRun second = kautham(runs + "--shard 2/2 " + out("shard2"));
  ASSERT_EQ(first.exitCode, 0) << first.output;
  ASSERT_EQ(second.exitCode, 0) << second.output;
  // 6 runs: the shards split them 3 and 3, by index, none twice.
  EXPECT_EQ(countFiles(folder / "shard1/runs", ".json"), 3u);
  EXPECT_EQ(countFiles(folder / "shard2/runs", ".json"), 3u);
  EXPECT_TRUE(fs::exists(folder / "shard1/runs/pusher_free/KPIECE/run-0.json"));
  EXPECT_TRUE(fs::exists(folder / "shard2/runs/pusher_free/KPIECE/run-1.json"));

  const CommandRun merge =
      kautham("bench --merge-only " + out("merged") + " '" + (folder / "shard2").string() + "' '" +
              (folder / "shard1").string() + "'");
  ASSERT_EQ(merge.exitCode, 0) << merge.output;
  EXPECT_NE(merge.output.find("merged    6 runs from 2 folders"), std::string::npos)
      << merge.output;
  const std::string whole = test::readFile(folder / "whole/logs/pusher_free.log");
  const std::string merged = test::readFile(folder / "merged/logs/pusher_free.log");
  ASSERT_NE(whole.find("3 runs\n"), std::string::npos) << whole;
  EXPECT_EQ(withoutMeasurements(merged), withoutMeasurements(whole));
  EXPECT_NE(withoutMeasurements(whole),
            withoutMeasurements(test::readFile(folder / "shard1/logs/pusher_free.log")));
}

TEST_F(BenchCommandTest, SecondInvocationResumesWithoutRerunning) {
  ASSERT_EQ(kautham(kFreeRuns + out()).exitCode, 0);
  const fs::path result = folder / "out/runs/pusher_free/KPIECE/run-1.json";
  const std::string before = test::readFile(result);  // its start time tells a rerun apart
  fs::remove(folder / "out/runs/pusher_free/KPIECE/run-0.json");

  const CommandRun again = kautham(kFreeRuns + out());
  ASSERT_EQ(again.exitCode, 0) << again.output;
  EXPECT_NE(again.output.find("runs      2: 1 made now, 1 resumed; 2 solved, 0 failed"),
            std::string::npos)
      << again.output;
  EXPECT_EQ(test::readFile(result), before);
  EXPECT_TRUE(fs::exists(folder / "out/runs/pusher_free/KPIECE/run-0.json"));
  EXPECT_NE(test::readFile(folder / "out/logs/pusher_free.log").find("2 runs\n"),
            std::string::npos);

  // Another setup in the same folder would mix two experiments: refused before any run.
  const CommandRun other = kautham(kFreeRuns + "--seed 7 " + out());
  EXPECT_EQ(other.exitCode, 2) << other.output;
  EXPECT_NE(other.output.find("another setup"), std::string::npos) << other.output;
  EXPECT_EQ(test::readFile(result), before);
}

TEST_F(BenchCommandTest, ResultFileHoldsTheRunAndItsProperties) {
  ASSERT_EQ(kautham(kFreeRuns + "--validate 2 " + out()).exitCode, 0);
  const json result = readJson(folder / "out/runs/pusher_free/KPIECE/run-1.json");
  EXPECT_EQ(result["format"], "kautham-bench-run");
  EXPECT_EQ(result["run"], 1);
  EXPECT_EQ(result["setup"]["seed"], 2);
  EXPECT_EQ(result["setup"]["time_limit"], 5.0);
  EXPECT_EQ(result["status"], "Exact solution");
  EXPECT_FALSE(result["failed"].get<bool>());
  EXPECT_EQ(result["validation"]["successes"], 2);
  const json plan = readJson(folder / "out" / result["plan"]["file"].get<std::string>());
  EXPECT_EQ(plan["seed"], 2);  // the plan is kept for replay
  const json& p = result["properties"];
  EXPECT_EQ(p["solution segments INTEGER"], std::to_string(plan["controls"].size()));
  EXPECT_EQ(p["graph states INTEGER"],
            std::to_string(plan["statistics"]["tree_states"].get<int>()));
  EXPECT_EQ(p["execution success REAL"], "1");
  EXPECT_FALSE(p.contains("particles INTEGER"));            // KPIECE has none
  EXPECT_FALSE(p.contains("motion budget spent BOOLEAN"));  // nor a motion budget
  EXPECT_NE(
      test::readFile(folder / "out/console/pusher_free/KPIECE/run-1.txt").find("solved    yes"),
      std::string::npos);
}

TEST_F(BenchCommandTest, PKpiecesRestartsAreARunProperty) {
  // restart_after 1: every expansion that brings the tree no centimetre nearer starts it afresh.
  ASSERT_EQ(kautham("bench problems/pusher_free.xml --planner p-KPIECE --runs 1 --time 5 "
                    "--set uncertainty=0 --set restart_after=1 " +
                    out())
                .exitCode,
            0);
  const json result = readJson(folder / "out/runs/pusher_free/p-KPIECE/run-0.json");
  const json plan = readJson(folder / "out" / result["plan"]["file"].get<std::string>());
  std::string restarts;
  for (const auto& [key, value] : plan["statistics"]["planner"].items())
    if (key == "restarts") restarts = value.is_string() ? value.get<std::string>() : value.dump();
  ASSERT_FALSE(restarts.empty()) << plan["statistics"].dump();
  EXPECT_EQ(result["properties"]["restarts INTEGER"], restarts);
}

TEST_F(BenchCommandTest, PKpiecesMotionBudgetIsARunProperty) {
  // max_motions 1: the root is the one motion, so the search ends before its first expansion,
  // with time to spare.
  ASSERT_EQ(kautham("bench problems/pusher_free.xml --planner p-KPIECE --runs 1 --time 30 "
                    "--set uncertainty=0 --set max_motions=1 " +
                    out())
                .exitCode,
            0);
  const json result = readJson(folder / "out/runs/pusher_free/p-KPIECE/run-0.json");
  const json& p = result["properties"];
  EXPECT_EQ(p["solved BOOLEAN"], "0");
  EXPECT_EQ(p["graph states INTEGER"], "1");
  EXPECT_EQ(p["motion budget spent BOOLEAN"], "1");
}

TEST_F(BenchCommandTest, AConfigurationsPhysicsReachesItsPlansAndTheirValidation) {
  const fs::path file = folder / "physics.json";
  const std::string problem = (fs::path(KAUTHAM_SOURCE_DIR) / "problems/pusher_free.xml").string();
  const auto spec = [&](const std::string& friction) {
    return "{\"problems\": [\"" + problem +
           "\"],\n \"configs\": [{\"name\": \"slippery\", \"planner\": \"KPIECE\",\n"
           "   \"physics\": {\"friction\": \"" +
           friction +
           "\", \"solverIterations\": 10}}],\n \"runs\": 1, \"time\": 5, "
           "\"validate\": 1}\n";
  };
  test::writeFile(file, spec("-1"));
  const CommandRun refused = kautham("bench --file '" + file.string() + "' " + out());
  EXPECT_EQ(refused.exitCode, 2) << refused.output;
  EXPECT_NE(refused.output.find("configuration slippery (planner KPIECE): --physics friction=-1: "
                                "attribute friction must be non-negative"),
            std::string::npos)
      << refused.output;
  EXPECT_FALSE(fs::exists(folder / "out")) << "nothing may run";

  test::writeFile(file, spec("0.2"));
  const CommandRun run = kautham("bench --file '" + file.string() + "' " + out());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const json result = readJson(folder / "out/runs/pusher_free/slippery/run-0.json");
  const json physics = json::array({"friction=0.2", "solverIterations=10"});
  EXPECT_EQ(result["setup"]["physics"], physics);
  const json plan = readJson(folder / "out" / result["plan"]["file"].get<std::string>());
  EXPECT_EQ(plan["problem"]["physics"], physics);
  const std::string validation =
      test::readFile(folder / "out/console/pusher_free/slippery/run-0.txt");
  EXPECT_NE(validation.find("physics      friction=0.2 solverIterations=10 (the plan's)"),
            std::string::npos)
      << validation;
}

TEST_F(BenchCommandTest, CheckLoadsEverythingAndRunsNothing) {
  const fs::path file = folder / "checked.json";
  const std::string problem = (fs::path(KAUTHAM_SOURCE_DIR) / "problems/pusher_free.xml").string();
  const auto spec = [&](const std::string& parameter) {
    return "{\"name\": \"c\", \"description\": \"KPIECE on the free pusher, to check a check\",\n"
           " \"problems\": [\"" +
           problem + "\"],\n \"configs\": [{\"planner\": \"KPIECE\", \"set\": {\"" + parameter +
           "\": \"0.5\"}}],\n \"runs\": 3, \"time\": 5, \"validate\": 10}\n";
  };
  test::writeFile(file, spec("goal_bias"));
  const CommandRun good = kautham("bench --check --file '" + file.string() + "' " + out());
  EXPECT_EQ(good.exitCode, 0) << good.output;
  EXPECT_NE(good.output.find("about     KPIECE on the free pusher, to check a check"),
            std::string::npos)
      << good.output;
  EXPECT_NE(good.output.find("1 problems x 1 configurations x 3 runs = 3 runs"), std::string::npos)
      << good.output;
  // Three runs of at most 5 s, one at a time; validation is not bounded.
  EXPECT_NE(good.output.find("limits    planning the 3 runs left takes at most about 15 s (their "
                             "time limits, 1 at a time); validation (10 executions of each solved "
                             "plan) comes on top"),
            std::string::npos)
      << good.output;
  EXPECT_NE(good.output.find("nothing run"), std::string::npos) << good.output;
  EXPECT_FALSE(fs::exists(folder / "out")) << "--check may not run or write anything";
  // Two at a time: the last of three 5 s runs may start when the first ends.
  const CommandRun twoJobs =
      kautham("bench --check --jobs 2 --file '" + file.string() + "' " + out());
  EXPECT_EQ(twoJobs.exitCode, 0) << twoJobs.output;
  EXPECT_NE(twoJobs.output.find("takes at most about 10 s"), std::string::npos) << twoJobs.output;
  // The command line replaced the file's configurations: its description is marked so.
  const CommandRun replaced =
      kautham("bench --check --planner RRT --file '" + file.string() + "' " + out());
  EXPECT_EQ(replaced.exitCode, 0) << replaced.output;
  EXPECT_NE(replaced.output.find("(the file's; the command line replaced"), std::string::npos)
      << replaced.output;
  const CommandRun merge = kautham("bench --check --merge-only " + out());
  EXPECT_NE(merge.exitCode, 0) << merge.output;
  EXPECT_NE(merge.output.find("excludes"), std::string::npos) << merge.output;

  test::writeFile(file, spec("no_such_parameter"));
  const CommandRun bad = kautham("bench --check --file '" + file.string() + "' " + out());
  EXPECT_EQ(bad.exitCode, 2) << bad.output;
  EXPECT_NE(bad.output.find("unknown parameter 'no_such_parameter'"), std::string::npos)
      << bad.output;
  EXPECT_FALSE(fs::exists(folder / "out"));
}

TEST_F(BenchCommandTest, AnOutputFolderThatIsAFileExitsTwoBeforeAnyRun) {
  // It failed after the banner with a raw filesystem error (exit 1), and --check passed it.
  const fs::path file = folder / "spec.json";
  test::writeFile(file, "{\"name\": \"f\", \"problems\": [\"" +
                            (fs::path(KAUTHAM_SOURCE_DIR) / "problems/pusher_free.xml").string() +
                            "\"],\n \"configs\": [{\"planner\": \"KPIECE\"}], \"runs\": 1, "
                            "\"time\": 1}\n");
  const fs::path aFile = folder / "afile";
  test::writeFile(aFile, "not a folder\n");
  for (const std::string check : {"", "--check "})
    for (const fs::path& output : {aFile, aFile / "sub"}) {
      const CommandRun run =
          kautham("bench " + check + "--file '" + file.string() + "' -o '" + output.string() + "'");
      EXPECT_EQ(run.exitCode, 2) << run.output;
      EXPECT_NE(run.output.find("-o " + output.string() + ": "), std::string::npos) << run.output;
      EXPECT_EQ(run.output.find("planning"), std::string::npos) << run.output;  // no run started
    }
  EXPECT_EQ(test::readFile(aFile), "not a folder\n");  // left as it was
}

TEST_F(BenchCommandTest, CheckSeesWhatTheOutputFolderAlreadyHolds) {
  // A run made, then checked again: resumed, nothing left; checked with another time limit, its
  // result belongs to another setup, which the campaign would refuse: so does --check.
  const std::string run = "bench problems/pusher_free.xml --planner KPIECE --runs 1 " + out();
  ASSERT_EQ(kautham(run + " --time 1").exitCode, 0);
  const CommandRun same = kautham(run + " --time 1 --check");
  EXPECT_EQ(same.exitCode, 0) << same.output;
  EXPECT_NE(same.output.find("resume    1 of these runs have results in"), std::string::npos)
      << same.output;
  EXPECT_NE(same.output.find("limits    nothing left to run"), std::string::npos) << same.output;
  const CommandRun other = kautham(run + " --time 2 --check");
  EXPECT_EQ(other.exitCode, 2) << other.output;
  EXPECT_NE(other.output.find("made with another setup"), std::string::npos) << other.output;
}

TEST_F(BenchCommandTest, BadInputExitsTwoBeforeAnyRun) {
  const CommandRun missing =
      kautham("bench problems/no_such_problem.xml --planner KPIECE " + out());
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_NE(missing.output.find("problems/no_such_problem.xml"), std::string::npos)
      << missing.output;
  const CommandRun planner = kautham(
      "bench problems/pusher_free.xml problems/pusher_cans_5.xml --planner KPIECE "
      "--planner NoSuchPlanner " +
      out());
  EXPECT_EQ(planner.exitCode, 2);
  EXPECT_NE(planner.output.find("problems/pusher_free.xml, configuration NoSuchPlanner"),
            std::string::npos)
      << planner.output;
  const CommandRun set =
      kautham("bench problems/pusher_free.xml --config 'x=KPIECE:goal_bias=7' " + out());
  EXPECT_EQ(set.exitCode, 2);
  EXPECT_NE(set.output.find("goal_bias"), std::string::npos) << set.output;
  // Settings each valid but not together: the planner's own check, when it is made.
  const CommandRun together = kautham(
      "bench problems/kuka_clutter_5.xml --config "
      "'x=p-KPIECE:particles=0:verify_runs=30:parallel_trees=1:plans=3' --check " +
      out());
  EXPECT_EQ(together.exitCode, 2);
  EXPECT_NE(
      together.output.find("configuration x (planner p-KPIECE): parallel_trees needs plans 1"),
      std::string::npos)
      << together.output;
  // Seeds are 32-bit: the last run's seed (seed + runs - 1) must be one.
  const CommandRun seed = kautham(
      "bench problems/pusher_free.xml --planner KPIECE --seed 4294967295 --runs 2 " + out());
  EXPECT_EQ(seed.exitCode, 2);
  EXPECT_NE(seed.output.find("the last run would plan with seed 4294967296"), std::string::npos)
      << seed.output;
  EXPECT_FALSE(fs::exists(folder / "out")) << "nothing may run";

  const fs::path file = folder / "bad.json";
  test::writeFile(file, "{\n  \"problems\": [\"p.xml\"],\n  \"run\": 3\n}\n");
  const CommandRun typo = kautham("bench --file '" + file.string() + "' " + out());
  EXPECT_EQ(typo.exitCode, 2);
  EXPECT_NE(typo.output.find(file.string() + ":3: unknown key \"run\""), std::string::npos)
      << typo.output;
  // A value out of range is the file's, at its line: not an option the user never gave.
  for (const auto& [entry, message] : std::vector<std::pair<std::string, std::string>>{
           {"\"runs\": 0", "\"runs\" must be a whole number from 1 to 4294967295"},
           {"\"seed\": 0", "\"seed\" must be a whole number from 1 to 4294967295"},
           {"\"threads\": 0", "\"threads\" must be a whole number from 1 to 4096"},
           {"\"time\": -2", "\"time\" must be a positive number of seconds"}}) {
    test::writeFile(file, "{\n  \"problems\": [\"p.xml\"],\n  " + entry + "\n}\n");
    const CommandRun range = kautham("bench --file '" + file.string() + "' " + out());
    EXPECT_EQ(range.exitCode, 2) << range.output;
    EXPECT_NE(range.output.find(file.string() + ":3: " + message), std::string::npos)
        << range.output;
  }
}

TEST_F(BenchCommandTest, FileNamesProblemsRelativeToItself) {
  const CommandRun run = kautham("bench --file bench/tiny.json --jobs 2 " + out());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("2 problems x 2 configurations x 1 runs"), std::string::npos)
      << run.output;
  const json result = readJson(folder / "out/runs/pusher_cans_5/RRT-gb/run-0.json");
  EXPECT_EQ(result["setup"]["problem_file"], "problems/pusher_cans_5.xml");
  EXPECT_EQ(result["setup"]["set"], json::array({"goal_bias=0.1"}));
  const std::string log = test::readFile(folder / "out/logs/pusher_free.log");
  EXPECT_NE(log.find("Experiment tiny/pusher_free\n"), std::string::npos) << log;
  // Each planner's settings: its OMPL parameters, sorted by name, with the run's values.
  EXPECT_NE(log.find("\nKPIECE\n11 common properties\nbad_score_factor = 0.45\n"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("\nRRT-gb\n7 common properties\ngoal_bias = 0.1\n"
                     "intermediate_states = 0\nmax_control_steps = 20\n"),
            std::string::npos)
      << log;
}

/// Starts `kautham ARGUMENTS` from the repository's root with its output in a file.
pid_t startKautham(const std::vector<std::string>& arguments, const fs::path& output) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (chdir(KAUTHAM_SOURCE_DIR) != 0) _exit(127);
    std::FILE* file = std::freopen(output.c_str(), "w", stdout);
    if (file == nullptr || dup2(fileno(stdout), STDERR_FILENO) < 0) _exit(127);
    std::vector<char*> argv{const_cast<char*>(KAUTHAM_BINARY)};
    for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(KAUTHAM_BINARY, argv.data());
    _exit(127);
  }
  return pid;
}

/// The processes whose command line mentions `text` (here: the test's own output folder).
std::vector<pid_t> processesMentioning(const std::string& text) {
  std::vector<pid_t> pids;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmdline = test::readFile(entry.path() / "cmdline");
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    if (cmdline.find(text) != std::string::npos && cmdline.find(" plan ") != std::string::npos)
      pids.push_back(std::stoi(name));
  }
  return pids;
}

/// Waits up to 30 s until `count` of bench's plan children run (a child shows its own command
/// line only once it has exec'd).
std::vector<pid_t> waitForPlanners(const std::string& text, std::size_t count) {
  std::vector<pid_t> pids;
  for (int i = 0; i < 300 && pids.size() < count; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    pids = processesMentioning(text);
  }
  return pids;
}

int waitExitCode(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// kuka_clutter_40 keeps KPIECE busy for many seconds (docs/benchmarks.md): plenty of time to
// interrupt it.
const std::vector<std::string> kLongRun{"bench",     "problems/kuka_clutter_40.xml",
                                        "--planner", "KPIECE",
                                        "--runs",    "2",
                                        "--jobs",    "2",
                                        "--time",    "60"};

TEST_F(BenchCommandTest, InterruptKillsTheRunsAndLeavesNoResult) {
  std::vector<std::string> arguments = kLongRun;
  arguments.insert(arguments.end(), {"-o", (folder / "out").string()});
  const pid_t bench = startKautham(arguments, folder / "bench.txt");
  ASSERT_EQ(waitForPlanners(folder.string(), 2).size(), 2u);
  kill(bench, SIGINT);
  EXPECT_EQ(waitExitCode(bench), 130) << test::readFile(folder / "bench.txt");
  EXPECT_NE(test::readFile(folder / "bench.txt").find("interrupted: 0 of 2 runs done"),
            std::string::npos);
  EXPECT_TRUE(processesMentioning(folder.string()).empty()) << "a planner outlived bench";
  EXPECT_EQ(countFiles(folder / "out/runs", ".json"), 0u);
  EXPECT_EQ(countFiles(folder / "out/plans", ".json"), 0u);
  EXPECT_EQ(countFiles(folder / "out", ".tmp"), 0u);
}

TEST_F(BenchCommandTest, CrashedRunIsRecordedAsFailed) {
  std::vector<std::string> arguments = kLongRun;
  arguments[5] = "1";  // one run
  arguments.insert(arguments.end(), {"-o", (folder / "out").string()});
  const pid_t bench = startKautham(arguments, folder / "bench.txt");
  const std::vector<pid_t> planners = waitForPlanners(folder.string(), 1);
  ASSERT_EQ(planners.size(), 1u);
  kill(planners.front(), SIGSEGV);
  EXPECT_EQ(waitExitCode(bench), 1) << test::readFile(folder / "bench.txt");

  const json result = readJson(folder / "out/runs/kuka_clutter_40/KPIECE/run-0.json");
  EXPECT_EQ(result["status"], "Crash");
  EXPECT_TRUE(result["failed"].get<bool>());
  EXPECT_EQ(result["plan"]["signal"], SIGSEGV);
  EXPECT_EQ(result["properties"]["status ENUM"], "7");
  EXPECT_EQ(result["properties"]["solved BOOLEAN"], "0");
  const std::string log = test::readFile(folder / "out/logs/kuka_clutter_40.log");
  EXPECT_NE(log.find("1 runs\n"), std::string::npos) << log;
}

}  // namespace
}  // namespace kautham::apps
