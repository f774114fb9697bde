// Why a tree does not grow: the validity checker counts the states it rejects, by reason.

#include <gtest/gtest.h>

#include "kautham/physics/WorldLayout.h"
#include "kautham/physics/WorldStateSpace.h"
#include "physics/PhysicsTestSupport.h"

namespace kautham::physics {
namespace {

TEST(RejectionCount, RejectedStatesAreCountedByReasonMostFirst) {
  test::ContextFixture scene("problems/kautham/sphere_cubes.xml");
  const auto& si = scene.context.spaceInformation();
  EXPECT_TRUE(scene.context.rejections().empty());
  ompl::base::State* state = si->allocState();
  double* values = WorldStateSpace::values(state);
  std::copy(scene.state.begin(), scene.state.end(), values);
  EXPECT_TRUE(si->isValid(state));
  // A cube thrown upwards: too fast, three times; then tipped over once.
  const std::size_t cube = scene.body("cube1");
  const std::size_t offset = cube * WorldLayout::kBodyStateSize;
  values[offset + 9] = 5.0;  // vz
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(si->isValid(state));
  values[offset + 9] = 0.0;
  values[offset + 3] = std::cos(0.5);  // qw: turned 1 rad about x
  values[offset + 4] = std::sin(0.5);
  EXPECT_FALSE(si->isValid(state));
  const auto counts = scene.context.rejections();
  ASSERT_EQ(counts.size(), 2u);
  EXPECT_EQ(counts[0].first, Violation::ObjectTooFast);
  EXPECT_EQ(counts[0].second, 3u);
  EXPECT_EQ(counts[1].first, Violation::ObjectTilted);
  EXPECT_EQ(counts[1].second, 1u);
  si->freeState(state);
}

}  // namespace
}  // namespace kautham::physics
