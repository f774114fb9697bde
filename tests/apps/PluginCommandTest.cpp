// Planner plugins as a user loads them: the example plugin (examples/greedy_plugin) is listed,
// plans, validates and benchmarks like a built-in planner; every kind of bad plugin is a clear
// error naming its file, with exit code 2, never a crash.

#include <filesystem>
#include <fstream>
#include <iterator>
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

const std::string kGreedy = KAUTHAM_GREEDY_PLUGIN;

class PluginCommandTest : public test::TemporaryFolderTest {
 protected:
  static std::string quoted(const fs::path& path) { return "'" + path.string() + "'"; }
  static std::string plugin(const fs::path& file) { return " --plugin " + quoted(file); }

  /// Expects `kautham planners` with the plugin to fail with exit 2, naming the file and `why`.
  void expectRejected(const fs::path& file, const std::string& why) {
    const CommandRun run = kautham("planners" + plugin(file));
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_NE(run.output.find("error: " + file.string() + ": planner plugin: "), std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find(why), std::string::npos) << why << "\n" << run.output;
    EXPECT_EQ(run.output.find("Greedy"), std::string::npos) << run.output;  // nothing listed
  }
};

TEST_F(PluginCommandTest, PlannersListsThePluginsPlannerWithItsTypedParameters) {
  const CommandRun run = kautham("planners" + plugin(kGreedy));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  for (const std::string& text :
       {std::string("\nGreedy: example plugin"), "    from plugin " + kGreedy,
        std::string("    samples                  integer  default 4        [1, 100]"),
        std::string("\nKPIECE: OMPL's KPIECE1")})
    EXPECT_NE(run.output.find(text), std::string::npos) << text << "\n" << run.output;
}

TEST_F(PluginCommandTest, PluginPlannerPlansAndItsPlanValidates) {
  const fs::path planFile = folder / "greedy.json";
  const CommandRun run =
      kautham("plan problems/pusher_cans_5.xml --planner Greedy --seed 1 --set samples=3" +
              plugin(kGreedy) + " -o " + quoted(planFile));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("planner   Greedy, seed 1"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("replay    reaches the goal"), std::string::npos) << run.output;
  std::ifstream in(planFile);
  const json plan = json::parse(in);
  EXPECT_EQ(plan["planner"]["name"], "Greedy");
  EXPECT_EQ(plan["planner"]["parameters"]["samples"], "3");
  EXPECT_EQ(plan["planner"]["ompl_parameters"]["samples"], "3");  // reached declareParam

  const CommandRun validate = kautham("validate problems/pusher_cans_5.xml " + quoted(planFile) +
                                      " --runs 3" + plugin(kGreedy));
  EXPECT_EQ(validate.exitCode, 0) << validate.output;
  EXPECT_NE(validate.output.find("success"), std::string::npos) << validate.output;
}

TEST_F(PluginCommandTest, ProblemFileMayNameAPluginPlanner) {
  std::string problem = test::readFile(test::repoFile("problems/pusher_cans_5.xml"));
  problem.replace(problem.find("<Name>KPIECE</Name>"), 19, "<Name>Greedy</Name>");
  const fs::path file = folder / "greedy_cans.xml";
  test::writeFile(file, problem);
  const std::string models = " --model-dir " + quoted(test::repoFile("models"));
  const CommandRun run = kautham("plan " + quoted(file) + " --seed 2 -o " +
                                 quoted(folder / "p.json") + models + plugin(kGreedy));
  EXPECT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("planner   Greedy, seed 2"), std::string::npos) << run.output;
  // Without the plugin the file's planner is unknown: bad input naming the line.
  const CommandRun without = kautham("plan " + quoted(file) + models);
  EXPECT_EQ(without.exitCode, 2) << without.output;
  EXPECT_NE(without.output.find("unknown planner 'Greedy'"), std::string::npos) << without.output;
}

TEST_F(PluginCommandTest, BenchChildrenLoadThePlugin) {
  const CommandRun run = kautham(
      "bench problems/pusher_cans_5.xml --planner Greedy --planner KPIECE --runs 1 "
      "--time 20 --validate 2 -o " +
      quoted(folder / "out") + plugin(kGreedy));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  std::ifstream in(folder / "out/runs/pusher_cans_5/Greedy/run-0.json");
  const json result = json::parse(in);
  EXPECT_TRUE(result["solved"].get<bool>()) << result.dump(1);
  EXPECT_FALSE(result["failed"].get<bool>()) << result.dump(1);
  EXPECT_EQ(result["validation"]["runs"], 2) << result.dump(1);
  const std::string log = test::readFile(folder / "out/logs/pusher_cans_5.log");
  EXPECT_NE(log.find("\nGreedy\n7 common properties\n"), std::string::npos) << log;
  EXPECT_NE(log.find("\nsamples = 4\n"), std::string::npos) << log;
}

