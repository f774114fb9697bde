// A configuration goal's measure (physics::jointDistance), which the goal and, for such a goal,
// the state space's distance use: a mobile base's heading counts, the short way round. Kautham's
// Tiago RRT, measured by end-effector positions only, grew 78000 states in 10 s and stopped
// beside a table with the wrong heading. On tests/data/kautham_compat/mobile_base.xml (X, Y and
// a continuous turn X3).

#include <cmath>

#include <gtest/gtest.h>

#include "kautham/physics/JointDistance.h"
#include "physics/PhysicsTestSupport.h"

namespace kautham::physics {
namespace {

TEST(JointDistance, AContinuousJointIsMeasuredTheShortWayRound) {
  std::vector<JointInfo> joints(2);
  joints[1].limited = false;
  const double a[] = {0.5, M_PI - 0.1};
  const double b[] = {0.2, -M_PI + 0.1};
  EXPECT_NEAR(jointDistance(joints, a, b, {1.0, 1.0}), std::hypot(0.3, 0.2), 1e-12);
  EXPECT_NEAR(jointDistance(joints, a, b, {10.0, 2.0 * M_PI}), std::hypot(0.03, 0.2 / (2.0 * M_PI)),
              1e-12);
}

TEST(JointDistance, AConfigurationGoalsSpaceMeasuresTheBasesHeading) {
  test::ContextFixture fixture("tests/data/kautham_compat/mobile_base.xml");
  const PlanningContext& context = fixture.context;
  const auto& si = context.spaceInformation();
  const std::size_t joints = context.layout().jointPositionIndex();
  ompl::base::State* a = si->allocState();
  ompl::base::State* b = si->allocState();
  std::copy(context.startState().begin(), context.startState().end(), WorldStateSpace::values(a));
  std::copy(context.startState().begin(), context.startState().end(), WorldStateSpace::values(b));
  // The same place, the heading 0.2 rad apart across the joint's ends: the goal link (the base)
  // is where it was, but the states are 0.2 apart, as they are to the goal.
  WorldStateSpace::values(a)[joints + 2] = M_PI - 0.1;
  WorldStateSpace::values(b)[joints + 2] = -M_PI + 0.1;
  EXPECT_NEAR(si->distance(a, b), 0.2, 1e-9);
  WorldStateSpace::values(b)[joints] += 0.3;
  EXPECT_NEAR(si->distance(a, b), std::hypot(0.3, 0.2), 1e-9);
  si->freeState(a);
  si->freeState(b);
}

}  // namespace
}  // namespace kautham::physics
