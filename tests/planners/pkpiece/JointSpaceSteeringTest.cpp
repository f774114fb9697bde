// The kinematic goal steering's motions, run in the real physics of the shipped dense scenes
// with the real KUKA and YuMi: they end where they aim.

#include <gtest/gtest.h>

#include "TestPaths.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/planners/pkpiece/JointSpaceSteering.h"
#include "kautham/planners/pkpiece/MotionEvaluator.h"

namespace kautham::planners {
namespace {

/// Steers the gripper from the start to `offset` away, keeping its start orientation, and
/// runs the motion: it ends within 1 cm of its aim, turned less than 0.05 rad.
void expectTheMotionEndsAtItsAim(const std::string& problemFile, const Eigen::Vector3d& offset) {
  const core::Problem problem = core::loadProblem(test::repoFile(problemFile));
  physics::PlanningContext context(problem, 0, physics::PropagationSettings{});
  MotionEvaluator evaluator(context, 0.0);
  const JointSpaceSteering steering(context);
  const std::vector<double>& start = context.startState();
  const physics::WorldLayout& layout = context.layout();
  const Eigen::Vector3d aim = layout.goalLinkPosition(start.data()) + offset;
  const Eigen::Matrix3d turn = layout.goalLinkOrientation(start.data());
  const std::optional<NominalMotion> motion = steering.towards(start.data(), aim, turn, 0.0);
  ASSERT_TRUE(motion.has_value()) << problemFile;
  for (double u : motion->control) EXPECT_LE(std::abs(u), 1.0);
  const NominalRun run = evaluator.runNominal(start.data(), motion->control.data(), motion->steps);
  ASSERT_EQ(run.steps, motion->steps) << problemFile << ": the motion touched something";
  EXPECT_LT((layout.goalLinkPosition(run.end.data()) - aim).norm(), 0.01) << problemFile;
  const Eigen::AngleAxisd error(layout.goalLinkOrientation(run.end.data()) * turn.transpose());
  EXPECT_LT(error.angle(), 0.05) << problemFile;
}

TEST(JointSpaceSteeringTest, CarriesTheKukasGripperToItsAim) {
  expectTheMotionEndsAtItsAim("problems/kuka_clutter_10.xml", {0.05, 0.05, 0.08});
}

TEST(JointSpaceSteeringTest, CarriesTheYumisGripperToItsAim) {
  expectTheMotionEndsAtItsAim("problems/yumi_clutter_10.xml", {-0.05, 0.05, 0.08});
}

TEST(JointSpaceSteeringTest, HoldsTheLinkBelowTheSpeedAsked) {
  const core::Problem problem = core::loadProblem(test::repoFile("problems/yumi_clutter_10.xml"));
  physics::PlanningContext context(problem, 0, physics::PropagationSettings{});
  const JointSpaceSteering steering(context);
  const std::vector<double>& start = context.startState();
  const physics::WorldLayout& layout = context.layout();
  const Eigen::Vector3d aim = layout.goalLinkPosition(start.data()) + Eigen::Vector3d(0, 0, 0.1);
  const Eigen::Matrix3d turn = layout.goalLinkOrientation(start.data());
  const std::optional<NominalMotion> fast = steering.towards(start.data(), aim, turn, 0.0);
  const std::optional<NominalMotion> slow = steering.towards(start.data(), aim, turn, 0.1);
  ASSERT_TRUE(fast && slow);
  const double step = context.spaceInformation()->getPropagationStepSize();
  EXPECT_GE(slow->steps * step * 0.1, 0.1 - 1e-9);  // 10 cm at 0.1 m/s: a second or more
  EXPECT_GT(slow->steps, fast->steps);
}

}  // namespace
}  // namespace kautham::planners