TEST_F(PluginCommandTest, PluginPathVariableAndTheFolderNextToTheProgramAreSearched) {
  const fs::path plugins = folder / "plugins";
  fs::create_directories(plugins);
  fs::copy_file(kGreedy, plugins / "libgreedy.so");
  test::writeFile(plugins / "README.txt", "not a plugin, not loaded: only *.so files are");
  const CommandRun byVariable = test::run("KAUTHAM_PLUGIN_PATH=" + quoted(plugins) + " " +
                                          quoted(KAUTHAM_BINARY) + " planners 2>&1");
  EXPECT_EQ(byVariable.exitCode, 0) << byVariable.output;
  EXPECT_NE(byVariable.output.find("from plugin " + (plugins / "libgreedy.so").string()),
            std::string::npos)
      << byVariable.output;

  // An installed layout: PREFIX/bin/kautham finds PREFIX/lib/kautham/plugins/*.so by itself.
  fs::create_directories(folder / "prefix/bin");
  fs::create_directories(folder / "prefix/lib/kautham/plugins");
  fs::copy_file(KAUTHAM_BINARY, folder / "prefix/bin/kautham");
  fs::permissions(folder / "prefix/bin/kautham", fs::perms::owner_exec, fs::perm_options::add);
  fs::copy_file(kGreedy, folder / "prefix/lib/kautham/plugins/libgreedy.so");
  const CommandRun installed = test::run(quoted(folder / "prefix/bin/kautham") + " planners 2>&1");
  EXPECT_EQ(installed.exitCode, 0) << installed.output;
  EXPECT_NE(installed.output.find("\nGreedy: example plugin"), std::string::npos)
      << installed.output;

  const CommandRun missing = test::run("KAUTHAM_PLUGIN_PATH=" + quoted(folder / "nowhere") + " " +
                                       quoted(KAUTHAM_BINARY) + " planners 2>&1");
  EXPECT_EQ(missing.exitCode, 2) << missing.output;
  EXPECT_NE(missing.output.find((folder / "nowhere").string() + ": planner plugin: no such file"),
            std::string::npos)
      << missing.output;
}

TEST_F(PluginCommandTest, TheSamePluginTwiceLoadsOnce) {
  const CommandRun run = kautham("planners" + plugin(kGreedy) + plugin(kGreedy));
  EXPECT_EQ(run.exitCode, 0) << run.output;
}

TEST_F(PluginCommandTest, FileThatIsNotALibrary) {
  const fs::path file = folder / "libnotalibrary.so";
  test::writeFile(file, "these are not the bytes of a shared library\n");
  expectRejected(file, "not a loadable shared library");
  expectRejected(folder / "libmissing.so", "no such file");
}

TEST_F(PluginCommandTest, LibraryCutShort) {
  // dlopen maps the segments the headers name: past the end of a truncated copy the process
  // died of SIGBUS, printing nothing.
  std::ifstream in(kGreedy, std::ios::binary);
  std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  ASSERT_GT(bytes.size(), 5000u);
  const fs::path file = folder / "libtruncated.so";
  test::writeFile(file, bytes.substr(0, 5000));
  expectRejected(file, "not a loadable shared library: the file is cut short (5000 bytes");
}

TEST_F(PluginCommandTest, LibraryWithoutTheRegistrationFunction) {
  expectRejected(KAUTHAM_BAD_PLUGIN_2, "it exports no function kautham_register_planners");
}

TEST_F(PluginCommandTest, PluginBuiltForAnotherAbi) {
  expectRejected(KAUTHAM_BAD_PLUGIN_1,
                 "built for plugin ABI version 42, but this kautham has version 1: rebuild");
}

TEST_F(PluginCommandTest, RegistrationThatThrows) {
  expectRejected(KAUTHAM_BAD_PLUGIN_3,
                 "its registration failed: the plugin's calibration file is missing");
  expectRejected(KAUTHAM_BAD_PLUGIN_5, "parameter 'goal_bias': its default 1.5 is outside [0, 1]");
}

TEST_F(PluginCommandTest, NameOfABuiltInPlanner) {
  expectRejected(KAUTHAM_BAD_PLUGIN_4,
                 "it registers planner 'KPIECE', a name already taken by a built-in planner");
  // Two plugins with one name: the second is refused, naming the first.
  const fs::path copy = folder / "libgreedy_copy.so";
  fs::copy_file(kGreedy, copy);
  const CommandRun run = kautham("planners" + plugin(kGreedy) + plugin(copy));
  EXPECT_EQ(run.exitCode, 2) << run.output;
  EXPECT_NE(run.output.find(copy.string() +
                            ": planner plugin: it registers planner 'Greedy', a "
                            "name already taken by plugin " +
                            kGreedy),
            std::string::npos)
      << run.output;
}

TEST_F(PluginCommandTest, BadPluginStopsEveryCommandBeforeItRuns) {
  for (const std::string& command :
       {std::string("plan problems/pusher_cans_5.xml --seed 1"),
        std::string("check problems/pusher_cans_5.xml"),
        "bench problems/pusher_free.xml --planner KPIECE --runs 1 -o " + quoted(folder / "b")}) {
    const CommandRun run = kautham(command + plugin(KAUTHAM_BAD_PLUGIN_3));
    EXPECT_EQ(run.exitCode, 2) << command << "\n" << run.output;
    EXPECT_NE(run.output.find(std::string(KAUTHAM_BAD_PLUGIN_3)), std::string::npos) << run.output;
  }
  EXPECT_FALSE(fs::exists(folder / "b"));
}

}  // namespace
}  // namespace kautham::apps
