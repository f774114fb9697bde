#include <gtest/gtest.h>
#include <ompl/base/ScopedState.h>

#include "TestPaths.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/planners/PlanRequest.h"
#include "kautham/planners/PlannerRegistry.h"

namespace kautham::planners {
namespace {

TEST(PlannerRegistryTest, OffersKpieceAndRrtWithDocumentedParameters) {
  for (const char* name : {"KPIECE", "RRT"}) {
    const PlannerRegistry::Entry* entry = plannerRegistry().find(name);
    ASSERT_NE(entry, nullptr) << name;
    EXPECT_FALSE(entry->summary.empty());
    for (const core::ParameterSpec& spec : entry->parameters) {
      EXPECT_FALSE(spec.description.empty()) << name << "." << spec.name;
      EXPECT_LE(spec.min, spec.defaultValue) << spec.name;
      EXPECT_LE(spec.defaultValue, spec.max) << spec.name;
    }
  }
}

TEST(PlannerRegistryTest, CreatesPlannersOverTheProblemsPhysics) {
  const core::Problem problem = core::loadProblem(test::repoFile("problems/pusher_free.xml"));
  physics::PlanningContext context(problem, 0, {});
  for (const auto* entry : plannerRegistry().entries()) {
    ompl::base::PlannerPtr planner =
        entry->create(plannerRegistry().defaults(entry->name), context);
    ASSERT_TRUE(planner) << entry->name;
    EXPECT_EQ(planner->getSpaceInformation(), context.spaceInformation());
  }
}

TEST(PlannerRegistryTest, KpieceProjectsOnTheEndEffectorWithTheRequestedCells) {
  const core::Problem problem = core::loadProblem(test::repoFile("problems/pusher_free.xml"));
  physics::PlanningContext context(problem, 0, {});
  const PlanRequest request = makeRequest(problem, std::nullopt, {{"cell_size", "0.02"}}, 1);
  ompl::base::PlannerPtr planner =
      plannerRegistry().at("KPIECE").create(request.parameters, context);
  planner->setProblemDefinition(context.problemDefinition());
  planner->setup();  // OMPL sets the state space up again here: our projection must survive it

  const auto projection = context.spaceInformation()->getStateSpace()->getDefaultProjection();
  ASSERT_EQ(projection.get(), &context.projection());
  ASSERT_EQ(projection->getDimension(), 2u);                      // the pusher's workspace is flat
  EXPECT_NEAR(projection->getCellSizes()[0], 0.02 * 0.9, 1e-12);  // workspace x side: 0.9 m
  EXPECT_NEAR(projection->getCellSizes()[1], 0.02 * 0.72, 1e-12);

  ompl::base::ScopedState<> start(context.spaceInformation());
  std::copy(context.startState().begin(), context.startState().end(),
            physics::WorldStateSpace::values(start.get()));
  Eigen::VectorXd projected(2);
  projection->project(start.get(), projected);
  EXPECT_NEAR(projected[0], 0.0, 1e-9);  // the gripper starts at (0, -0.3)
  EXPECT_NEAR(projected[1], -0.3, 1e-9);
}

class RequestTest : public ::testing::Test {
 protected:
  core::Problem problem = core::loadProblem(test::repoFile("problems/pusher_cans_5.xml"));
};

TEST_F(RequestTest, TakesPlannerAndKauthamParametersFromTheFile) {
  const PlanRequest request = makeRequest(problem, std::nullopt, {}, 7);
  EXPECT_EQ(request.planner, "KPIECE");
  EXPECT_EQ(request.seed, 7u);
  EXPECT_DOUBLE_EQ(request.timeLimit(), 60.0);                   // "_Max Planning Time"
  EXPECT_DOUBLE_EQ(request.parameters.real("goal_bias"), 0.05);  // "Goal Bias"
  EXPECT_EQ(request.propagation().maxControlSteps, 20u);         // "Max Control Steps"
}

TEST_F(RequestTest, CommandLineOverridesTheFile) {
  const PlanRequest request =
      makeRequest(problem, std::nullopt, {{"goal_bias", "0.2"}, {"time_limit", "5"}}, 1);
  EXPECT_DOUBLE_EQ(request.parameters.real("goal_bias"), 0.2);
  EXPECT_DOUBLE_EQ(request.timeLimit(), 5.0);
}

TEST_F(RequestTest, AnotherPlannerKeepsTheCommonParametersAndSkipsTheOthers) {
  problem.planner.parameters.push_back({"border_fraction", "0.5", {}});  // KPIECE only
  const PlanRequest request = makeRequest(problem, std::string("RRT"), {}, 1);
  EXPECT_EQ(request.planner, "RRT");
  EXPECT_DOUBLE_EQ(request.timeLimit(), 60.0);
  EXPECT_FALSE(request.parameters.has("border_fraction"));
}

TEST_F(RequestTest, UnknownCommandLineParameterListsTheKnownOnes) {
  try {
    makeRequest(problem, std::nullopt, {{"goal_bais", "0.2"}}, 1);
    FAIL() << "accepted an unknown parameter";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("goal_bais"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("goal_bias"), std::string::npos);
  }
}

TEST_F(RequestTest, BadValueInTheFileNamesItsLine) {
  problem.planner.parameters.push_back({"Goal Bias", "1.5", {problem.file, 42}});
  try {
    makeRequest(problem, std::nullopt, {}, 1);
    FAIL() << "accepted goal bias 1.5";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where().line, 42);
    EXPECT_NE(std::string(e.what()).find("[0, 1]"), std::string::npos) << e.what();
  }
}

TEST_F(RequestTest, UnknownPlannerInTheFileNamesItsLine) {
  problem.planner.name = "NoSuchPlanner";
  try {
    makeRequest(problem, std::nullopt, {}, 1);
    FAIL() << "accepted an unknown planner";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where().line, problem.planner.where.line);
    EXPECT_NE(std::string(e.what()).find("KPIECE"), std::string::npos) << e.what();
  }
}

TEST_F(RequestTest, KauthamGenericParametersAreIgnored) {
  problem.planner.parameters.push_back({"_Speed Factor", "1", {}});
  EXPECT_NO_THROW(makeRequest(problem, std::nullopt, {}, 1));
}

}  // namespace
}  // namespace kautham::planners
