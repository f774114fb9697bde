// A Kautham benchmark file run by `kautham bench --file`, as Kautham runs it: the first entry's
// scene and query, each entry's own planner and parameters (`kautham plan --planner-from`), its
// alias in the OMPL log that Debian's ompl_benchmark_statistics reads. Kautham's own files are
// used too when they are there (../shared/kautham-demos, test data outside the project).

#include <filesystem>
#include <fstream>
#include <string>

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

json readJson(const fs::path& file) {
  std::ifstream in(file);
  return json::parse(in);
}

/// The planner parameters a benchmark run planned with, as its result file records them.
json parametersOfRun(const fs::path& out, const std::string& problem, const std::string& config) {
  return readJson(out / "runs" / problem / config / "run-0.json").at("planner_parameters");
}

/// Two Kautham problem files of one scene (tests/data/kautham_compat/mobile_base.xml) that
/// differ in their <Planner>, and a benchmark file comparing them. They sit beside the original
/// so that its relative model paths resolve; the names are the test's own.
class KauthamBenchmarkCommandTest : public test::TemporaryFolderTest {
 protected:
  fs::path data = test::repoFile("tests/data/kautham_compat");
  std::string stem = "bench_" + folder.filename().string();
  fs::path scene = data / (stem + "_connect.xml");
  fs::path rrt = data / (stem + "_rrt.xml");
  fs::path benchmark = data / (stem + ".xml");

  void SetUp() override {
    test::TemporaryFolderTest::SetUp();
    const std::string base = test::readFile(data / "mobile_base.xml");
    const std::string name = "<Name>omplRRTConnect</Name>";
    std::string connect = base;
    connect.replace(connect.find(name), name.size(),
                    name + "\n      <Parameter name=\"Range\">0.3</Parameter>");
    test::writeFile(scene, connect);
    std::string other = base;
    other.replace(other.find(name), name.size(), "<Name>omplRRT</Name>");
    test::writeFile(rrt, other);
    test::writeFile(benchmark,
                    "<Benchmark Name=\"two planners\">\n"
                    "  <Problem File=\"" +
                        scene.filename().string() +
                        "\" PlannerAlias=\"connect\"/>\n"
                        "  <Problem File=\"" +
                        rrt.filename().string() +
                        "\" PlannerAlias=\"rrt\"/>\n"
                        "  <Parameter Name=\"maxTime\" Value=\"3\"/>\n"
                        "  <Parameter Name=\"runCount\" Value=\"2\"/>\n"
                        "  <Parameter Name=\"filename\" Value=\"result.log\"/>\n"
                        "</Benchmark>\n");
  }
  void TearDown() override {
    for (const fs::path& f : {scene, rrt, benchmark}) fs::remove(f);
    test::TemporaryFolderTest::TearDown();
  }
};

