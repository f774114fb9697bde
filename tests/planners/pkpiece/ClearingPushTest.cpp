// The clearing push p-KPIECE steers while an object fills the goal's free space, on the real
// kuka_clutter_10 scene (can1 stands on its side pre-grasp) with the real physics.

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "TestPaths.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/planners/pkpiece/ClearingPush.h"
#include "kautham/planners/pkpiece/GoalSteering.h"
#include "kautham/planners/pkpiece/MotionEvaluator.h"

namespace kautham::planners {
namespace {

constexpr double kPitch = 0.45;  // rad, p-KPIECE's default push_pitch
// The push as p-KPIECE does it by default: free space only, and with the corridor 20 cm
// behind the goal point cleared first, pitched 1.2 rad.
const PushSettings kPush{kPitch};
const PushSettings kCorridorPush{kPitch, 0.2, 1.2};

struct ClutterScene {
  core::Problem problem = core::loadProblem(test::repoFile("problems/kuka_clutter_10.xml"));
  physics::PlanningContext context{problem, 0, physics::PropagationSettings{}};

  std::size_t body(const std::string& name) const {
    const auto& bodies = context.layout().bodies;
    const auto found = std::find_if(bodies.begin(), bodies.end(),
                                    [&](const physics::BodyInfo& b) { return b.name == name; });
    EXPECT_NE(found, bodies.end()) << name;
    return static_cast<std::size_t>(found - bodies.begin());
  }
  Eigen::Vector3d position(const std::vector<double>& state, const std::string& name) const {
    return physics::WorldLayout::position(state.data(), body(name));
  }
};

TEST(ClearingPushTest, StartsAboveAStandOffBesideTheBlockerAndLowEnoughNotToTipIt) {
  ClutterScene scene;
  const ClearingPush clearing(scene.context, kPush);
  const std::vector<double>& start = scene.context.startState();
  const std::optional<ClearingPush::Step> step = clearing.next(start.data());
  ASSERT_TRUE(step.has_value());
  EXPECT_FALSE(step->pushing);
  const Eigen::Vector3d can = scene.position(start, "can1");
  // The approach is +y: the stand-off lies across it (x), beyond the free space's half width
  // (6 cm) and the can's radius, and above the cans' tops (0.872 m).
  EXPECT_GT(std::abs(step->waypoint.x() - can.x()), 0.09);
  EXPECT_GT(step->waypoint.z(), 0.872);
  // What remains: down to the push, across the free space and up to the goal.
  EXPECT_GT(step->remaining, 0.3);
}

/// kuka_clutter_10's start with the whole robot carried (every body, unturned) so that its
/// fingertips stand where the default push at can1 starts: its stand-off, lowered to 1.5 cm
/// below the can's centre.
std::vector<double> atTheStandOff(const ClutterScene& scene) {
  const ClearingPush clearing(scene.context, kPush);
  const std::vector<double>& start = scene.context.startState();
  const Eigen::Vector3d above = clearing.next(start.data())->waypoint;
  const Eigen::Vector3d can = scene.position(start, "can1");
  std::vector<double> state = start;
  const physics::WorldLayout& layout = scene.context.layout();
  const Eigen::Vector3d standOff(above.x(), above.y(), can.z() - 0.015);
  const Eigen::Vector3d shift = standOff - layout.goalLinkPosition(state.data());
  for (std::size_t b = 0; b < layout.bodies.size(); ++b)
    if (layout.bodies[b].role == physics::BodyRole::Robot)
      for (int k = 0; k < 3; ++k) state[b * physics::WorldLayout::kBodyStateSize + k] += shift[k];
  return state;
}

TEST(ClearingPushTest, PushesFromBehindTheBlockerAcrossTheApproachLowOnIt) {
  ClutterScene scene;
  const ClearingPush clearing(scene.context, kPush);
  const std::vector<double>& start = scene.context.startState();
  const ClearingPush::Step first = *clearing.next(start.data());
  const Eigen::Vector3d can = scene.position(start, "can1");
  const std::vector<double> state = atTheStandOff(scene);
  const Eigen::Vector3d standOff = scene.context.layout().goalLinkPosition(state.data());
  const std::optional<ClearingPush::Step> push = clearing.next(state.data());
  ASSERT_TRUE(push.has_value());
  EXPECT_TRUE(push->pushing);
  // Across, to the far side of the can's centre, with the fingers' middle (2.5 cm back from
  // the fingertips along the approach) 4.6 cm up the 12.2 cm can (its centre is 6.1 cm up):
  // pushed above 6.6 cm (radius / friction), a can tips before it slides. The gripper points
  // down by the push's pitch, so the wrist rides above the table.
  EXPECT_LT((push->waypoint.x() - can.x()) * (standOff.x() - can.x()), 0.0);
  const Eigen::Vector3d fingers = push->orientation.col(2);
  EXPECT_NEAR(fingers.z(), -std::sin(kPitch), 1e-9);
  EXPECT_NEAR((push->waypoint - 0.025 * fingers).z(), can.z() - 0.015, 1e-9);
  EXPECT_LT(push->remaining, first.remaining);
}

TEST(ClearingPushTest, PushesAsFarBelowTheCentreAsAskedButNotBelowTheWorkspaceFloor) {
  // push_below_centre sets where the fingers' middle meets can1 (centre 0.811 m): 1 cm above
  // the centre when asked; asked 8 cm below it (under the table top), the goal link stays
  // 1.2 cm above the workspace's floor (0.77 m) instead.
  ClutterScene scene;
  const double centre = scene.position(scene.context.startState(), "can1").z();
  const std::vector<double> state = atTheStandOff(scene);
  const ClearingPush higher(scene.context, PushSettings{kPitch, 0.0, 0.0, -0.01});
  const ClearingPush::Step high = *higher.next(state.data());
  ASSERT_TRUE(high.pushing);
  const Eigen::Vector3d fingers = high.orientation.col(2);
  EXPECT_NEAR((high.waypoint - 0.025 * fingers).z(), centre + 0.01, 1e-9);
  const ClearingPush deeper(scene.context, PushSettings{kPitch, 0.0, 0.0, 0.08});
  EXPECT_NEAR(deeper.next(state.data())->waypoint.z(), scene.problem.workspace.min().z() + 0.012,
              1e-9);
}

TEST(ClearingPushTest, BlockedStatesRankBehindClearOnesByWhatRemainsOfThePush) {
  ClutterScene scene;
  MotionEvaluator evaluator(scene.context, 0.3);
  const GoalSteering steering(scene.context, evaluator, true, kPush, false);
  const std::vector<double>& start = scene.context.startState();
  const double blocked = steering.rankDistance(start.data());
  EXPECT_GT(blocked, GoalSteering::kBlockedRank + 0.3);
  std::vector<double> cleared = start;
  cleared[scene.body("can1") * physics::WorldLayout::kBodyStateSize] += 0.2;
  const double clear = steering.rankDistance(cleared.data());
  EXPECT_NEAR(clear, scene.context.goal().searchDistance(cleared.data()), 1e-12);
  EXPECT_LT(clear, blocked);
  // Without the clearing push the rank is the search distance, blocked or not.
  const GoalSteering plain(scene.context, evaluator, false, kPush, false);
  EXPECT_NEAR(plain.rankDistance(start.data()), scene.context.goal().searchDistance(start.data()),
              1e-12);
}

TEST(ClearingPushTest, TheLearningRankMeasuresTheBlockerAcrossWhateverThePushesAngle) {
  // What the push angles learn from (push_angle_generation) must not favour an angle for itself:
  // the rank the goal bias grows by counts the push's length still to go, which a push turned
  // towards the target shortens. The learning rank counts only how far can1 still reaches across
  // into the free space (the approach is +y: across is x).
  ClutterScene scene;
  MotionEvaluator evaluator(scene.context, 0.3);
  PushSettings turnedPush = kPush;
  turnedPush.angleSpread = 0.8;
  const GoalSteering straight(scene.context, evaluator, true, kPush, false);
  GoalSteering turned(scene.context, evaluator, true, turnedPush, false);
  turned.setTree(1);
  const std::vector<double>& start = scene.context.startState();
  EXPECT_GT(std::abs(turned.rankDistance(start.data()) - straight.rankDistance(start.data())),
            0.005);
  const double blocked = straight.learningRank(start.data());
  EXPECT_GT(blocked, GoalSteering::kBlockedRank);
  EXPECT_LT(blocked, GoalSteering::kBlockedRank + 0.2);  // at most the free space's width and can
  EXPECT_DOUBLE_EQ(turned.learningRank(start.data()), blocked);

  const std::size_t can = scene.body("can1") * physics::WorldLayout::kBodyStateSize;
  const auto movedBy = [&](double dx, double dy) {
    std::vector<double> moved = start;
    moved[can] += dx;
    moved[can + 1] += dy;
    return straight.learningRank(moved.data());
  };
  // Moved across, out of the free space by the side it is nearer, it is nearer by as much.
  for (const double across : {0.01, 0.03})
    EXPECT_NEAR(std::min(movedBy(across, 0.0), movedBy(-across, 0.0)), blocked - across, 1e-9);
  EXPECT_NEAR(movedBy(0.0, 0.005), blocked, 1e-9);  // along the approach: no nearer
  // Cleared, it is the search distance, as the rank the goal bias grows by.
  std::vector<double> cleared = start;
  cleared[can] += 0.2;
  EXPECT_NEAR(straight.learningRank(cleared.data()),
              scene.context.goal().searchDistance(cleared.data()), 1e-12);
}

TEST(ClearingPushTest, SteeringHeadsForTheStandOffWhileTheFreeSpaceIsBlocked) {
  ClutterScene scene;
  MotionEvaluator evaluator(scene.context, 0.3);
  const GoalSteering steering(scene.context, evaluator, true, kPush, false);
  const ClearingPush clearing(scene.context, kPush);
  const std::vector<double>& start = scene.context.startState();
  const Eigen::Vector3d waypoint = clearing.next(start.data())->waypoint;
  const std::optional<NominalMotion> motion = steering.towardsGoal(start.data());
  ASSERT_TRUE(motion.has_value());
  const NominalRun run =
      evaluator.runNominal(start.data(), motion->control.data(), motion->steps, false);
  ASSERT_GT(run.steps, 0u);
  const physics::WorldLayout& layout = scene.context.layout();
  const double before = (layout.goalLinkPosition(start.data()) - waypoint).norm();
  const double after = (layout.goalLinkPosition(run.end.data()) - waypoint).norm();
  // One stride (at most 10 cm) closer, nearly all of it.
  EXPECT_LT(after, before - 0.07) << before << " -> " << after;
}

TEST(ClearingPushTest, PushesNoFasterThanItsPushSpeed) {
  // kuka_clutter_10, the real physics: steered by inverse kinematics to can1's stand-off, and
  // from there pushed. At push_speed 0.05 m/s the link goes at most that fast: a motion lasts
  // at most 20 steps of 0.05 s, so the push's stride shortens to 5 cm. At 0.1 m/s it goes
  // faster. (Before the stride followed the speed, both went 10 cm in a second.)
  ClutterScene scene;
  MotionEvaluator evaluator(scene.context, 0.0);
  const GoalSteering steering(scene.context, evaluator, true, kPush, true);
  const ClearingPush clearing(scene.context, kPush);
  std::vector<double> state = scene.context.startState();
  for (int motion = 0; motion < 12 && !clearing.next(state.data())->pushing; ++motion) {
    const std::optional<NominalMotion> steered = steering.towardsGoal(state.data());
    ASSERT_TRUE(steered.has_value()) << "motion " << motion;
    state = evaluator.runNominal(state.data(), steered->control.data(), steered->steps, false).end;
  }
  ASSERT_TRUE(clearing.next(state.data())->pushing);
  const physics::WorldLayout& layout = scene.context.layout();
  const auto linkSpeed = [&](double pushSpeed) {
    const GoalSteering pusher(scene.context, evaluator, true,
                              PushSettings{kPitch, 0.0, 0.0, 0.015, pushSpeed}, true);
    const NominalMotion push = *pusher.towardsGoal(state.data());
    const NominalRun run =
        evaluator.runNominal(state.data(), push.control.data(), push.steps, false);
    EXPECT_EQ(run.steps, push.steps) << "the push at " << pushSpeed << " m/s broke a rule";
    const double travelled =
        (layout.goalLinkPosition(run.end.data()) - layout.goalLinkPosition(state.data())).norm();
    return travelled / (run.steps * scene.context.spaceInformation()->getPropagationStepSize());
  };
  const double slow = linkSpeed(0.05);
  const double fast = linkSpeed(0.1);
  EXPECT_LT(slow, 0.055);
  EXPECT_GT(fast, 1.5 * slow);
}

TEST(ClearingPushTest, ClearsTheCorridorBehindThePreGraspFirstFurthestBack) {
  // kuka_clutter_20: can1 fills the free space and reaches behind the goal point; can3 stands
  // 16 cm behind it, where the wrist is at the pre-grasp (kautham check: every arm pose touches
  // both). Within 0.2 m, can3 is the one furthest back: it goes first.
  const core::Problem problem = core::loadProblem(test::repoFile("problems/kuka_clutter_20.xml"));
  physics::PlanningContext context(problem, 0, physics::PropagationSettings{});
  const auto& bodies = context.layout().bodies;
  const ClearingPush corridor(context, kCorridorPush);
  const std::vector<double>& start = context.startState();
  const std::optional<std::size_t> first = corridor.corridorBlocker(start.data());
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(bodies[*first].name, "can3");
  // The push that clears it points the gripper down steeply, so the wrist passes over can4
  // behind it; without the corridor the free space's can1 is pushed as before.
  const ClearingPush::Step step = *corridor.next(start.data());
  EXPECT_NEAR(step.orientation.col(2).z(), -std::sin(1.2), 1e-9);
  const ClearingPush freeSpaceOnly(context, kPush);
  EXPECT_FALSE(freeSpaceOnly.corridorBlocker(start.data()).has_value());
  EXPECT_NEAR(freeSpaceOnly.next(start.data())->orientation.col(2).z(), -std::sin(kPitch), 1e-9);
}

TEST(ClearingPushTest, TheSteeredPushesClearTheCorridorAndThenTheFreeSpace) {
  // The same scene, the real physics: the gripper steered by inverse kinematics along the
  // clearing's waypoints, motion after motion, clears can3 from the corridor and can1 from the
  // free space, each motion valid all along, and no can tipped on the way.
  const core::Problem problem = core::loadProblem(test::repoFile("problems/kuka_clutter_20.xml"));
  physics::PlanningContext context(problem, 0, physics::PropagationSettings{});
  MotionEvaluator evaluator(context, 0.0);
  const GoalSteering steering(context, evaluator, true, kCorridorPush, true);
  const ClearingPush clearing(context, kCorridorPush);
  std::vector<double> state = context.startState();
  double leastUpright = 1.0;  // the cosine of the largest tilt of any can, after any motion
  std::string mostTilted;
  int motions = 0;
  for (; motions < 16 && clearing.next(state.data()); ++motions) {
    const std::optional<NominalMotion> steered = steering.towardsGoal(state.data());
    ASSERT_TRUE(steered.has_value()) << "motion " << motions;
    const NominalRun run =
        evaluator.runNominal(state.data(), steered->control.data(), steered->steps, false);
    ASSERT_EQ(run.steps, steered->steps) << "motion " << motions << " broke a rule";
    state = run.end;
    for (std::size_t b = 0; b < context.layout().bodies.size(); ++b) {
      if (context.layout().bodies[b].role != physics::BodyRole::Movable) continue;
      const double upright =
          (physics::WorldLayout::orientation(state.data(), b) * Eigen::Vector3d::UnitZ()).z();
      if (upright < leastUpright) {
        leastUpright = upright;
        mostTilted = context.layout().bodies[b].name;
      }
    }
  }
  // Every can stays upright: from the end of can3's push, low, the gripper rises before it
  // goes to can1's stand-off (straight there, its fingers tipped can1 by 6.5 degrees).
  EXPECT_GT(leastUpright, std::cos(4.0 * M_PI / 180.0)) << mostTilted << " tilted";
  EXPECT_FALSE(clearing.next(state.data()).has_value()) << "not clear after " << motions;
  EXPECT_FALSE(context.goal().freeSpaceBlocker(state.data()).has_value());
  EXPECT_EQ(steering.jacobianAims(), 0u);
}

/// yumi_clutter_30 as its file sets the push (level, corridor 15 cm behind the goal point),
/// with the crowded pitch `crowdedPitch`, steered in the real physics along the clearing's
/// waypoints, motion after motion, while it lasts (at most 24 motions): how many motions it
/// took, whether one broke a rule, and where the last valid one ended.
struct SteeredClearing {
  int motions = 0;
  bool brokeARule = false;
  std::vector<double> end;
};

struct Clutter30 {
  core::Problem problem = core::loadProblem(test::repoFile("problems/yumi_clutter_30.xml"));
  physics::PlanningContext context{problem, 0, physics::PropagationSettings{}};
};

PushSettings yumiPush(double crowdedPitch) {
  return PushSettings{0.0, 0.15, 0.0, 0.015, 0.1, crowdedPitch};
}

SteeredClearing steerTheClearing(physics::PlanningContext& context, double crowdedPitch) {
  const PushSettings push = yumiPush(crowdedPitch);
  MotionEvaluator evaluator(context, 0.0);
  const GoalSteering steering(context, evaluator, true, push, true, ApproachSettings{0.0, 0.2});
  const ClearingPush clearing(context, push);
  SteeredClearing result;
  result.end = context.startState();
  for (; result.motions < 24 && clearing.next(result.end.data()); ++result.motions) {
    const std::optional<NominalMotion> steered = steering.towardsGoal(result.end.data());
    if (!steered) break;
    const NominalRun run =
        evaluator.runNominal(result.end.data(), steered->control.data(), steered->steps, false);
    result.end = run.end;
    if (run.steps < steered->steps) {
      result.brokeARule = true;
      return result;
    }
  }
  return result;
}

TEST(ClearingPushTest, AStandOffWithNoRoomForTheLevelGripperIsReachedPitchedDown) {
  // yumi_clutter_30: can2 stands in the corridor behind the pre-grasp, can4 beside it (1 cm
  // apart) and can6 beyond it, 2.4 cm from the level gripper's footprint at can2's far stand-off.
  // Lowered level onto that stand-off, the gripper tips can6. Pitched down 1.2 rad (the
  // crowded pitch), its footprint reaches 4.3 cm back instead of 12: it gets down, and its
  // push clears can2 (and can4 with it) from the corridor, and then can1 from the free space,
  // every motion valid.
  Clutter30 level;
  const SteeredClearing tipped = steerTheClearing(level.context, 0.0);
  EXPECT_TRUE(tipped.brokeARule);
  Clutter30 crowded;
  const SteeredClearing cleared = steerTheClearing(crowded.context, 1.2);
  EXPECT_FALSE(cleared.brokeARule) << "after " << cleared.motions << " motions";
  const ClearingPush clearing(crowded.context, yumiPush(1.2));
  EXPECT_FALSE(clearing.next(cleared.end.data()).has_value());
  EXPECT_FALSE(crowded.context.goal().freeSpaceBlocker(cleared.end.data()).has_value());
}

/// kuka_clutter_30 as its file sets the push (the defaults' pitches and corridor, pushing at
/// 0.2 m/s and moving at 0.5 m/s between pushes), with `slide` (PushSettings::crowdedSlide),
/// steered in the real physics along the clearing's waypoints until can3, the corridor's first
/// blocker, has left the corridor (at most 24 motions): whether a motion broke a rule on the way,
/// and whether can3 left.
struct Can3Cleared {
  bool brokeARule = false;
  physics::Violation rule = physics::Violation::None;  ///< the rule broken, if one was
  std::string brokenBy;                                ///< the object that broke it
  double mostTilted = 0.0;  ///< degrees, the largest tilt of any can at any step on the way
  bool left = false;
};

Can3Cleared steerCan3OutOfTheCorridor(double slide) {
  const core::Problem problem = core::loadProblem(test::repoFile("problems/kuka_clutter_30.xml"));
  physics::PlanningContext context(problem, 0, physics::PropagationSettings{});
  const PushSettings push{kPitch, 0.2, 1.2, 0.015, 0.2, 0.0, slide};
  MotionEvaluator evaluator(context, 0.0);
  const GoalSteering steering(context, evaluator, true, push, true,
                              ApproachSettings{0.05, 0.2, 0.0, 0.0075, 0.5});
  const ClearingPush clearing(context, push);
  const auto& bodies = context.layout().bodies;
  const auto isCan3 = [&](std::optional<std::size_t> body) {
    return body && bodies[*body].name == "can3";
  };
  std::vector<double> state = context.startState();
  Can3Cleared result;
  for (int motion = 0; motion < 24 && isCan3(clearing.corridorBlocker(state.data())); ++motion) {
    const std::optional<NominalMotion> steered = steering.towardsGoal(state.data());
    if (!steered) return result;
    const NominalRun run =
        evaluator.runNominal(state.data(), steered->control.data(), steered->steps, false);
    state = run.end;
    for (const std::vector<double>& s : run.states)
      for (std::size_t b = 0; b < bodies.size(); ++b)
        if (bodies[b].role == physics::BodyRole::Movable) {
          const double up =
              (physics::WorldLayout::orientation(s.data(), b) * Eigen::Vector3d::UnitZ()).z();
          result.mostTilted =
              std::max(result.mostTilted, std::acos(std::min(1.0, up)) * 180.0 / M_PI);
        }
    if (run.steps < steered->steps) {
      result.brokeARule = true;
      result.rule = run.stoppedBy;
      if (run.stoppedOn) result.brokenBy = bodies[*run.stoppedOn].name;
      return result;
    }
  }
  result.left = !isCan3(clearing.corridorBlocker(state.data()));
  return result;
}

TEST(ClearingPushTest, ACrowdedStandOffIsReachedLowFromBehind) {
  // kuka_clutter_30: can3 stands in the corridor 1.7 cm from can21 on one side and 2.1 cm from
  // can6 on the other; the gripper (12 cm wide over the table) has no room beside it. Lowered
  // onto the stand-off, the fingers land on can21's top and tilt it past the scene's limit.
  // With crowded_slide 0.1 the gripper is lowered 10 cm further back, the roomiest point within
  // reach (can7's centre 3.7 cm from its outline there, clear of a can's 3.3 cm radius), and
  // slid in at the push's height; it meets can21 low, where a can slides: can3 leaves the
  // corridor, every motion valid.
  const core::Problem problem = core::loadProblem(test::repoFile("problems/kuka_clutter_30.xml"));
  physics::PlanningContext context(problem, 0, physics::PropagationSettings{});
  const std::vector<double>& start = context.startState();
  const Eigen::Vector3d above =
      ClearingPush(context, PushSettings{kPitch, 0.2, 1.2}).next(start.data())->waypoint;
  const Eigen::Vector3d aboveLanding =
      ClearingPush(context, PushSettings{kPitch, 0.2, 1.2, 0.015, 0.1, 0.0, 0.1})
          .next(start.data())
          ->waypoint;
  // The approach is +y: the landing lies back along -y from the stand-off, across it the same.
  EXPECT_NEAR(aboveLanding.x(), above.x(), 1e-9);
  EXPECT_NEAR(aboveLanding.y(), above.y() - 0.10, 1e-9);

  const Can3Cleared lowered = steerCan3OutOfTheCorridor(0.0);
  EXPECT_TRUE(lowered.brokeARule);
  EXPECT_EQ(lowered.rule, physics::Violation::ObjectTilted);
  EXPECT_EQ(lowered.brokenBy, "can21");
  EXPECT_GT(lowered.mostTilted, 15.0);
  const Can3Cleared slid = steerCan3OutOfTheCorridor(0.1);
  EXPECT_FALSE(slid.brokeARule) << physics::toString(slid.rule) << " on " << slid.brokenBy;
  EXPECT_TRUE(slid.left);
  EXPECT_LT(slid.mostTilted, 10.0);
}

TEST(GoalSteeringTest, AfterASteepPushTheGripperRisesBeforeItTurns) {
  // yumi_clutter_30 cleared with pushes pitched 1.2 rad: the last push ends with the fingertips
  // 1.2 cm above the workspace's floor. Steered straight at the goal from there, turning to the
  // approach's 0.2 rad on the way, the fingertips left the workspace at the first step. The
  // steering first lifts the gripper straight up, still pitched as it is.
  Clutter30 scene;
  const SteeredClearing cleared = steerTheClearing(scene.context, 1.2);
  ASSERT_FALSE(cleared.brokeARule);
  MotionEvaluator evaluator(scene.context, 0.0);
  const GoalSteering steering(scene.context, evaluator, true, yumiPush(1.2), true,
                              ApproachSettings{0.0, 0.2});
  const NominalMotion rise = *steering.towardsGoal(cleared.end.data());
  const NominalRun run =
      evaluator.runNominal(cleared.end.data(), rise.control.data(), rise.steps, false);
  ASSERT_EQ(run.steps, rise.steps);
  const physics::WorldLayout& layout = scene.context.layout();
  const Eigen::Vector3d moved =
      layout.goalLinkPosition(run.end.data()) - layout.goalLinkPosition(cleared.end.data());
  EXPECT_GT(moved.z(), 0.05);
  EXPECT_LT(moved.head<2>().norm(), 0.015);
  EXPECT_GT(-layout.goalLinkOrientation(run.end.data()).col(2).z(), std::sin(1.0));
}

/// A scene steered by GoalSteering (with `approach`, and `push` while something blocks the
/// goal) until the goal is reached: whether it was (within 24 motions, no rule broken), how far
/// off the approach line the goal link strayed during the last motion, and the state it ended
/// in. `throughGoal`: each motion runs to its end, as p-KPIECE runs a steered candidate, not
/// only until it enters the goal.
struct SteeredApproach {
  double offLine = std::numeric_limits<double>::infinity();
  std::vector<double> end;  ///< empty when the goal was not reached
  bool reached() const { return !end.empty(); }
};

SteeredApproach steerToTheGoal(physics::PlanningContext& context,
                               const ApproachSettings& approachSettings,
                               const PushSettings& push = kCorridorPush, bool throughGoal = false) {
  MotionEvaluator evaluator(context, 0.0);
  const GoalSteering steering(context, evaluator, true, push, true, approachSettings);
  const physics::WorkspaceGoal& goal = context.goal();
  const Eigen::Vector3d approach = goal.spec().approach->normalized();
  SteeredApproach result;
  std::vector<double> state = context.startState();
  for (int motion = 0; motion < 24; ++motion) {
    const std::optional<NominalMotion> steered = steering.towardsGoal(state.data());
    if (!steered) return result;
    const NominalRun run =
        evaluator.runNominal(state.data(), steered->control.data(), steered->steps, throughGoal);
    if (run.steps < steered->steps && !run.reachedGoal) return result;
    if (run.reachedGoal) {
      result.offLine = 0.0;
      for (const std::vector<double>& s : run.states) {
        const Eigen::Vector3d fromGoal =
            context.layout().goalLinkPosition(s.data()) - goal.position();
        result.offLine =
            std::max(result.offLine, (fromGoal - fromGoal.dot(approach) * approach).norm());
      }
      result.end = run.end;
      return result;
    }
    state = run.end;
  }
  return result;
}

struct Clutter20 {
  core::Problem problem = core::loadProblem(test::repoFile("problems/kuka_clutter_20.xml"));
  physics::PlanningContext context{problem, 0, physics::PropagationSettings{}};
};

double offLineOfTheLastMove(double finalApproach) {
  Clutter20 scene;
  return steerToTheGoal(scene.context, ApproachSettings{finalApproach}).offLine;
}

TEST(GoalSteeringTest, TheLastMoveGoesStraightInAlongTheApproach) {
  // Once the clearing is done, the link rises, lines up 5 cm behind the goal point, turned as
  // the goal asks, and goes straight in: it stays within 1.5 cm of the approach line all the
  // way in. Steered straight at the goal point from the end of the last push (low, pitched
  // down), the turning gripper swept its fingers forwards and broke a rule on the way.
  const double lined = offLineOfTheLastMove(0.05);
  const double direct = offLineOfTheLastMove(0.0);
  EXPECT_LT(lined, 0.015);
  EXPECT_GT(direct, 0.03);
}

TEST(GoalSteeringTest, TheApproachPitchedDownLiftsTheWristOverTheCansBehind) {
  // At the pre-grasp the KUKA's wrist and forearm reach back over kuka_clutter_20's can4;
  // pitched down by 0.2 rad (the goal allows 0.3), the gripper still reaches the goal, points
  // 0.2 rad below level, and its wrist stands higher than with the level approach.
  Clutter20 level;
  Clutter20 pitched;
  const SteeredApproach flat = steerToTheGoal(level.context, ApproachSettings{0.05});
  const SteeredApproach down = steerToTheGoal(pitched.context, ApproachSettings{0.05, 0.2});
  ASSERT_TRUE(flat.reached());
  ASSERT_TRUE(down.reached());
  const physics::WorldLayout& layout = pitched.context.layout();
  const auto pitchOf = [&layout](const std::vector<double>& state) {
    return -std::asin(layout.goalLinkOrientation(state.data()).col(2).z());
  };
  EXPECT_NEAR(pitchOf(flat.end), 0.0, 0.05);
  EXPECT_NEAR(pitchOf(down.end), 0.2, 0.05);
  const auto& bodies = layout.bodies;
  const auto wrist = std::find_if(bodies.begin(), bodies.end(), [](const physics::BodyInfo& b) {
    return b.name.find("kuka_link_6") != std::string::npos;
  });
  ASSERT_NE(wrist, bodies.end());
  const auto wristBody = static_cast<std::size_t>(wrist - bodies.begin());
  EXPECT_GT(physics::WorldLayout::position(down.end.data(), wristBody).z(),
            physics::WorldLayout::position(flat.end.data(), wristBody).z() + 0.015);
}

/// How far from the goal point the goal link ends when yumi_clutter_5 (nothing blocks its
/// pre-grasp) is steered to the goal with the last move capped at `approachSpeed` (m/s; 0: no
/// cap), motion after motion in the real physics, each run through the goal to its end as
/// p-KPIECE runs a steered candidate; infinity if it never gets there.
double yumiEndsFromTheGoalPoint(double approachSpeed) {
  const core::Problem problem = core::loadProblem(test::repoFile("problems/yumi_clutter_5.xml"));
  physics::PlanningContext context(problem, 0, physics::PropagationSettings{});
  const SteeredApproach steered =
      steerToTheGoal(context, ApproachSettings{0.0, 0.2, approachSpeed}, PushSettings{}, true);
  if (!steered.reached()) return std::numeric_limits<double>::infinity();
  return (context.layout().goalLinkPosition(steered.end.data()) - context.goal().position()).norm();
}

TEST(GoalSteeringTest, ALastMoveCappedInSpeedEndsNearerTheGoalPoint) {
  // At the joints' full speed the YuMi's one steered move to the pre-grasp (27 cm in 0.25 s)
  // ends about 1 cm short of the goal point: the arm lags its joint-space line. Capped at
  // 0.3 m/s (approach_speed), the moves end much nearer it.
  const double fast = yumiEndsFromTheGoalPoint(0.0);
  const double capped = yumiEndsFromTheGoalPoint(0.3);
  EXPECT_GT(fast, 0.008);
  EXPECT_LT(capped, 0.5 * fast) << "full speed " << fast << " m, capped " << capped << " m";
}

/// The way to kuka_clutter_20's first push, steered with the other moves at `moveSpeed` (m/s):
/// how many propagation steps it took, and the goal link's fastest speed over a step (m/s).
struct WayToThePush {
  unsigned steps = 0;
  double fastest = 0.0;
  bool reached = false;  ///< the gripper got to the push's line
};

WayToThePush steerToTheFirstPush(double moveSpeed) {
  Clutter20 scene;
  physics::PlanningContext& context = scene.context;
  MotionEvaluator evaluator(context, 0.0);
  ApproachSettings approach{0.05, 0.2};
  approach.moveSpeed = moveSpeed;
  const GoalSteering steering(context, evaluator, true, kCorridorPush, true, approach);
  const ClearingPush clearing(context, kCorridorPush);
  const double stepTime =
      static_cast<const ompl::control::SpaceInformation&>(*context.spaceInformation())
          .getPropagationStepSize();
  WayToThePush way;
  std::vector<double> state = context.startState();
  for (int motion = 0; motion < 24; ++motion) {
    const std::optional<ClearingPush::Step> step = clearing.next(state.data());
    if (step && step->pushing) {
      way.reached = true;
      return way;
    }
    const std::optional<NominalMotion> steered = steering.towardsGoal(state.data());
    if (!steered) return way;
    const NominalRun run =
        evaluator.runNominal(state.data(), steered->control.data(), steered->steps);
    if (run.steps < steered->steps) return way;
    Eigen::Vector3d link = context.layout().goalLinkPosition(state.data());
    for (const std::vector<double>& s : run.states) {
      const Eigen::Vector3d next = context.layout().goalLinkPosition(s.data());
      way.fastest = std::max(way.fastest, (next - link).norm() / stepTime);
      link = next;
    }
    way.steps += run.steps;
    state = run.end;
  }
  return way;
}

TEST(GoalSteeringTest, TheMovesBetweenPushesGoAtTheMoveSpeed) {
  // From the start the gripper goes up, over the cans and down to the first push's stand-off.
  // At 0.5 m/s (move_speed) it gets there in fewer steps than at 0.3, and at neither speed
  // does the goal link go much faster than asked.
  const WayToThePush slow = steerToTheFirstPush(0.3);
  const WayToThePush fast = steerToTheFirstPush(0.5);
  ASSERT_TRUE(slow.reached);
  ASSERT_TRUE(fast.reached);
  EXPECT_LT(fast.steps, slow.steps) << fast.steps << " against " << slow.steps;
  EXPECT_GT(fast.fastest, 0.3 * 1.1) << fast.fastest << " m/s against " << slow.fastest;
  EXPECT_LT(slow.fastest, 0.3 * 1.25);
  EXPECT_LT(fast.fastest, 0.5 * 1.25);
}

/// Where the goal steering alone gets on kuka_clutter_25 for p-KPIECE's tree `tree`, with the
/// KUKA files' push and approach (docs/scenes.md) and pushes turned by up to `spread` (rad).
struct TreeSteering {
  bool reachedGoal = false;
  physics::Violation broke = physics::Violation::None;
  std::vector<double> firstControl;
  std::vector<double> end;
};

TreeSteering followTreeOnClutter25(std::uint64_t tree, double spread, std::uint64_t after = 1) {
  const core::Problem problem = core::loadProblem(test::repoFile("problems/kuka_clutter_25.xml"));
  physics::PlanningContext context(problem, 0, physics::PropagationSettings{});
  PushSettings push{kPitch, 0.2, 1.2, 0.015, 0.2};
  push.crowdedSlide = 0.1;
  push.angleSpread = spread;
  push.angleAfter = after;
  const ApproachSettings approach{0.05, 0.2, 0.0, 0.0075, 0.5};
  MotionEvaluator evaluator(context, 0.0);
  GoalSteering steering(context, evaluator, true, push, true, approach);
  steering.setTree(tree);
  TreeSteering result;
  std::vector<double> state = context.startState();
  for (int motion = 0; motion < 60; ++motion) {
    const std::optional<NominalMotion> steered = steering.towardsGoal(state.data());
    if (!steered) break;
    if (result.firstControl.empty()) result.firstControl = steered->control;
    const NominalRun run =
        evaluator.runNominal(state.data(), steered->control.data(), steered->steps);
    state = run.end;
    if (run.reachedGoal) {
      result.reachedGoal = true;
      break;
    }
    if (run.stoppedBy != physics::Violation::None) {
      result.broke = run.stoppedBy;
      break;
    }
  }
  result.end = state;
  return result;
}

TEST(GoalSteeringTest, EachTreeAfterTheFirstPushesAtAnglesOfItsOwn) {
  // On kuka_clutter_25 the first tree's steering pushes straight across and tips can21
  // (docs/benchmarks.md, session 59). With push_angle_spread every later tree pushes each object
  // at an angle of its own: the same for the tree every time, other pushes for other trees, and
  // some of them reach the goal with every motion valid.
  const TreeSteering first = followTreeOnClutter25(0, 0.4);
  EXPECT_FALSE(first.reachedGoal);
  EXPECT_EQ(first.broke, physics::Violation::ObjectTilted);
  // Without a spread a later tree steers as the first.
  EXPECT_EQ(followTreeOnClutter25(3, 0.0).firstControl, first.firstControl);
  int reached = 0;
  int differ = 0;
  for (std::uint64_t tree = 1; tree <= 6; ++tree) {
    const TreeSteering later = followTreeOnClutter25(tree, 0.4);
    differ += later.firstControl != first.firstControl;
    reached += later.reachedGoal && later.broke == physics::Violation::None;
  }
  EXPECT_GE(differ, 4);
  EXPECT_GE(reached, 1);
  const TreeSteering again = followTreeOnClutter25(2, 0.4);
  EXPECT_EQ(again.end, followTreeOnClutter25(2, 0.4).end);
}

TEST(GoalSteeringTest, TreesBeforePushAngleAfterPushStraightAndTheRestAsBefore) {
  // push_angle_after holds the spread back for the first trees: a tree numbered below it steers
  // as the first tree does (and tips can21 on kuka_clutter_25), one from it on at the angles it
  // has with every tree after the first turned.
  const TreeSteering first = followTreeOnClutter25(0, 0.4);
  std::uint64_t opens = 0;
  for (std::uint64_t tree = 1; tree <= 6 && opens == 0; ++tree)
    if (followTreeOnClutter25(tree, 0.4).reachedGoal) opens = tree;
  ASSERT_GT(opens, 0u);
  const TreeSteering held = followTreeOnClutter25(opens, 0.4, opens + 1);
  EXPECT_FALSE(held.reachedGoal);
  EXPECT_EQ(held.end, first.end);
  const TreeSteering turned = followTreeOnClutter25(opens, 0.4, opens);
  EXPECT_TRUE(turned.reachedGoal);
  EXPECT_EQ(turned.end, followTreeOnClutter25(opens, 0.4).end);
}

}  // namespace
}  // namespace kautham::planners
