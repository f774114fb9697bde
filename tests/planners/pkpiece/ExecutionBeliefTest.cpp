// A motion's belief once rejected plans' executions ran through it (learn_from_executions).

#include <gtest/gtest.h>

#include "kautham/planners/pkpiece/ExecutionBelief.h"

namespace kautham::planners {
namespace {

TEST(ExecutionBeliefTest, WithoutExecutionsTheParticlesBeliefStands) {
  EXPECT_DOUBLE_EQ(beliefAfterExecutions(0.8, 15, 0, 0), 0.8);
  EXPECT_DOUBLE_EQ(beliefAfterExecutions(1.0, 5, 0, 0), 1.0);
  EXPECT_DOUBLE_EQ(beliefAfterExecutions(0.7, 0, 0, 0), 0.7);  // nothing judged it at all
}

TEST(ExecutionBeliefTest, TheParticlesCountAsTheRunsTheyWere) {
  // 15 particles at 0.8 are 12 successes in 15; 10 executions began it, 4 got through.
  EXPECT_DOUBLE_EQ(beliefAfterExecutions(0.8, 15, 10, 4), (12.0 + 4.0) / 25.0);
}

TEST(ExecutionBeliefTest, AMotionFewParticlesFoundCertainYieldsSooner) {
  // certain_after 5: five particles all succeeded. The same ten executions, half through,
  // weigh more against 5 runs than against the 15 n_p would have been.
  const double fromFive = beliefAfterExecutions(1.0, 5, 10, 5);
  const double fromFifteen = beliefAfterExecutions(1.0, 15, 10, 5);
  EXPECT_DOUBLE_EQ(fromFive, 10.0 / 15.0);
  EXPECT_DOUBLE_EQ(fromFifteen, 20.0 / 25.0);
  EXPECT_LT(fromFive, fromFifteen);
}

TEST(ExecutionBeliefTest, WithoutParticlesTheExecutionsDecide) {
  // pKPV (particles 0): the nominal run's belief of 1 gives way to the executions' rate.
  EXPECT_DOUBLE_EQ(beliefAfterExecutions(1.0, 0, 20, 7), 7.0 / 20.0);
}

TEST(ExecutionBeliefTest, EnoughExecutionsOverruleAnyPrior) {
  const double belief = beliefAfterExecutions(1.0, 15, 10000, 3000);
  EXPECT_NEAR(belief, 0.3, 0.01);
}

}  // namespace
}  // namespace kautham::planners
