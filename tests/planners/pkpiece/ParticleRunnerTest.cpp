// ParticleRunner on the real ODE world: a run that ends touching a fixed obstacle is invalid
// there, as an execution is (physics::addFinalContacts), though no step of it started touching.

#include <vector>

#include <gtest/gtest.h>

#include "kautham/physics/Replay.h"
#include "kautham/physics/WorldValidityChecker.h"
#include "kautham/planners/pkpiece/ParticleRunner.h"
#include "physics/PhysicsTestSupport.h"

namespace kautham::planners {
namespace {

/// The pusher driven straight at the wall in front of it for `steps` steps, every state kept.
ParticleJob intoTheWall(physics::PlanningContext& context, unsigned steps) {
  ParticleJob job;
  job.start = context.startState();
  job.control = {0.0, 1.0, 0.0};
  job.steps = steps;
  job.contact = context.world().contactParameters();
  job.targetReference = context.validityChecker().targetStart();
  for (unsigned s = 1; s <= steps; ++s) job.recordAfter.push_back(s);
  return job;
}

TEST(ParticleRunnerTest, ARunThatEndsTouchingAFixedObstacleIsInvalidThere) {
  test::ContextFixture scene("tests/data/pusher_wall.xml");
  // Where the replay of the same control first breaks a rule: its step started from the state
  // before, already touching the wall.
  const physics::ReplayResult replayed = physics::replay(scene.context, {{{0.0, 1.0, 0.0}, 40}});
  ASSERT_EQ(replayed.firstViolation, physics::Violation::RobotTouchedFixed);
  const auto touching = static_cast<unsigned>(replayed.frames.size() - 2);
  ASSERT_GT(touching, 1u);

  ParticleRunner runner(scene.context);
  const ParticleResult endingThere = runner.run(intoTheWall(scene.context, touching));
  EXPECT_FALSE(endingThere.valid);
  EXPECT_EQ(endingThere.recorded.size(), touching - 1);  // the touching state is not kept
  EXPECT_EQ(scene.context.validityChecker().check(endingThere.end.data(),
                                                  scene.context.validityChecker().targetStart()),
            physics::Violation::RobotTouchedFixed);

  // One step short of the wall, the run ends clear of it, every state kept.
  const ParticleResult short1 = runner.run(intoTheWall(scene.context, touching - 1));
  EXPECT_TRUE(short1.valid);
  EXPECT_EQ(short1.recorded.size(), touching - 1);
  EXPECT_EQ(short1.recorded.back(), endingThere.recorded.back());
}

}  // namespace
}  // namespace kautham::planners
