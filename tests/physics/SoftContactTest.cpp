// Kautham's soft contacts (issue 14): its 'Error Reduction Parameter' and 'Constraint Force
// Mixing' read as the contact spring and damper they make at Kautham's step, and objects that
// rest sunk into the ground on such contacts are not taken for dropped. A Kautham-form problem
// written here: a sphere on a mobile base and a 0.5 kg box on Kautham's ground.

#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "TestPaths.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/core/SoftContact.h"
#include "kautham/physics/PlanningContext.h"
#include "kautham/physics/RestingSink.h"
#include "kautham/physics/World.h"

namespace kautham::physics {
namespace {

namespace fs = std::filesystem;

const char* kBox = R"(<?xml version="1.0"?>
<robot name="box">
  <link name="box">
    <inertial><mass value="0.5"/>
      <inertia ixx="0.000833" iyy="0.000833" izz="0.000833" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
</robot>
)";

/// Kautham's Sphere demos' contact parameters: ERP 0.5, CFM 0.3, 0.03 s steps, 3 contacts.
std::string problemText(const std::string& erp, const std::string& cfm) {
  return R"(<?xml version="1.0"?>
<Problem name="soft">
  <Robot robot="robots/sphere.urdf" scale="1">
    <Limits name="X" min="-0.3" max="0.3"/>
    <Limits name="Y" min="-0.3" max="0.3"/>
    <Home X="0" Y="0" Z="0.1" WX="0" WY="0" WZ="1" TH="0"/>
  </Robot>
  <Obstacle obstacle="box.urdf" scale="1">
    <Home X="1" Y="0" Z="0.05" WX="0" WY="0" WZ="1" TH="0"/>
  </Obstacle>
  <Planner>
    <Parameters>
      <Name>KPIECE</Name>
      <Parameter name="PropagationStepSize">0.03</Parameter>
      <Parameter name="Max Contacts">3</Parameter>
      <Parameter name="Error Reduction Parameter">)" +
         erp + R"(</Parameter>
      <Parameter name="Constraint Force Mixing">)" +
         cfm + R"(</Parameter>
    </Parameters>
    <Queries><Query><Init>0.25 0.5</Init><Goal>0.75 0.5</Goal></Query></Queries>
  </Planner>
</Problem>
)";
}

class SoftContactTest : public ::testing::Test {
 protected:
  // One folder per process: CTest runs these tests in parallel processes, and a shared folder
  // (gtest's random seed, which comes from the clock, named it before) was removed by one
  // test's TearDown while another wrote into it.
  fs::path folder =
      fs::temp_directory_path() / ("kautham_soft_contact_" + std::to_string(::getpid()) + "_" +
                                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
  void SetUp() override {
    fs::create_directories(folder);
    std::ofstream(folder / "box.urdf") << kBox;
  }
  void TearDown() override { fs::remove_all(folder); }

  core::Problem load(const std::string& erp, const std::string& cfm) {
    std::ofstream(folder / "soft.xml") << problemText(erp, cfm);
    return core::loadProblem(folder / "soft.xml", {test::repoFile("models")});
  }
};

std::size_t boxBody(const WorldLayout& layout) {
  for (std::size_t b = 0; b < layout.bodies.size(); ++b)
    if (layout.bodies[b].role != BodyRole::Robot) return b;
  throw std::logic_error("no box");
}

TEST(SoftContactAtStep, KeepsTheSpringAndTheDamper) {
  const core::SoftContact kautham{0.5, 0.3};
  const core::SoftContact here = core::softContactAtStep(kautham, 0.03, 0.01);
  EXPECT_NEAR(core::contactSpring(here, 0.01), core::contactSpring(kautham, 0.03), 1e-9);
  EXPECT_NEAR(core::contactDamper(here), core::contactDamper(kautham), 1e-9);
  EXPECT_NEAR(core::contactSpring(kautham, 0.03), 0.5 / (0.03 * 0.3), 1e-9);  // 55.6 N/m
  // A hard contact has no spring to keep.
  const core::SoftContact hard{0.2, 0.0};
  EXPECT_EQ(core::softContactAtStep(hard, 0.03, 0.01).cfm, 0.0);
}

TEST_F(SoftContactTest, KauthamsErpAndCfmAreReadAtKauthamsStep) {
  const core::Problem problem = load("0.5", "0.3");
  // kp = 0.5 / (0.03 * 0.3) = 55.6 N/m, kd = 0.5 / 0.3 = 1.67 N s/m; at 0.01 s steps:
  // ERP = 0.556 / (0.556 + 1.667) = 0.25, CFM = 1 / 2.222 = 0.45.
  EXPECT_NEAR(problem.physics.erp, 0.25, 1e-9);
  EXPECT_NEAR(problem.physics.cfm, 0.45, 1e-9);
  EXPECT_EQ(problem.physics.maxContacts, 3);
}

TEST_F(SoftContactTest, ABoxRestingSunkInSoftContactsHasNotDropped) {
  const core::Problem problem = load("0.5", "0.3");
  PlanningContext context(problem, 0, PropagationSettings{0.03, 1, 10});
  ASSERT_EQ(context.startViolation(), Violation::None);
  const WorldLayout& layout = context.layout();
  const std::size_t box = boxBody(layout);
  const WorldValidityChecker& checker = context.validityChecker();
  // 0.5 kg on three springs of 55.6 N/m sinks about 4.9 / 167 = 2.9 cm: more than the 2 cm the
  // drop rule allows, so without the resting sink the box would count as fallen through.
  const double sink = checker.restingSink()[box];
  EXPECT_GT(sink, 0.02);
  EXPECT_LT(sink, 0.05);

  std::vector<double> state = context.startState();
  const std::size_t z = box * WorldLayout::kBodyStateSize + WorldLayout::kPosition + 2;
  state[z] -= sink;
  EXPECT_EQ(checker.check(state.data()), Violation::None);
  state[z] -= 0.03;  // deeper than resting: it has fallen through
  EXPECT_EQ(checker.check(state.data()), Violation::ObjectOffSupport);

  // Settling leaves no trace: the start is what a fresh world reads.
  World fresh(problem, problem.queries[0]);
  std::vector<double> freshStart(layout.stateSize());
  fresh.readState(freshStart.data());
  EXPECT_EQ(context.startState(), freshStart);
}

TEST_F(SoftContactTest, StiffContactsAreNotSettled) {
  const core::Problem problem = load("0.8", "1e-5");
  PlanningContext context(problem, 0, PropagationSettings{0.03, 1, 10});
  EXPECT_FALSE(hasSoftContacts(context.world()));
  for (double sink : context.validityChecker().restingSink()) EXPECT_EQ(sink, 0.0);
}

}  // namespace
}  // namespace kautham::physics
