// The sequential test of p-KPIECE's particles (certain_after): a motion whose first m particles
// all succeed is judged by them alone; any failure among them has all n_p run. Real physics,
// real uncertainty sampling, real worker processes.

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "TestPaths.h"
#include "WorkBudget.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/planners/Solve.h"
#include "kautham/planners/pkpiece/MotionEvaluator.h"
#include "kautham/planners/pkpiece/ObjectPoseBelief.h"

namespace kautham::planners {
namespace {

struct Scene {
  core::Problem problem = core::loadProblem(test::repoFile("tests/data/pusher_cans_uncertain.xml"));
  physics::PlanningContext context{problem, 0, physics::PropagationSettings{}};
};

/// Seven particles of `control` held for 40 steps from the scene's start, the first
/// `certainAfter` of them a sequential test.
ParticleRequest request(const Scene& scene, const ObjectPoseBelief& poses,
                        const std::vector<double>& control, unsigned certainAfter) {
  ParticleRequest r;
  r.start = scene.context.startState().data();
  r.control = control.data();
  r.steps = 40;
  r.poses = &poses;
  r.recordAfter = {5, 40};
  r.particles = 7;
  r.certainAfter = certainAfter;
  r.streamSeed = 4321;
  return r;
}

/// The scene with an evaluator that lets an object move at most `maxDisplacement` in a motion,
/// and the scene's initial pose belief.
struct Judging {
  explicit Judging(double maxDisplacement) : evaluator(scene.context, maxDisplacement) {}
  /// Seven particles of `control` (request), the first `certainAfter` a sequential test.
  ParticleVerdict judge(const std::vector<double>& control, unsigned certainAfter) {
    return evaluator.runParticles(request(scene, *poses, control, certainAfter));
  }
  Scene scene;
  MotionEvaluator evaluator;
  std::shared_ptr<const ObjectPoseBelief> poses = ObjectPoseBelief::initial(
      scene.context.layout(), evaluator.sampler(), scene.context.startState().data());
};

TEST(SequentialTestTest, AMotionWhoseFirstParticlesAllSucceedIsJudgedByThemAlone) {
  Judging judging(0.05);
  const std::vector<double> still = {0.0, 0.0, 0.0};  // the pusher stands: nothing can fail
  const ParticleVerdict all = judging.judge(still, 0);
  ASSERT_EQ(all.ends.size(), 7u);
  EXPECT_EQ(all.belief(), 1.0);
  EXPECT_EQ(judging.evaluator.certainEarly(), 0u);

  const ParticleVerdict first = judging.judge(still, 3);
  EXPECT_EQ(first.particles, 3u);
  ASSERT_EQ(first.ends.size(), 3u);
  EXPECT_EQ(first.belief(), 1.0);
  EXPECT_EQ(first.goal, all.goal);  // none of either ends in the goal
  // The same three particles as the first three of all seven, bit for bit.
  for (std::size_t p = 0; p < 3; ++p) EXPECT_EQ(first.ends[p], all.ends[p]) << p;
  EXPECT_EQ(judging.evaluator.particleCount(), 7u + 3u);
  EXPECT_EQ(judging.evaluator.certainEarly(), 1u);
}

TEST(SequentialTestTest, AFailureAmongTheFirstParticlesHasEveryParticleRun) {
  // Any push that moves a can more than 0.1 mm fails the interaction rule.
  Judging judging(0.0001);
  // The first of these pushes whose seven particles all fail, judged in full.
  const std::vector<std::vector<double>> pushes = {
      {0.0, 1.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, -1.0, 0.0}, {-1.0, 0.0, 0.0}, {0.7, 0.7, 0.0}};
  const std::vector<double>* failing = nullptr;
  for (const std::vector<double>& push : pushes)
    if (judging.judge(push, 0).belief() == 0.0) {
      failing = &push;
      break;
    }
  ASSERT_NE(failing, nullptr) << "no push moves a can in every particle";
  const std::uint64_t before = judging.evaluator.particleCount();
  const ParticleVerdict verdict = judging.judge(*failing, 3);
  EXPECT_EQ(verdict.particles, 7u);
  EXPECT_EQ(verdict.ends.size(), 7u);
  EXPECT_EQ(verdict.belief(), 0.0);
  EXPECT_EQ(judging.evaluator.particleCount() - before, 7u);
  EXPECT_EQ(judging.evaluator.certainEarly(), 0u);
}

TEST(SequentialTestTest, WorkersJudgeWithTheSameParticles) {
  Judging judging(0.05);
  const std::vector<double> still = {0.0, 0.0, 0.0};
  const ParticleVerdict alone = judging.judge(still, 3);
  judging.evaluator.useWorkers(2);
  const ParticleVerdict spread = judging.judge(still, 3);
  EXPECT_EQ(spread.particles, alone.particles);
  EXPECT_EQ(spread.ends, alone.ends);
  EXPECT_EQ(judging.evaluator.particleCount(), 6u);
}

std::string property(const PlanOutcome& outcome, const std::string& name) {
  for (const auto& [key, value] : outcome.statistics.plannerProperties)
    if (key == name) return value;
  return "";
}

PlanOutcome plan(std::vector<ParameterOverride> overrides) {
  const core::Problem problem =
      core::loadProblem(test::repoFile("tests/data/pusher_cans_uncertain.xml"));
  const PlanRequest request =
      makeRequest(problem, "p-KPIECE", test::withWorkBudget(overrides), seedRandomness(2));
  physics::PlanningContext context(problem, 0, request.propagation());
  return solve(context, request);
}

TEST(SequentialTestTest, PKpieceEndsJudgementsEarlyTheSameAtAnyThreads) {
  const std::vector<ParameterOverride> small = {
      {"particles", "6"}, {"candidates", "4"}, {"verify_runs", "0"}, {"certain_after", "3"}};
  const PlanOutcome one = plan(small);
  std::vector<ParameterOverride> twoThreads = small;
  twoThreads.push_back({"threads", "2"});
  const PlanOutcome two = plan(twoThreads);
  ASSERT_TRUE(one.solved);
  EXPECT_GT(std::stol(property(one, "certain_early")), 0);
  // Each belief is a product of fractions of 6 particles, or of 3 all successful (1).
  for (double b : one.beliefs) EXPECT_NEAR(b * 6.0, std::round(b * 6.0), 1e-9) << b;
  ASSERT_EQ(one.controls.size(), two.controls.size());
  for (std::size_t i = 0; i < one.controls.size(); ++i)
    EXPECT_EQ(one.controls[i].values, two.controls[i].values) << i;
  EXPECT_EQ(one.beliefs, two.beliefs);
  EXPECT_EQ(property(one, "particles"), property(two, "particles"));
  EXPECT_EQ(property(one, "certain_early"), property(two, "certain_early"));
  // Without the test every judgement runs all 6: none ends early.
  std::vector<ParameterOverride> off = small;
  off.back() = {"certain_after", "0"};
  EXPECT_EQ(property(plan(off), "certain_early"), "0");
}

}  // namespace
}  // namespace kautham::planners
