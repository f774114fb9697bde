// A candidate's particle verdict cut after one of its recorded steps.

#include <gtest/gtest.h>

#include "kautham/planners/pkpiece/ParticleVerdict.h"

namespace kautham::planners {
namespace {

/// Four particles recorded after steps {a, b}: 0 valid throughout, in the goal at b only;
/// 1 invalid before b; 2 invalid before a; 3 valid throughout, in the goal at a and b, but
/// its objects moved too far by b.
ParticleVerdict fourParticles() {
  ParticleVerdict v;
  v.particles = 4;
  v.stateValidity = 0.5;
  v.interaction = 0.75;
  v.goal = 0.25;
  const std::vector<double> atA{1.0};
  const std::vector<double> atB{2.0};
  const std::vector<double> dead{9.0};
  v.ends = {atB, dead, dead, atB};
  v.endValid = {1, 0, 0, 1};
  v.endInteractionOk = {1, 1, 1, 0};
  v.endInGoal = {1, 0, 0, 0};
  v.recorded = {{atA, atB}, {atA}, {}, {atA, atB}};
  v.recordedInGoal = {{0, 1}, {0}, {}, {1, 0}};
  v.recordedInteractionOk = {{1, 1}, {1}, {}, {1, 0}};
  return v;
}

TEST(ParticleVerdictTest, InGoalAtCountsParticlesRecordedInTheirGoal) {
  const ParticleVerdict v = fourParticles();
  EXPECT_EQ(v.inGoalAt(0), 1u);  // particle 3
  EXPECT_EQ(v.inGoalAt(1), 1u);  // particle 0
  EXPECT_EQ(v.inGoalAt(2), 0u);  // nobody recorded a third state
}

TEST(ParticleVerdictTest, CutAtJudgesEachParticleAsItWasAtTheCut) {
  const ParticleVerdict cut = fourParticles().cutAt(0);
  // Particles 0, 1 and 3 were valid after step a; particle 2 was not.
  EXPECT_DOUBLE_EQ(cut.stateValidity, 0.75);
  // At a, 0, 1 and 3 had moved the objects within d; 2 is judged by where it ended (ok).
  EXPECT_DOUBLE_EQ(cut.interaction, 1.0);
  EXPECT_DOUBLE_EQ(cut.goal, 0.25);
  EXPECT_DOUBLE_EQ(cut.belief(), 0.75);
  // The valid ones end at their state after a, the invalid one where it stopped.
  EXPECT_EQ(cut.ends[0], std::vector<double>{1.0});
  EXPECT_EQ(cut.ends[1], std::vector<double>{1.0});
  EXPECT_EQ(cut.ends[2], std::vector<double>{9.0});
  // Records after the cut are gone.
  for (const auto& r : cut.recorded) EXPECT_LE(r.size(), 1u);
  EXPECT_EQ(cut.recordedInGoal[0].size(), 1u);
}

TEST(ParticleVerdictTest, CutAtTheLastRecordKeepsTheFullVerdict) {
  const ParticleVerdict full = fourParticles();
  const ParticleVerdict cut = full.cutAt(1);
  EXPECT_DOUBLE_EQ(cut.stateValidity, full.stateValidity);
  EXPECT_DOUBLE_EQ(cut.interaction, full.interaction);
  EXPECT_DOUBLE_EQ(cut.goal, full.goal);
  EXPECT_EQ(cut.ends, full.ends);
}

}  // namespace
}  // namespace kautham::planners
