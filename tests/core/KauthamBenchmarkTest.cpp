// Kautham's benchmark files (<Benchmark>): their entries, settings and defaults as Kautham reads
// them, and every mistake refused with the file and the line. On small files each test writes.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "kautham/core/InputError.h"
#include "kautham/core/KauthamBenchmark.h"
#include "kautham/core/ProblemLoader.h"

namespace kautham::core {
namespace {

namespace fs = std::filesystem;

class KauthamBenchmarkTest : public ::testing::Test {
 protected:
  fs::path folder = fs::temp_directory_path() /
                    ("kautham_benchmark_" +
                     std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));

  void SetUp() override {
    fs::create_directories(folder / "problems");
    // An entry's problem: only its planner's <Name> is read here.
    write("problems/rrt.xml",
          "<Problem name=\"a\">\n  <Planner>\n    <Parameters>\n      <Name>omplRRT</Name>\n"
          "    </Parameters>\n  </Planner>\n</Problem>\n");
    write("problems/prm.xml",
          "<Problem name=\"b\">\n  <Planner>\n    <Parameters>\n      <Name>omplPRM</Name>\n"
          "    </Parameters>\n  </Planner>\n</Problem>\n");
  }
  void TearDown() override { fs::remove_all(folder); }

  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(folder / name) << text;
    return folder / name;
  }

  /// The message of the InputError that loading `text` as a benchmark file throws.
  std::string errorOf(const std::string& text) const {
    const fs::path file = write("bench.xml", text);
    try {
      loadKauthamBenchmark(file);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  }
};

TEST_F(KauthamBenchmarkTest, ReadsEntriesFromItsFolderAndTheSettingsKauthamKnows) {
  const fs::path file = write("bench.xml",
                              "<Benchmark Name=\"experiment\">\n"
                              "  <Problem File=\"problems/rrt.xml\" PlannerAlias=\"RRT\"/>\n"
                              "  <Problem File=\"problems/prm.xml\"/>\n"
                              "  <Parameter Name=\"maxTime\" Value=\"3.5\"/>\n"
                              "  <Parameter Name=\"runCount\" Value=\"7\"/>\n"
                              "  <Parameter Name=\"maxMem\" Value=\"4096\"/>\n"
                              "  <Parameter Name=\"filename\" Value=\"result.log\"/>\n"
                              "</Benchmark>\n");
  const KauthamBenchmark b = loadKauthamBenchmark(file);
  EXPECT_EQ(b.name, "experiment");
  ASSERT_EQ(b.entries.size(), 2u);
  EXPECT_EQ(b.entries[0].problem, folder / "problems/rrt.xml");
  EXPECT_EQ(b.entries[0].planner, "omplRRT");
  EXPECT_EQ(b.entries[0].alias, "RRT");
  EXPECT_EQ(b.entries[0].where.line, 2);
  EXPECT_EQ(b.entries[1].planner, "omplPRM");
  EXPECT_EQ(b.entries[1].alias, "");
  EXPECT_DOUBLE_EQ(b.maxTime, 3.5);
  EXPECT_EQ(b.runCount, 7u);
  ASSERT_EQ(b.unused.size(), 2u);
  EXPECT_EQ(b.unused[0].name, "maxMem");
  EXPECT_EQ(b.unused[1].name, "filename");
  EXPECT_EQ(b.unused[1].value, "result.log");
  EXPECT_EQ(b.unused[1].where.line, 7);
}

TEST_F(KauthamBenchmarkTest, SettingsNotGivenAreOmplsRequestDefaultsAsInKautham) {
  const KauthamBenchmark b = loadKauthamBenchmark(
      write("bench.xml", "<Benchmark>\n  <Problem File=\"problems/rrt.xml\"/>\n</Benchmark>\n"));
  EXPECT_DOUBLE_EQ(b.maxTime, 5.0);
  EXPECT_EQ(b.runCount, 100u);
  EXPECT_EQ(b.name, "");
  EXPECT_TRUE(b.unused.empty());
}

TEST_F(KauthamBenchmarkTest, MistakesAreRefusedWithTheFileAndTheLine) {
  const std::string entry = "  <Problem File=\"problems/rrt.xml\"/>\n";
  EXPECT_NE(errorOf("<Benchmark>\n" + entry +
                    "  <Parameter Name=\"maxTim\" Value=\"3\"/>\n"
                    "</Benchmark>\n")
                .find("bench.xml:3: unknown benchmark parameter 'maxTim'; Kautham's are maxTime"),
            std::string::npos);
  EXPECT_NE(errorOf("<Benchmark>\n" + entry +
                    "  <Parameter Name=\"runCount\" Value=\"0\"/>\n"
                    "</Benchmark>\n")
                .find("bench.xml:3: runCount must be a whole number of at least 1"),
            std::string::npos);
  EXPECT_NE(errorOf("<Benchmark>\n" + entry +
                    "  <Parameter Name=\"maxTime\" Value=\"nan\"/>\n"
                    "</Benchmark>\n")
                .find("bench.xml:3:"),
            std::string::npos);
  EXPECT_NE(errorOf("<Benchmark>\n" + entry + "  <Parameter Name=\"maxTime\"/>\n</Benchmark>\n")
                .find("bench.xml:3: <Parameter Name=\"maxTime\"> needs the attribute Value"),
            std::string::npos);
  EXPECT_NE(errorOf("<Benchmark>\n  <Problem File=\"problems/none.xml\"/>\n</Benchmark>\n")
                .find("bench.xml:2: problem file 'problems/none.xml' not found"),
            std::string::npos);
  EXPECT_NE(errorOf("<Benchmark>\n  <Problem Flie=\"problems/rrt.xml\"/>\n</Benchmark>\n")
                .find("bench.xml:2:"),
            std::string::npos);
  EXPECT_NE(errorOf("<Benchmark Name=\"e\">\n</Benchmark>\n")
                .find("bench.xml:1: the benchmark has no <Problem"),
            std::string::npos);
  EXPECT_NE(errorOf("<Benchmark>\n" + entry + "  <Parameter Name=\"runCount\" Value=\"2\"/>\n" +
                    "  <Parameter Name=\"runCount\" Value=\"3\"/>\n</Benchmark>\n")
                .find("bench.xml:4: the benchmark sets 'runCount' twice"),
            std::string::npos);
  // Kautham runs each <Benchmark> of a file in turn; here a file holds one.
  EXPECT_NE(
      errorOf("<Benchmark>\n" + entry + "</Benchmark>\n<Benchmark>\n" + entry + "</Benchmark>\n")
          .find("bench.xml:4: a second <Benchmark>: Kautham runs a file's benchmarks in turn, "
                "`kautham bench --file` runs one; put each in a file of its own"),
      std::string::npos);
  write("problems/none_named.xml", "<Problem name=\"c\">\n  <Planner/>\n</Problem>\n");
  EXPECT_NE(errorOf("<Benchmark>\n  <Problem File=\"problems/none_named.xml\"/>\n</Benchmark>\n")
                .find("none_named.xml:2: a benchmark entry's problem needs "
                      "<Planner><Parameters><Name>"),
            std::string::npos);
}

TEST_F(KauthamBenchmarkTest, LoadingOneAsAProblemSaysHowToRunIt) {
  const fs::path file = write("bench.xml",
                              "<Benchmark>\n  <Problem File=\"problems/rrt.xml\"/>\n"
                              "</Benchmark>\n");
  try {
    loadProblem(file);
    FAIL() << "a benchmark file loaded as a problem";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bench.xml:1: a Kautham benchmark file, not a problem: "
                                         "run it with `kautham bench --file"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace kautham::core