TEST_F(KauthamBenchmarkCommandTest, EachEntryPlansWithItsOwnPlannerOnTheFirstScene) {
  const fs::path out = folder / "out";
  const CommandRun run =
      kautham("bench --file '" + benchmark.string() + "' -o '" + out.string() + "'");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("bench     1 problems x 2 configurations x 2 runs = 4 runs"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("4 made now, 0 resumed"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find(stem + ".xml:1: name 'two planners' is used as 'two_planners'"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find(stem +
                            ".xml:6: Kautham's filename \"result.log\": ignored; the log "
                            "is OUT/logs/" +
                            scene.stem().string() + ".log"),
            std::string::npos)
      << run.output;
  // The entries' own parameters: the scene file's Range is its planner's, not the other's.
  EXPECT_EQ(parametersOfRun(out, scene.stem().string(), "connect").at("range"), "0.3");
  EXPECT_NE(parametersOfRun(out, scene.stem().string(), "rrt").at("range"), "0.3");
  const json setup = readJson(out / "runs" / scene.stem().string() / "rrt/run-0.json").at("setup");
  EXPECT_EQ(setup.at("planner"), "omplRRT");
  EXPECT_EQ(setup.at("planner_file"), rrt.string());
  EXPECT_EQ(setup.at("time_limit"), 3.0);

  const fs::path log = out / "logs" / (scene.stem().string() + ".log");
  const fs::path db = folder / "bench.db";
  const CommandRun statistics = test::run("/usr/bin/ompl_benchmark_statistics '" + log.string() +
                                          "' -d '" + db.string() + "' 2>&1");
  ASSERT_EQ(statistics.exitCode, 0) << statistics.output;
  const CommandRun names =
      test::run("sqlite3 '" + db.string() + "' 'SELECT name FROM plannerConfigs ORDER BY id' 2>&1");
  EXPECT_EQ(names.output, "connect\nrrt\n");
}

TEST_F(KauthamBenchmarkCommandTest, PlanTakesThePlannerOfAnotherFile) {
  const CommandRun run = kautham("plan tests/data/kautham_compat/mobile_base.xml --planner-from '" +
                                 rrt.string() + "' --time 5 --seed 1");
  EXPECT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("planner 'omplRRT' is Kautham's geometric OMPL planner; planned here "
                            "with 'RRT-geometric'"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("planner   RRT-geometric, seed 1"), std::string::npos) << run.output;
  const CommandRun both = kautham(
      "plan tests/data/kautham_compat/mobile_base.xml --planner RRT "
      "--planner-from '" +
      rrt.string() + "'");
  EXPECT_NE(both.exitCode, 0) << both.output;
  EXPECT_NE(both.output.find("--planner excludes --planner-from"), std::string::npos)
      << both.output;
}

TEST_F(KauthamBenchmarkCommandTest, ABadEntryStopsTheBenchBeforeAnyRun) {
  test::writeFile(benchmark, "<Benchmark>\n  <Problem File=\"" + scene.filename().string() +
                                 "\" PlannerAlias=\"same\"/>\n  <Problem File=\"" +
                                 rrt.filename().string() + "\" PlannerAlias=\"same\"/>\n" +
                                 "</Benchmark>\n");
  const fs::path out = folder / "out";
  const CommandRun run =
      kautham("bench --file '" + benchmark.string() + "' -o '" + out.string() + "'");
  EXPECT_EQ(run.exitCode, 2) << run.output;
  EXPECT_NE(run.output.find(stem + ".xml:3: a second entry named 'same'"), std::string::npos)
      << run.output;
  EXPECT_FALSE(fs::exists(out / "runs")) << run.output;
}

TEST(KauthamDemoBenchmarks, KauthamsRrtConnectBenchmarkRunsItsThreeRanges) {
  const fs::path demo = test::repoFile(
      "../shared/kautham-demos/OMPL_geo_demos/Cube-sPassage_R2/benchmarking_RRTconnect.xml");
  if (!fs::exists(demo))
    GTEST_SKIP() << "Kautham's demos (test data outside the project) are not at " << demo;
  const fs::path out = fs::temp_directory_path() / "kautham_demo_benchmark_rrtconnect";
  fs::remove_all(out);
  const CommandRun run =
      kautham("bench --file '" + demo.string() + "' --runs 1 -o '" + out.string() + "'");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const std::string scene = "OMPL_RRTconnect_bigcube-s-passage_R2_0.02";
  EXPECT_EQ(parametersOfRun(out, scene, "RRTconnect_002").at("range"), "0.02");
  EXPECT_EQ(parametersOfRun(out, scene, "RRTconnect_005").at("range"), "0.05");
  EXPECT_EQ(parametersOfRun(out, scene, "RRTconnect_010").at("range"), "0.1");
  EXPECT_EQ(
      readJson(out / "runs" / scene / "RRTconnect_010/run-0.json").at("setup").at("time_limit"),
      1.5);
  fs::remove_all(out);
}

}  // namespace
}  // namespace kautham::apps
