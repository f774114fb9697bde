// `kautham check` on the shipped dense scenes: what the arm overlaps at the pre-grasp.

#include <string>

#include <gtest/gtest.h>

#include "apps/CommandTestSupport.h"

namespace kautham::apps {
namespace {

using test::CommandRun;
using test::kautham;

TEST(CheckCommandTest, SaysWhichObjectsTheArmOverlapsAtThePreGrasp) {
  // kuka_clutter_20: every arm pose at the pre-grasp touches can1 (between the fingers) and
  // can3 (where the wrist is): a plan must move both.
  const CommandRun dense = kautham("check problems/kuka_clutter_20.xml");
  ASSERT_EQ(dense.exitCode, 0) << dense.output;
  const std::size_t line = dense.output.find("at goal     ");
  ASSERT_NE(line, std::string::npos) << dense.output;
  const std::string atGoal = dense.output.substr(line, dense.output.find('\n', line) - line);
  EXPECT_NE(atGoal.find(" 0 touch nothing in the start scene"), std::string::npos) << atGoal;
  EXPECT_NE(atGoal.find("can1 "), std::string::npos) << atGoal;
  EXPECT_NE(atGoal.find("can3 "), std::string::npos) << atGoal;
  // yumi_clutter_5's pre-grasp is free: no object is named.
  const CommandRun open = kautham("check problems/yumi_clutter_5.xml");
  ASSERT_EQ(open.exitCode, 0) << open.output;
  EXPECT_NE(open.output.find("at goal     "), std::string::npos) << open.output;
  EXPECT_EQ(open.output.find("objects touched"), std::string::npos) << open.output;
}

}  // namespace
}  // namespace kautham::apps
