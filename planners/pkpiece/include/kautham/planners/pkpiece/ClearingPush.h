#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "kautham/physics/PlanningContext.h"
#include "kautham/planners/pkpiece/GoalEnd.h"
#include "kautham/planners/pkpiece/PushAngles.h"

namespace kautham::planners {

/// A move of the goal link to `target` over the objects on the table, at `height` (m): down
/// onto the target once within `over` of it horizontally; otherwise straight up first while
/// more than `below` under `height`, then across at that height to above the target.
struct Transfer {
  enum class Leg { Up, Across, Down };
  Leg leg;
  Eigen::Vector3d waypoint;  ///< where the link heads next
  double length;             ///< m from the link through the waypoint and on to the target
};
Transfer transferOver(const Eigen::Vector3d& link, const Eigen::Vector3d& target, double height,
                      double over, double below);

/// How far below level (rad) a gripper turned as `turn` points: its approach, where the fingers
/// point, is the third column.
double pitchBelowLevel(const Eigen::Matrix3d& turn);

/// How the clearing push is done: p-KPIECE's push_pitch, clear_behind, corridor_pitch,
/// push_below_centre, push_speed, crowded_pitch, crowded_slide and push_angle_* parameters.
struct PushSettings {
  double pitch = 0.0;          ///< rad the gripper points down on the way to and during a push
  double behind = 0.0;         ///< m behind the goal point the corridor is cleared (0: not)
  double corridorPitch = 0.0;  ///< rad the corridor's pushes point down (at least `pitch`)
  /// m below the pushed object's centre the fingers' middle meets it (negative: above); never
  /// lower than the workspace's floor allows the goal link.
  double belowCentre = 0.015;
  double speed = 0.1;  ///< m/s the goal link pushes at
  /// rad a push points down when no stand-off beside the object has room for the gripper at
  /// its own pitch, if that leaves more room (the footprint is shorter as it points down); at
  /// or below the push's own pitch (the default 0): never.
  double crowdedPitch = 0.0;
  /// m back along the approach from a stand-off without room for the whole gripper the gripper
  /// may be lowered (the nearest point with room, else the roomiest), to slide forward into the
  /// stand-off at the push's height; a gripper already low within this behind a stand-off
  /// slides in too. 0: lowered onto the stand-off.
  double crowdedSlide = 0.0;
  /// rad a tree after the first may turn each push away from straight across the approach, at an
  /// angle drawn for the tree and the object (towards the target or away from it); 0: across.
  double angleSpread = 0.0;
  /// With an angle spread, the first tree whose pushes turn: the trees numbered below it push
  /// straight across, as the first does.
  std::uint64_t angleAfter = 1;
  /// With an angle spread, the trees per generation whose angles are learned from the trees
  /// before (PushAngles); 0: every tree draws its angles afresh.
  std::uint64_t angleGeneration = 0;
  /// With an angle spread, the search's seed: the same tree pushes at other angles under another.
  std::uint64_t angleSeed = 0;
};

/// Where p-KPIECE steers while an object fills the goal's free space (ours, not in the
/// paper): a push that moves the object sideways out of the approach, low on the object.
///
/// The gripper first goes above a stand-off point beside the object (on the side with more
/// room; from a push that ended low, straight up first, so that it passes over the cans),
/// down to the push height, then sweeps across the approach through the object's centre. It
/// points down a little all the while: held level that low, the wrist (behind the gripper, and
/// wider) would drag on the table. The push is low (by default 1.5 cm below the object's
/// centre, 4.6 cm up a 12.2 cm can) because a can pushed at a side pre-grasp's height, near its
/// top, tips over before it slides: it slides only when pushed below radius / friction (6.6 cm for
/// a can with friction 0.5).
///
/// With `behind` > 0 it first clears the part of the approach corridor that the arm fills at
/// the pre-grasp (up to `behind` metres back from the goal point, as wide as the free space):
/// the wrist stands there at the goal, and pushes an object left there high, where it tips.
/// Those objects go first, the one furthest back first, each pushed across the same way but
/// with the gripper pointing down steeply (`corridorPitch`), so that the wrist passes over the
/// cans behind the one pushed. The free space's blocker counts among them when it reaches
/// behind the goal point.
///
/// Where neither stand-off leaves the gripper's footprint room (it reaches 12 cm back held
/// level, less as it points down), the push goes pitched down by `crowdedPitch` instead, if that
/// leaves more: the dense scenes' corridors hold cans 1-2 cm apart. With `crowdedSlide`, a
/// stand-off without room for the whole gripper (as wide as the free space) is reached low from
/// behind instead of from above: lowered onto it, the fingers land on the neighbouring can's top
/// and tip it; moved in at the push's height they meet it low, where a can slides. A gripper
/// already low behind a stand-off, within `crowdedSlide`, slides in whatever the room: a slide
/// goes on when the cans it moves make room at the stand-off.
///
/// The waypoints follow the object as it moves, so a push in progress goes on until the
/// object leaves the free space (or the corridor). `remaining` is the length of the rest of
/// this plan and on to the goal: the goal bias ranks blocked states by it, so the motions
/// furthest along the clearing are the ones grown.
class ClearingPush {
 public:
  struct Step {
    Eigen::Vector3d waypoint;                                   ///< where the goal link heads next
    Eigen::Matrix3d orientation = Eigen::Matrix3d::Identity();  ///< and how it is turned there
    double remaining = 0.0;  ///< m of the clearing plan still to go, and on to the goal
    /// the goal link is behind the object, on the line of the push, or sliding in to it low
    bool pushing = false;
  };

