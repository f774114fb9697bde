#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <ompl/base/StateValidityChecker.h>

#include "kautham/core/Problem.h"
#include "kautham/physics/WorldLayout.h"

namespace kautham::physics {

/// Why a state is invalid (the paper's validity function F(W, C)).
enum class Violation {
  None,
  SimulationDiverged,  ///< NaN or runaway speeds: the physics blew up
  RobotTouchedFixed,   ///< the robot touched a fixed obstacle
  RobotTouchedTarget,  ///< the robot touched the target
  TargetMoved,         ///< the target drifted more than the tolerance
  OutsideWorkspace,    ///< the end effector left the workspace
  JointLimit,          ///< a robot joint passed its limit by more than the tolerance
  JointTooFast,        ///< a robot joint turned faster than its velocity limit allows
  LinkTooFast,         ///< a robot link moved faster than the link speed limit
  ObjectTooFast,       ///< a movable object is faster than the limit
  ObjectTilted,        ///< a movable object tipped beyond the limit
  ObjectOffSupport,    ///< a movable object left the table (or fell)
};
const char* toString(Violation violation);
/// Whether the rule is about an object (the target touched or moved, a movable object too fast,
/// tilted or off the support): WorldValidityChecker::offendingObject names it.
bool isObjectRule(Violation violation);
constexpr std::size_t kViolationKinds = static_cast<std::size_t>(Violation::ObjectOffSupport) + 1;

/// Which constraints a checker applies.
enum class ValidityRules {
  Full,           ///< every constraint (p-KPIECE, KPIECE, replays, validation)
  KnowledgeOnly,  ///< o-KPIECE: only whom the robot may touch, the workspace and the robot's
                  ///< own limits; no after-effects (object speed, tilt, support, target drift)
};

/// State validity for pushing: the robot may touch movable objects only, and what it pushes
/// must stay upright, slow and on the support surface. Reads states through WorldLayout only,
/// so a check costs a few arithmetic operations per object and no physics.
class WorldValidityChecker : public ompl::base::StateValidityChecker {
 public:
  WorldValidityChecker(const ompl::base::SpaceInformationPtr& si,
                       std::shared_ptr<const WorldLayout> layout, const core::Problem& problem,
                       const double* startState, ValidityRules rules = ValidityRules::Full);

  bool isValid(const ompl::base::State* state) const override;
  /// The first constraint the state breaks, or Violation::None.
  Violation check(const double* state) const;
  /// As check(), with the target's reference position given: a run whose start was sampled
  /// (the target's pose is uncertain) measures the target's drift from where it started.
  Violation check(const double* state, const Eigen::Vector3d& targetReference) const;
  /// As check(), with the object the gripper holds (a layout body) exempt from the object
  /// checks: carried, it leaves the table and turns with the gripper by design.
  Violation check(const double* state, const Eigen::Vector3d& targetReference,
                  std::optional<std::size_t> held) const;
  /// Which object breaks a rule in `state`: the target if the robot touched or moved it, else
  /// the first movable object (other than `held`) that is too fast, tilted or off the support.
  /// Nothing if no object does (the robot broke a rule, or none was broken).
  std::optional<std::size_t> offendingObject(const double* state,
                                             const Eigen::Vector3d& targetReference,
                                             std::optional<std::size_t> held) const;
  /// Per body, how deep it sinks when resting at the start (RestingSink.h): soft contacts let
  /// objects settle into the ground, which is no drop. Zero for every body until set.
  void allowRestingSink(std::vector<double> sink);
  const std::vector<double>& restingSink() const { return restingSink_; }
  /// Where the target stands at the start of the query.
  const Eigen::Vector3d& targetStart() const { return targetStart_; }
  std::optional<std::size_t> targetBody() const { return targetBody_; }
  /// How many states isValid() (the planner's calls) rejected, indexed by Violation: why a
  /// tree that never grows stays where it is (PlanningContext::rejections sums and sorts them).
  std::array<std::uint64_t, kViolationKinds> rejectionCounts() const;

 private:
  Violation checkObject(const double* state, std::size_t body) const;
  Violation checkRobot(const double* state) const;

  std::shared_ptr<const WorldLayout> layout_;
  core::InteractionConstraints limits_;
  core::KinodynamicLimits robotLimits_;
  ValidityRules rules_;
  Eigen::AlignedBox3d workspace_;
  bool onSupport(const Eigen::Vector3d& position) const;

  /// The support's shapes seen from above: an object is on the support when its centre is
  /// over one of them (boxes are rectangles turned with their yaw, the rest discs).
  std::vector<core::CollisionShape> supportShapes_;
  std::vector<double> startHeights_;       ///< per body: height of its centre at the start
  std::vector<double> restingSink_;        ///< per body: see allowRestingSink()
  std::optional<std::size_t> targetBody_;  ///< none in Kautham files without roles
  Eigen::Vector3d targetStart_;
  mutable std::array<std::atomic<std::uint64_t>, kViolationKinds> rejected_{};
};

}  // namespace kautham::physics
