// Kautham's files through the `kautham` program (issue 14): planner names, `check --planner`,
// `--package-path`, warnings on stderr only, and the UR5 problem when its description package
// (test data outside the project, ../shared/robots) is there.

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "TestPaths.h"
#include "apps/CommandTestSupport.h"

namespace kautham::apps {
namespace {

namespace fs = std::filesystem;
using test::CommandRun;
using test::kautham;

const std::string kMobileBase = "tests/data/kautham_compat/mobile_base.xml";

TEST(KauthamPlannerNames, CheckAcceptsAGeometricKauthamPlannerAndSaysWhichPlannerToUse) {
  const CommandRun run = kautham("check " + kMobileBase);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("warning: " + kMobileBase +
                            ":24: planner 'omplRRTConnect' is one of Kautham's geometric OMPL "
                            "planners"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("e.g. --planner KPIECE"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("\nok\n"), std::string::npos) << run.output;
}

TEST(KauthamPlannerNames, PlanRejectsItNamingTheLineAndThePlannerToUse) {
  const CommandRun run = kautham("plan " + kMobileBase + " --time 1");
  EXPECT_EQ(run.exitCode, 2) << run.output;
  EXPECT_NE(run.output.find("mobile_base.xml:24: planner 'omplRRTConnect'"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("--planner KPIECE"), std::string::npos) << run.output;
}

TEST(KauthamPlannerNames, CheckTakesPlannerAndNoWarningIsPrintedOnStdout) {
  const CommandRun run =
      test::run("cd '" + std::string(KAUTHAM_SOURCE_DIR) + "' && '" + KAUTHAM_BINARY + "' check " +
                kMobileBase + " --planner RRT 2>/dev/null");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("planner     RRT"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("warning"), std::string::npos) << run.output;
  // check prints where the goal link starts
  EXPECT_NE(run.output.find("start       query0: body at (0.000, 0.500, 0.030)"), std::string::npos)
      << run.output;
}

TEST(PackagePathOption, IsReadAsNameEqualsDirAndCheckedEarly) {
  const CommandRun run = kautham(
      "check tests/data/kautham_compat/mimic_arm.xml --package-path "
      "shared_meshes=tests/data/kautham_compat/ros/shared_meshes");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const CommandRun bad = kautham("check tests/data/kautham_compat/mimic_arm.xml --package-path x");
  EXPECT_EQ(bad.exitCode, 2) << bad.output;
  EXPECT_NE(bad.output.find("--package-path takes NAME=DIR"), std::string::npos) << bad.output;
}

// The UR5 as its authors ship it (package:// paths, DAE visual meshes): problems/ur5_cans.xml.
TEST(Ur5Description, TheUr5ProblemLoadsAndPlansWhenItsPackageIsThere) {
  if (!fs::is_directory(test::repoFile("../shared/robots/ur_description")))
    GTEST_SKIP() << "the UR5 description (test data outside the project) is not at "
                 << test::repoFile("../shared/robots/ur_description");
  const CommandRun check = kautham("check problems/ur5_cans.xml");
  ASSERT_EQ(check.exitCode, 0) << check.output;
  EXPECT_EQ(check.output.find("Polygon"), std::string::npos) << check.output;
  const CommandRun plan = kautham("plan problems/ur5_cans.xml --seed 1 --time 30");
  EXPECT_EQ(plan.exitCode, 0) << plan.output;
  EXPECT_NE(plan.output.find("reaches the goal"), std::string::npos) << plan.output;
}

}  // namespace
}  // namespace kautham::apps