  /// With `end`, an object that reaches into the free space only where the gripper need not
  /// end (GoalEnd::clearPose() finds a pose nearby whose free space is clear) is left alone.
  ClearingPush(const physics::PlanningContext& context, const PushSettings& settings,
               const GoalEnd* end = nullptr);

  /// None when the free space and the corridor are clear, or the goal has no free space or
  /// side approach.
  std::optional<Step> next(const double* state) const;
  /// How high the goal link travels between pushes: above the tallest movable object's top (at
  /// its home), within the workspace.
  double travelHeight() const { return travelHeight_; }
  /// How much clearing is left in `state`, by a measure that does not depend on the pushes'
  /// angles (what PushAngles learns from): none when next() has nothing to clear; else how far
  /// the object being cleared still reaches across into the free space's width (m), plus
  /// kLaterPush when the free space's own push is still to come after it.
  std::optional<double> clearingLeft(const double* state) const;
  /// The movable object in the corridor behind the goal point that is pushed first (the one
  /// furthest back), if any.
  std::optional<std::size_t> corridorBlocker(const double* state) const;
  /// Which of p-KPIECE's trees the pushes are for: with an angle spread, each tree from
  /// PushSettings::angleAfter on pushes each object at an angle of its own (PushAngles).
  void setTree(std::uint64_t tree) { angles_.setTree(tree); }
  /// The angles the trees push at, and how near each tree got (what later trees learn from).
  PushAngles& angles() { return angles_; }

