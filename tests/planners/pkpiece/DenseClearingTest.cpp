// How p-KPIECE's goal steering copes with kuka_clutter_30, where a can (can20) reaches 6 mm
// into the free space from behind the target, where no push can get at it: the real scene, the
// real physics, the steering followed motion after motion.

#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "kautham/physics/GoalFreeSpace.h"
#include "kautham/planners/pkpiece/ClearingPush.h"
#include "kautham/planners/pkpiece/GoalSteering.h"
#include "kautham/planners/pkpiece/MotionEvaluator.h"
#include "physics/PhysicsTestSupport.h"

namespace kautham::planners {
namespace {

// The push as kuka_clutter_30's file sets it: pitched 0.45 rad, the corridor 20 cm behind the
// goal point cleared first pitched 1.2 rad.
const PushSettings kFilePush{0.45, 0.2, 1.2};
// Its approach: lined up 5 cm behind the goal point, pitched 0.2 rad; ending up to `shift` from
// the goal point.
ApproachSettings fileApproach(double shift) { return ApproachSettings{0.05, 0.2, 0.0, shift}; }

struct Clutter30 : test::ContextFixture {
  Clutter30() : ContextFixture("problems/kuka_clutter_30.xml") {}
  /// The start with the named cans carried (upright, at rest) to (x, y).
  void carry(std::vector<double>& edited, const std::string& name, double x, double y) const {
    double* position = edited.data() + body(name) * physics::WorldLayout::kBodyStateSize +
                       physics::WorldLayout::kPosition;
    position[0] = x;
    position[1] = y;
  }
  /// The start as p-KPIECE's search leaves it once the corridor is clear (pKP, seed 1): can3
  /// and can6, in the wrist's way at the pre-grasp, pushed aside to -x.
  std::vector<double> corridorCleared() const {
    std::vector<double> cleared = context.startState();
    carry(cleared, "can3", -0.10, 0.02);
    carry(cleared, "can6", -0.15, 0.06);
    return cleared;
  }
};

/// Follows the steering from `state` while `going` holds (at most `most` motions): whether a
/// motion broke a rule or the steering had no motion to give, and where the last valid one
/// ended.
struct Steered {
  bool brokeARule = false;
  bool gaveUp = false;
  int motions = 0;
  std::vector<double> end;
};

template <typename Going>
Steered follow(physics::PlanningContext& context, const PushSettings& push,
               const ApproachSettings& approach, std::vector<double> state, int most, Going going) {
  MotionEvaluator evaluator(context, 0.0);
  const GoalSteering steering(context, evaluator, true, push, true, approach);
  Steered result;
  result.end = std::move(state);
  for (; result.motions < most && going(result.end); ++result.motions) {
    const std::optional<NominalMotion> steered = steering.towardsGoal(result.end.data());
    if (!steered) {
      result.gaveUp = true;
      break;
    }
    const NominalRun run =
        evaluator.runNominal(result.end.data(), steered->control.data(), steered->steps, true);
    // A run stops early at a broken rule, or where it enters the goal region.
    if (run.steps < steered->steps && !run.reachedGoal) {
      result.brokeARule = true;
      return result;
    }
    result.end = run.end;
  }
  return result;
}

TEST(DenseClearingTest, AnObjectAtTheFreeSpacesFarEndIsLeftByEndingBesideTheGoalPoint) {
  // With can1 pushed out (to +x), can20 is left reaching 6 mm into the free space's far end,
  // behind the target. The push the clearing then asks for reaches round the target: the
  // steering stops beside it, its probes for the next step ending on the target (before a run's
  // last state was judged, session 51, it pushed on and touched the target). Ending within 7.5 mm
  // of the goal point (kuka_clutter_30's margin is 1 cm), a pose whose free space is clear is
  // found, no push is asked for, and the steering reaches the goal there, every motion valid.
  Clutter30 scene;
  std::vector<double> state = scene.corridorCleared();
  scene.carry(state, "can1", 0.16, 0.14);
  const physics::WorkspaceGoal& goal = scene.context.goal();
  ASSERT_EQ(goal.freeSpaceBlocker(state.data()), scene.body("can20"));
  const auto notThere = [&](const std::vector<double>& s) {
    return !goal.reached(s.data()) || goal.distance(s.data()) > 0.01;
  };

  const Eigen::Matrix3d turn = goal.nominalGoalPose().linear();
  EXPECT_FALSE(GoalEnd(scene.context, turn, 0.0).clearPose(state.data()).has_value());
  const Steered pushed = follow(scene.context, kFilePush, fileApproach(0.0), state, 24, notThere);
  EXPECT_TRUE(pushed.brokeARule || pushed.gaveUp) << "after " << pushed.motions << " motions";
  EXPECT_FALSE(goal.reached(pushed.end.data()));

  const GoalEnd shifted(scene.context, turn, 0.0075);
  const std::optional<GoalEnd::Pose> end = shifted.clearPose(state.data());
  ASSERT_TRUE(end.has_value());
  // Turned about the vertical, or beside the goal point, or both.
  EXPECT_TRUE((end->point - goal.position()).norm() > 0.0 || !end->turn.isApprox(turn));
  EXPECT_LE((end->point - goal.position()).norm(), 0.0075 + 1e-9);
  EXPECT_FALSE(ClearingPush(scene.context, kFilePush, &shifted).next(state.data()));

  const Steered steered =
      follow(scene.context, kFilePush, fileApproach(0.0075), state, 24, notThere);
  EXPECT_FALSE(steered.brokeARule) << "after " << steered.motions << " motions";
  EXPECT_TRUE(goal.reached(steered.end.data()))
      << "goal distance " << goal.distance(steered.end.data());
  EXPECT_LE(goal.distance(steered.end.data()), 0.01);
}

TEST(DenseClearingTest, AnEndBesideTheGoalPointKeepsTheMostRoomAroundItsFreeSpace) {
  // kuka_clutter_30 as pKP's plan for seed 4 leaves it: can1 pushed to -x, carrying can15 and
  // can11 ahead of it; can20 reaches into the free space at the goal point. The gripper is
  // pitched 0.2 rad down, as the file's approach holds it. The nearest pose with 2 mm of room
  // (the end chosen before session 33) is 5 mm back, turned 0.15 rad about the vertical: its
  // free space has less than 5 mm of room from can20 and can23, whose poses are uncertain by
  // 5 mm (standard deviation). The end chosen now keeps 5 mm or more.
  Clutter30 scene;
  std::vector<double> state = scene.corridorCleared();
  scene.carry(state, "can1", -0.134, 0.171);
  scene.carry(state, "can15", -0.181, 0.125);
  scene.carry(state, "can11", -0.246, 0.136);
  const physics::WorkspaceGoal& goal = scene.context.goal();
  const physics::GoalSpec& spec = goal.spec();
  ASSERT_TRUE(spec.freeSpace.has_value());
  const auto roomAt = [&](double room, const Eigen::Vector3d& point, const Eigen::Matrix3d& turn) {
    const physics::GoalFreeSpace grown(scene.context.sharedLayout(),
                                       spec.freeSpace->size + Eigen::Vector3d::Constant(2 * room),
                                       spec.freeSpace->center);
    Eigen::Isometry3d link = Eigen::Isometry3d::Identity();
    link.linear() = turn;
    link.translation() = point;
    return grown.isFree(state.data(), link);
  };
  const Eigen::Vector3d across = spec.approach->cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Matrix3d pitched = Eigen::AngleAxisd(-0.2, across) * goal.nominalGoalPose().linear();
  Eigen::Isometry3d atGoalPoint = Eigen::Isometry3d::Identity();
  atGoalPoint.linear() = pitched;
  atGoalPoint.translation() = goal.position();
  ASSERT_GT(goal.freeSpaceFilledAt(state.data(), atGoalPoint), 0.0);
  const Eigen::Vector3d back = goal.position() - 0.005 * *spec.approach;
  const Eigen::Matrix3d turned = Eigen::AngleAxisd(-0.15, Eigen::Vector3d::UnitZ()) * pitched;
  EXPECT_TRUE(roomAt(0.002, back, turned));
  EXPECT_FALSE(roomAt(0.005, back, turned));

  const GoalEnd shifted(scene.context, pitched, 0.0075);
  EXPECT_TRUE(shifted.anyClearPose(state.data()));
  const std::optional<GoalEnd::Pose> end = shifted.clearPose(state.data());
  ASSERT_TRUE(end.has_value());
  EXPECT_LE((end->point - goal.position()).norm(), 0.0075 + 1e-9);
  EXPECT_TRUE(roomAt(0.005, end->point, end->turn));
  // Not the nearest clear pose: the room is bought with distance from the goal point.
  EXPECT_GT((end->point - goal.position()).norm(), 0.005 - 1e-9);
  EXPECT_FALSE(end->point.isApprox(back, 1e-9) && end->turn.isApprox(turned, 1e-9));
}

}  // namespace
}  // namespace kautham::planners
