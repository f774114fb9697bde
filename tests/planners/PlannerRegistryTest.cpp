#include <gtest/gtest.h>
#include <ompl/base/ScopedState.h>
#include <ompl/control/planners/kpiece/KPIECE1.h>
#include <ompl/control/planners/rrt/RRT.h>
#include <ompl/util/Console.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "TestPaths.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/planners/PlanRequest.h"
#include "kautham/planners/PlannerEntry.h"
#include "kautham/planners/PlannerRegistry.h"
#include "kautham/planners/Solve.h"
#include "kautham/planners/pkpiece/PKpieceSettings.h"

namespace kautham::planners {
namespace {

TEST(PlannerRegistryTest, OffersTheBuiltInPlanners) {
  std::vector<std::string> names;
  for (const auto* entry : plannerRegistry().entries()) names.push_back(entry->name);
  EXPECT_EQ(names, (std::vector<std::string>{"BITstar", "EST", "EST-geometric", "KPIECE",
                                             "KPIECE-geometric", "LazyRRT", "PDST", "PRM", "RRT",
                                             "RRT-geometric", "RRTConnect", "RRTstar", "SST", "TMP",
                                             "TMP-U", "goal-steering", "o-KPIECE", "p-KPIECE"}));
}

TEST(PlannerRegistryTest, EveryPlannersSpecsAreWellFormed) {
  for (const auto* entry : plannerRegistry().entries()) {
    SCOPED_TRACE(entry->name);
    EXPECT_FALSE(entry->summary.empty());
    EXPECT_NO_THROW(core::checkSpecs(entry->parameters));
    // No planner parameter takes a name of the common ones: one name, one meaning.
    std::vector<core::ParameterSpec> all = commonParameters();
    all.insert(all.end(), entry->parameters.begin(), entry->parameters.end());
    EXPECT_NO_THROW(core::checkSpecs(all));
    for (const core::ParameterSpec& spec : entry->parameters) {
      EXPECT_FALSE(spec.description.empty()) << spec.name;
      EXPECT_LE(spec.min, spec.defaultValue) << spec.name;
      EXPECT_LE(spec.defaultValue, spec.max) << spec.name;
    }
  }
  EXPECT_NO_THROW(core::checkSpecs(commonParameters()));
}

TEST(PlannerRegistryTest, SharedParametersAreDeclaredOnce) {
  // goal_bias and cell_size mean the same in every planner that has them: the same spec but
  // for the default.
  const core::ParameterSpec goalBias = goalBiasParameter(0.0);
  const core::ParameterSpec cellSize = cellSizeParameter();
  for (const auto* entry : plannerRegistry().entries())
    for (const core::ParameterSpec& spec : entry->parameters)
      for (const core::ParameterSpec* shared : {&goalBias, &cellSize})
        if (spec.name == shared->name) {
          EXPECT_EQ(spec.description, shared->description) << entry->name;
          EXPECT_EQ(spec.aliases, shared->aliases) << entry->name;
          EXPECT_EQ(spec.min, shared->min) << entry->name;
          EXPECT_EQ(spec.max, shared->max) << entry->name;
        }
}

TEST(PlannerRegistryTest, PKpieceSettingsComeFromItsParameterTable) {
  const auto& table = PKpieceSettings::parameters();
  EXPECT_EQ(table.specs().size(), plannerRegistry().at("p-KPIECE").parameters.size());
  const PKpieceSettings defaults = table.defaults();
  EXPECT_EQ(defaults.candidates, 5u);
  EXPECT_EQ(defaults.particles, 15u);
  EXPECT_EQ(defaults.displacement, 0.0);  // the problem's maxDisplacement (not 0.3 of its own)
  EXPECT_EQ(defaults.goalBias, 0.2);
  EXPECT_TRUE(defaults.uncertainty);

  // Every field follows its parameter: set each to a value other than its default.
  core::ParameterSet values(table.specs());
  for (const auto& [name, text] :
       std::vector<std::pair<std::string, std::string>>{{"k", "7"},
                                                        {"n_p", "3"},
                                                        {"d", "0.125"},
                                                        {"bias", "0.5"},
                                                        {"f", "2"},
                                                        {"kpiece_selection", "0.25"},
                                                        {"uncertainty", "false"},
                                                        {"goal_confidence", "0.75"},
                                                        {"path_belief", "false"},
                                                        {"robot_spread", "false"},
                                                        {"prune_candidates", "false"},
                                                        {"goal_steering", "false"},
                                                        {"Goal Bias", "0.375"},
                                                        {"border_fraction", "0.625"}})
    values.set(name, text);
  const PKpieceSettings s = table.read(values);
  EXPECT_EQ(s.candidates, 7u);
  EXPECT_EQ(s.particles, 3u);
  EXPECT_EQ(s.displacement, 0.125);
  EXPECT_EQ(s.randomCandidate, 0.5);
  EXPECT_EQ(s.beliefWeight, 2.0);
  EXPECT_EQ(s.kpieceSelection, 0.25);
  EXPECT_FALSE(s.uncertainty);
  EXPECT_EQ(s.goalConfidence, 0.75);
  EXPECT_FALSE(s.pathBelief);
  EXPECT_FALSE(s.robotSpread);
  EXPECT_FALSE(s.pruneCandidates);
  EXPECT_FALSE(s.goalSteering);
  EXPECT_EQ(s.goalBias, 0.375);
  EXPECT_EQ(s.borderFraction, 0.625);
}

TEST(PlannerRegistryTest, EveryParameterReachesOmplsParameterSet) {
  const core::Problem problem = core::loadProblem(test::repoFile("problems/pusher_free.xml"));
  for (const auto* entry : plannerRegistry().entries()) {
    SCOPED_TRACE(entry->name);
    physics::PlanningContext context(problem, 0, {});
    PlanRequest request = makeRequest(problem, entry->name, {{"time_limit", "7"}}, 1);
    ompl::base::PlannerPtr planner = makePlanner(context, request);
    std::map<std::string, std::string> ompl;
    planner->params().getParams(ompl);
    for (const core::ParameterSet* set : {&request.parameters, &request.common})
      for (const core::ParameterSpec& spec : set->specs()) {
        ASSERT_TRUE(ompl.count(spec.name)) << spec.name;
        const std::string& text = ompl.at(spec.name);
        if (spec.type == core::ParameterType::Boolean)
          EXPECT_EQ(text, set->boolean(spec.name) ? "1" : "0") << spec.name;
        else
          EXPECT_DOUBLE_EQ(std::stod(text), set->real(spec.name)) << spec.name;
      }
    EXPECT_EQ(ompl.at("time_limit"), "7");
  }
}

TEST(PlannerRegistryTest, OmplPlannersGetTheValuesExactly) {
  const core::Problem problem = core::loadProblem(test::repoFile("problems/pusher_free.xml"));
  physics::PlanningContext context(problem, 0, {});
  const double bias = 0.1 + 1e-15;  // 17 significant digits must survive the way through OMPL
  const PlanRequest kpieceRequest = makeRequest(problem, "KPIECE",
                                                {{"goal_bias", "0.10000000000000100"},
                                                 {"border_fraction", "0.7"},
                                                 {"max_close_samples", "9"}},
                                                1);
  auto kpiece = makePlanner(context, kpieceRequest);
  const auto* k = kpiece->as<ompl::control::KPIECE1>();
  EXPECT_EQ(k->getGoalBias(), bias);
  EXPECT_EQ(k->getBorderFraction(), 0.7);
  EXPECT_EQ(k->getMaxCloseSamplesCount(), 9u);
  EXPECT_EQ(kpiece->getName(), "KPIECE");

  auto rrt = makePlanner(context, makeRequest(problem, "RRT", {{"intermediate_states", "on"}}, 1));
  EXPECT_TRUE(rrt->as<ompl::control::RRT>()->getIntermediateStates());

  // A parameter set through OMPL after the planner is made changes nothing of ours.
  auto pk = makePlanner(context, makeRequest(problem, "p-KPIECE", {{"candidates", "3"}}, 1));
  std::map<std::string, std::string> before;
  pk->params().getParams(before);
  EXPECT_EQ(before.at("candidates"), "3");
  pk->params().setParam("candidates", "9");
  std::map<std::string, std::string> after;
  pk->params().getParams(after);
  EXPECT_EQ(after.at("candidates"), "3");
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

TEST_F(RequestTest, AValueBeyondADoubleInTheFileIsOutOfRangeAtItsLine) {
  problem.planner.parameters.push_back({"_Max Planning Time", "1e400", {problem.file, 42}});
  try {
    makeRequest(problem, std::nullopt, {}, 1);
    FAIL() << "accepted a time limit of 1e400";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where().line, 42);
    EXPECT_NE(std::string(e.what()).find("parameter 'time_limit' is out of range: 1e400 is "
                                         "beyond the largest number a double holds"),
              std::string::npos)
        << e.what();
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