 private:
  /// How the gripper is held during a push: pitched down by `pitch`, turned as `orientation`,
  /// its fingers pointing along `fingers`, reaching `reach` (m) back from the goal link over the
  /// table.
  struct Posture {
    double pitch = 0.0;
    Eigen::Matrix3d orientation = Eigen::Matrix3d::Identity();
    Eigen::Vector3d fingers = Eigen::Vector3d::Zero();
    double reach = 0.0;
  };
  Posture posture(double pitch) const;
  /// What next() clears in a state: the corridor's object first, then the free space's.
  struct Blockers {
    std::optional<std::size_t> corridor;
    std::optional<std::size_t> freeSpace;
    double later = 0.0;  ///< kLaterPush when the free space's push comes after the corridor's
  };
  Blockers blockers(const double* state) const;
  /// The push that clears `blocker`, held as `own` (or crowded); `later` (m) stands for the
  /// clearing still to come after it (in the remaining length).
  Step pushStep(const double* state, std::size_t blocker, double later, const Posture& own) const;
  /// `own`, or the crowded posture when no stand-off has room at `own` and more at it; during a
  /// push the one nearest the gripper's pitch.
  const Posture& choosePosture(const double* state, std::size_t blocker, const Posture& own) const;
  /// Where the goal link meets the object centred at `centre`: its fingers' middle below the
  /// centre, not below the workspace's floor.
  Eigen::Vector3d aimAt(const Eigen::Vector3d& centre, const Posture& posture) const;
  /// The stand-off beside the object on the `side` (+1 or -1) across the approach (turned by
  /// the push's angle).
  Eigen::Vector3d standOff(const Eigen::Vector3d& centre, const Posture& posture, double side,
                           std::size_t blocker) const;
  /// The angle (rad) this tree pushes `blocker` at, away from straight across the approach.
  double pushAngle(std::size_t blocker) const;
  /// Which way a push of `blocker` from the `side` (+1 or -1) stand-off goes: across the
  /// approach, turned by pushAngle().
  Eigen::Vector3d pushDirection(double side, std::size_t blocker) const;
  /// The more room of the two stand-offs beside the object held as `posture` (room()).
  double widerRoom(const double* state, const Eigen::Vector3d& centre, std::size_t blocker,
                   const Posture& posture) const;
  /// How far the gripper points down in `state` (rad).
  double pitchNow(const double* state) const;
  /// Of `a` and `b`, the posture whose pitch is nearer `pitch` (`a` if as near).
  static const Posture& nearer(double pitch, const Posture& a, const Posture& b);
  /// Whether `link` is on the line of a push through `aim` going along `direction`.
  bool onLine(const Eigen::Vector3d& link, const Eigen::Vector3d& aim,
              const Eigen::Vector3d& direction) const;
  /// Where the gripper is lowered to slide into the stand-off `start`: the nearest point from it
  /// back (along back_, up to slide_) where the gripper has room over its whole width (`start`
  /// itself if it has), or the roomiest.
  Eigen::Vector3d landing(const double* state, const Eigen::Vector3d& start, std::size_t blocker,
                          const Posture& posture) const;
  /// How near the gripper over the table at `point` (as wide as the free space, reaching `reach`
  /// back) the other objects' centres stand.
  double landingRoom(const double* state, const Eigen::Vector3d& point, std::size_t blocker,
                     double reach) const;
  /// Whether `link` is low on the slide into `start` (within kOnLine of the line back from it).
  bool sliding(const Eigen::Vector3d& link, const Eigen::Vector3d& start) const;
  /// How far `body`'s footprint reaches across into the free space's width in `state` (m): the
  /// shorter move across the approach that takes it out (0: out).
  double reachAcross(const double* state, std::size_t body) const;
  /// How near the stand-off at `point` (and the footprint `reach` behind it) the other objects
  /// stand.
  double room(const double* state, const Eigen::Vector3d& point, std::size_t blocker,
              double reach) const;

  const physics::PlanningContext& context_;
  Eigen::Vector3d back_ = Eigen::Vector3d::Zero();    ///< level, against the approach
  Eigen::Vector3d across_ = Eigen::Vector3d::Zero();  ///< level, across the approach
  double halfWidth_ = 0.0;                            ///< of the free space, across the approach
  double lowest_ = 0.0;        ///< the lowest the goal link may go (workspace floor and margin)
  double travelHeight_ = 0.0;  ///< see travelHeight()
  Posture push_;               ///< the free space's push
  Posture corridor_;           ///< the corridor's push
  Posture crowded_;            ///< either, when its stand-offs have no room
  /// A movable object's bounds at the start, and where its body was then (the footprint moves
  /// with its body).
  struct Footprint {
    std::size_t body;
    Eigen::Vector3d start;
    Eigen::AlignedBox3d bounds;
  };
  std::vector<Footprint> footprints_;
  double behind_ = 0.0;
  double belowCentre_ = 0.0;
  double slide_ = 0.0;  ///< PushSettings::crowdedSlide
  const GoalEnd* end_ = nullptr;
  PushAngles angles_;
};

}  // namespace kautham::planners
