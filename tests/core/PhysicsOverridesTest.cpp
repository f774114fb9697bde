// core::applyPhysicsOverrides: <Physics> attributes set from outside the problem file
// (`kautham plan --physics`), read and checked as the loader reads and checks the file's.

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "TestPaths.h"
#include "kautham/core/PhysicsOverrides.h"
#include "kautham/core/ProblemLoader.h"

namespace kautham::core {
namespace {

/// The message of the std::invalid_argument `apply` throws ("" when it throws none).
std::string errorOf(PhysicsSettings settings, const std::string& assignment) {
  try {
    applyPhysicsOverrides(settings, {assignment});
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(PhysicsOverrides, SetAttributesOverTheFilesInOrder) {
  PhysicsSettings physics = loadProblem(test::repoFile("problems/kuka_clutter_20.xml")).physics;
  ASSERT_EQ(physics.solverIterations, 40);
  ASSERT_DOUBLE_EQ(physics.overRelaxation, 1.3);
  applyPhysicsOverrides(physics, {"overRelaxation=1.7", "solverIterations=20", "sleep=false",
                                  "gravity=0 0 -5", "solverIterations=30"});
  EXPECT_DOUBLE_EQ(physics.overRelaxation, 1.7);
  EXPECT_EQ(physics.solverIterations, 30);  // the later assignment wins
  EXPECT_FALSE(physics.sleep);
  EXPECT_DOUBLE_EQ(physics.gravity.z(), -5.0);
  EXPECT_DOUBLE_EQ(physics.friction, 0.5);  // untouched: the file's
}

TEST(PhysicsOverrides, BadAssignmentsAreRefusedNamingThem) {
  const PhysicsSettings physics;
  EXPECT_EQ(errorOf(physics, "overRelaxation=2"),
            "--physics overRelaxation=2: overRelaxation must be above 0 and below 2 (ODE's "
            "default is 1.3)");
  EXPECT_EQ(errorOf(physics, "solverIterations=2.5"),
            "--physics solverIterations=2.5: expected a whole number, got '2.5'");
  EXPECT_EQ(errorOf(physics, "friction=high"),
            "--physics friction=high: expected a number, got 'high'");
  EXPECT_EQ(errorOf(physics, "friction=-1"),
            "--physics friction=-1: attribute friction must be non-negative");
  EXPECT_EQ(errorOf(physics, "erp=nan"), "--physics erp=nan: expected a number, got 'nan'");
  EXPECT_EQ(errorOf(physics, "gravity=0 0"),
            "--physics gravity=0 0: expected three numbers, "
            "got '0 0'");
  EXPECT_EQ(errorOf(physics, "sleep=maybe"),
            "--physics sleep=maybe: expected true or false, got 'maybe'");
  const std::string unknown = errorOf(physics, "iterations=20");
  EXPECT_NE(unknown.find("--physics iterations=20: expected NAME=VALUE with NAME an attribute of "
                         "<Physics>: "),
            std::string::npos)
      << unknown;
  EXPECT_NE(unknown.find("solverIterations"), std::string::npos) << unknown;
  EXPECT_NE(errorOf(physics, "solverIterations").find("expected NAME=VALUE"), std::string::npos);
}

TEST(PhysicsOverrides, TheLoaderHoldsTheFileToTheSameRules) {
  PhysicsSettings physics;
  EXPECT_EQ(physicsSettingsError(physics), std::nullopt);
  physics.maxContacts = 0;
  EXPECT_EQ(physicsSettingsError(physics), "maxContacts must be in [1, 64]");
  physics.maxContacts = 8;
  physics.stepSize = 0.2;
  EXPECT_EQ(physicsSettingsError(physics),
            "stepSize must be at most 0.1 s for a stable simulation");
}

TEST(PhysicsOverrides, ValuesThatWouldHangOrAbortTheSimulationAreRefused) {
  // A simulated second of settling at 1e-9 s was a billion steps: `kautham plan` hung. ODE
  // aborted the process (an assertion in dxNormalize4) on a gravity of 1e300 m/s^2.
  const PhysicsSettings physics;
  for (const auto& [bad, good, why] : std::vector<std::array<std::string, 3>>{
           {"stepSize=1e-9", "stepSize=0.0001",
            "stepSize must be at least 0.0001 s (a simulated second would take over 10 000 "
            "steps; the shipped problems use 0.01)"},
           {"gravity=0 0 -1e300", "gravity=0 0 -1000",
            "gravity must be at most 1000 m/s^2 in magnitude (the Earth's is 9.81)"}}) {
    EXPECT_EQ(errorOf(physics, bad), "--physics " + bad + ": " + why);
    EXPECT_EQ(errorOf(physics, good), "");
  }
}

}  // namespace
}  // namespace kautham::core
