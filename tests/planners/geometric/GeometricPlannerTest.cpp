// The geometric planners (issue 12): configuration coordinates, collision checks of the frozen
// scene without physics, inverse kinematics for pose goals, and plans that the physics
// executes, on the real problem files.

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <utility>

#include <gtest/gtest.h>
#include <ompl/base/PlannerData.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/util/Console.h>

#include "TestPaths.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/planners/Solve.h"
#include "kautham/planners/geometric/ComponentPRM.h"
#include "kautham/planners/geometric/GeometricQuery.h"
#include "kautham/planners/geometric/GoalPoseOverlaps.h"

namespace kautham::planners {
namespace {

const bool quietOmpl = [] {
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  return true;
}();

struct Scene {
  explicit Scene(const std::string& file)
      : problem(core::loadProblem(test::repoFile(file))), context(problem, 0, {}), query(context) {}
  core::Problem problem;
  physics::PlanningContext context;
  geometric::GeometricQuery query;
};

TEST(JointSpaceTest, TheStartCoordinatesPlaceTheRobotExactlyWhereThePhysicsStartsIt) {
  Scene scene("problems/kuka_clutter_10.xml");
  const std::vector<double> placed =
      scene.query.checker().stateAt(scene.query.joints().start().data());
  const std::vector<double>& start = scene.context.startState();
  ASSERT_EQ(placed.size(), start.size());
  for (std::size_t i = 0; i < start.size(); ++i) EXPECT_NEAR(placed[i], start[i], 1e-9) << i;
}

TEST(SceneCheckerTest, TheStartIsFreeAndAGripperInsideACanTouchesThatCan) {
  Scene scene("problems/kuka_clutter_10.xml");
  physics::SceneChecker& checker = scene.query.checker();
  EXPECT_FALSE(checker.touchesAt(scene.query.joints().start().data()).any());

  const physics::WorldLayout& layout = scene.context.layout();
  std::size_t can = 0;
  while (layout.bodies[can].name != "can1") ++can;
  physics::PoseTarget inside;
  inside.position = layout.linkPose(scene.context.startState().data(), can).translation();
  inside.approach = Eigen::Vector3d(0, 0, -1);
  inside.tolerance = 0.01;
  inside.angleTolerance = 0.2;
  std::optional<std::vector<double>> c;
  for (int attempt = 0; attempt < 50 && !c; ++attempt) {
    std::vector<double> seed(scene.query.joints().dimension(), 0.1 + 0.016 * attempt);
    c = scene.query.ik().solve(inside, seed);
  }
  ASSERT_TRUE(c) << "no IK solution reaches can1";
  const physics::RobotTouches touches = checker.touchesAt(c->data());
  EXPECT_NE(std::find(touches.bodies.begin(), touches.bodies.end(), static_cast<int>(can)),
            touches.bodies.end());
  // Where would the arm go if nothing blocked? Movable objects are then no obstacles.
  checker.setObstacles(physics::Obstacles::FixedOnly);
  const physics::RobotTouches fixedOnly = checker.touchesAt(c->data());
  EXPECT_EQ(std::find(fixedOnly.bodies.begin(), fixedOnly.bodies.end(), static_cast<int>(can)),
            fixedOnly.bodies.end());
}

TEST(SceneCheckerTest, AnObjectMarginKeepsTheArmFartherFromMovableObjects) {
  // TMP-U's inflation: just clear of a can, the arm is valid; with a 15 mm margin it is not.
  Scene scene("problems/kuka_clutter_10.xml");
  physics::SceneChecker& checker = scene.query.checker();
  const physics::WorldLayout& layout = scene.context.layout();
  std::size_t can = 0;
  while (layout.bodies[can].name != "can1") ++can;
  physics::PoseTarget inside;
  inside.position = layout.linkPose(scene.context.startState().data(), can).translation();
  inside.approach = Eigen::Vector3d(0, 1, 0);  // from the side, as the pre-grasp
  inside.tolerance = 0.01;
  inside.angleTolerance = 0.2;
  std::optional<std::vector<double>> in;
  for (int attempt = 0; attempt < 50 && !in; ++attempt)
    in = scene.query.ik().solve(
        inside, std::vector<double>(scene.query.joints().dimension(), 0.1 + 0.016 * attempt));
  ASSERT_TRUE(in);
  // Bisect the straight line from the start to it: the last configuration that touches nothing.
  const std::vector<double>& start = scene.query.joints().start();
  const auto at = [&](double t) {
    std::vector<double> c(start.size());
    for (std::size_t i = 0; i < c.size(); ++i) c[i] = start[i] + t * ((*in)[i] - start[i]);
    return c;
  };
  ASSERT_FALSE(checker.touchesAt(start.data()).any());
  ASSERT_TRUE(checker.touchesAt(in->data()).any());
  double free = 0.0, touching = 1.0;
  for (int step = 0; step < 30; ++step) {
    const double middle = 0.5 * (free + touching);
    (checker.touchesAt(at(middle).data()).any() ? touching : free) = middle;
  }
  const std::vector<double> justClear = at(free);
  const physics::RobotTouches first = checker.touchesAt(at(touching).data());
  ASSERT_FALSE(checker.touchesAt(justClear.data()).any());
  checker.setObjectMargin(0.015);
  const physics::RobotTouches inflated = checker.touchesAt(justClear.data());
  checker.setObjectMargin(0.0);
  ASSERT_FALSE(first.fixed || first.target) << "the line must first meet a movable object";
  EXPECT_FALSE(inflated.bodies.empty());
  EXPECT_FALSE(inflated.fixed);  // the margin is for movable objects only
}

TEST(SceneCheckerTest, AHeldObjectMovesWithTheGripper) {
  Scene scene("problems/kuka_clutter_10.xml");
  physics::SceneChecker& checker = scene.query.checker();
  const physics::WorldLayout& layout = scene.context.layout();
  std::size_t can = 0;
  while (layout.bodies[can].name != "can1") ++can;
  Eigen::Isometry3d inGripper = Eigen::Isometry3d::Identity();
  inGripper.translation() = Eigen::Vector3d(0, 0, 0.05);
  checker.hold(physics::HeldObject{can, inGripper});
  std::vector<double> c = scene.query.joints().start();
  for (std::size_t i = 0; i < c.size(); ++i) {
    c[i] = std::min(1.0, c[i] + 0.05);
    const std::vector<double> state = checker.stateAt(c.data());
    const Eigen::Isometry3d gripper = scene.query.joints().linkPose(
        scene.query.joints().jointValues(c.data()), scene.query.gripperLink());
    EXPECT_TRUE(layout.linkPose(state.data(), can).isApprox(gripper * inGripper, 1e-9)) << i;
  }
}

TEST(InverseKinematicsTest, SolvesTheSidePreGraspOfTheClutterSceneWithinHalfItsTolerance) {
  Scene scene("problems/kuka_clutter_5.xml");
  const physics::GoalSpec& goal = scene.context.goal().spec();
  physics::PoseTarget target;
  target.position = goal.position;
  target.approach = goal.approach;
  target.levelAxis = goal.levelAxis;
  target.tolerance = 0.5 * goal.tolerance;
  target.angleTolerance = 0.5 * goal.approachTolerance;
  int solved = 0;
  std::mt19937 random(7);  // random seeds, as the goal sampler uses
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int attempt = 0; attempt < 40; ++attempt) {
    std::vector<double> seed(scene.query.joints().dimension());
    for (double& value : seed) value = uniform(random);
    const auto c = scene.query.ik().solve(target, seed);
    if (!c) continue;
    ++solved;
    const auto [position, angle] = scene.query.ik().errors(target, *c);
    EXPECT_LE(position, target.tolerance);
    EXPECT_LE(angle, target.angleTolerance);
    const std::vector<double> state = scene.query.checker().stateAt(c->data());
    EXPECT_LE(scene.context.goal().distance(state.data()), 0.5 * goal.tolerance + 1e-9);
  }
  EXPECT_GE(solved, 3);  // a 7-joint arm from random seeds: about one in five converges
}

TEST(GoalPoseOverlapsTest, TheDenseScenesAskTheArmToMoveMoreThanTheFreeSpacesBlocker) {
  // kuka_clutter_20: can1 stands in the free space between the fingers, and can3, 11 cm
  // behind it, where the wrist is at the pre-grasp: every arm pose touches both.
  Scene dense("problems/kuka_clutter_20.xml");
  const geometric::GoalPoseOverlaps overlaps = geometric::goalPoseOverlaps(dense.context);
  ASSERT_GT(overlaps.poses, 0);
  EXPECT_EQ(overlaps.touchFree, 0);
  std::map<std::string, int> touched(overlaps.objects.begin(), overlaps.objects.end());
  EXPECT_EQ(touched["can1"], overlaps.poses);
  EXPECT_EQ(touched["can3"], overlaps.poses);
  for (std::size_t i = 1; i < overlaps.objects.size(); ++i)
    EXPECT_GE(overlaps.objects[i - 1].second, overlaps.objects[i].second);
  // yumi_clutter_5 leaves the pre-grasp free; the answer is the same every time.
  Scene open("problems/yumi_clutter_5.xml");
  const geometric::GoalPoseOverlaps free = geometric::goalPoseOverlaps(open.context);
  ASSERT_GT(free.poses, 0);
  EXPECT_EQ(free.touchFree, free.poses);
  EXPECT_TRUE(free.objects.empty());
  EXPECT_EQ(geometric::goalPoseOverlaps(open.context).poses, free.poses);
  // A configuration goal (Kautham's <Goal>) has no pose to check.
  Scene configuration("problems/kautham/kuka_table.xml");
  EXPECT_EQ(geometric::goalPoseOverlaps(configuration.context).poses, 0);
}

struct Planned {
  PlanOutcome outcome;
  physics::ReplayResult replay;
};

Planned plan(const std::string& file, const std::string& planner, std::uint32_t seed) {
  const core::Problem problem = core::loadProblem(test::repoFile(file));
  const PlanRequest request =
      makeRequest(problem, planner, {{"time_limit", "60"}}, seedRandomness(seed));
  physics::PlanningContext context(problem, 0, request.propagation());
  Planned run;
  run.outcome = solve(context, request);
  run.replay = physics::replay(context, run.outcome.controls);
  return run;
}

// Kautham's omplPRM tries edges only between components; so does our PRM. Its roadmap is then a
// forest: every edge joined two components, so there are fewer edges than vertices.
TEST(ComponentPRMTest, EveryEdgeJoinsTwoComponentsSoTheRoadmapIsAForest) {
  Scene scene("problems/kautham/kuka_table_rrtconnect.xml");
  const ompl::base::SpaceInformationPtr& si = scene.query.spaceInformation();
  auto pdef = std::make_shared<ompl::base::ProblemDefinition>(si);
  ompl::base::ScopedState<> start(si->getStateSpace());
  for (std::size_t i = 0; i < si->getStateDimension(); ++i)
    start[i] = scene.query.joints().start()[i];
  pdef->addStartState(start);
  pdef->setGoal(scene.query.problemGoal());
  geometric::ComponentPRM prm(si);
  prm.setProblemDefinition(pdef);
  prm.setup();
  for (int round = 0; round < 200 && prm.milestoneCount() < 40; ++round) prm.growRoadmap(0.05);
  ompl::base::PlannerData data(si);
  prm.getPlannerData(data);
  ASSERT_GE(data.numVertices(), 40u);
  std::set<std::pair<unsigned, unsigned>> edges;
  for (unsigned v = 0; v < data.numVertices(); ++v) {
    std::vector<unsigned> out;
    data.getEdges(v, out);
    for (unsigned w : out) edges.insert({std::min(v, w), std::max(v, w)});
  }
  EXPECT_GT(edges.size(), 0u);
  EXPECT_LT(edges.size(), data.numVertices());
}

TEST(GeometricPlannerTest, RRTConnectSolvesAConfigurationQueryOfTheKukaAtTheTable) {
  const Planned run = plan("problems/kautham/kuka_table_rrtconnect.xml", "RRTConnect", 1);
  ASSERT_TRUE(run.outcome.solved);
  EXPECT_TRUE(run.replay.reachedGoal);
  EXPECT_EQ(run.replay.firstViolation, physics::Violation::None);
  // It ends on the goal configuration, not at the tolerance's edge.
  EXPECT_LT(run.replay.finalGoalDistance, 0.01);
  EXPECT_GT(run.outcome.tree.endEffector.size(), 1u);
}

TEST(GeometricPlannerTest, TheProblemFilesOwnKauthamNameRunsThroughTheRequest) {
  const core::Problem problem =
      core::loadProblem(test::repoFile("problems/kautham/kuka_table_rrtconnect.xml"));
  EXPECT_EQ(problem.planner.name, "omplRRTConnect");
  const PlanRequest request = makeRequest(problem, std::string("RRTConnect"), {}, 1);
  EXPECT_DOUBLE_EQ(request.parameters.real("range"), 0.1);  // Kautham's "Range"
}

TEST(GeometricPlannerTest, PlannersReachAPoseGoalByInverseKinematicsAndThePhysicsExecutesIt) {
  for (const std::string planner : {"PRM", "RRTstar"}) {
    SCOPED_TRACE(planner);
    const Planned run = plan("problems/yumi_cans_5.xml", planner, 1);
    ASSERT_TRUE(run.outcome.solved);
    EXPECT_TRUE(run.replay.reachedGoal);
  }
}

TEST(GeometricPlannerTest, AFixedSeedGivesTheSamePlan) {
  const Planned a = plan("problems/yumi_cans_5.xml", "RRTConnect", 3);
  const Planned b = plan("problems/yumi_cans_5.xml", "RRTConnect", 3);
  ASSERT_EQ(a.outcome.controls.size(), b.outcome.controls.size());
  for (std::size_t i = 0; i < a.outcome.controls.size(); ++i) {
    EXPECT_EQ(a.outcome.controls[i].values, b.outcome.controls[i].values) << i;
    EXPECT_EQ(a.outcome.controls[i].steps, b.outcome.controls[i].steps) << i;
  }
}

}  // namespace
}  // namespace kautham::planners
