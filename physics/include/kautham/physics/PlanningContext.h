#pragma once

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include <ompl/base/ProblemDefinition.h>
#include <ompl/control/SpaceInformation.h>

#include "kautham/core/Problem.h"
#include "kautham/physics/EndEffectorProjection.h"
#include "kautham/physics/PhysicsPropagator.h"
#include "kautham/physics/RestingSink.h"
#include "kautham/physics/WorkspaceGoal.h"
#include "kautham/physics/World.h"
#include "kautham/physics/WorldStateSpace.h"
#include "kautham/physics/WorldValidityChecker.h"

namespace kautham::physics {

/// How controls are applied: each control is held for a whole number of propagation steps,
/// between min and max, and each propagation step is a whole number of physics steps.
struct PropagationSettings {
  double propagationStepSize = 0.05;  ///< seconds
  unsigned minControlSteps = 2;
  unsigned maxControlSteps = 20;
};

/// Everything a control planner needs for one query of a problem, wired together: the ODE
/// world, OMPL's state and control spaces, the propagator, the validity checker, the
/// end-effector projection, the start state and the goal region.
class PlanningContext {
 public:
  PlanningContext(const core::Problem& problem, std::size_t queryIndex,
                  const PropagationSettings& settings);

  const core::Problem& problem() const { return problem_; }
  const core::Query& query() const { return problem_.queries.at(queryIndex_); }
  World& world() { return *world_; }
  const WorldLayout& layout() const { return *layout_; }
  /// The layout, for what keeps it (GoalFreeSpace).
  const std::shared_ptr<const WorldLayout>& sharedLayout() const { return layout_; }

  const ompl::control::SpaceInformationPtr& spaceInformation() const { return si_; }
  const ompl::base::ProblemDefinitionPtr& problemDefinition() const { return pdef_; }
  const PhysicsPropagator& propagator() const { return *propagator_; }
  /// The full validity checker: replays and validation always judge with every constraint.
  const WorldValidityChecker& validityChecker() const { return *validity_; }
  /// States the planner's validity checks rejected, by reason (both rule sets), most first.
  std::vector<std::pair<Violation, std::uint64_t>> rejections() const;
  /// Which rules the planner's space information checks states with (o-KPIECE plans with
  /// the knowledge rules only); Full until changed.
  void usePlanningRules(ValidityRules rules);
  const WorkspaceGoal& goal() const { return *goal_; }
  WorkspaceGoal& goal() { return *goal_; }
  /// The goal for a world whose objects start as in `start` rather than as planned: a region
  /// given relative to an object moves as that object's start pose moved. Null when the goal
  /// is the same as goal() (it is fixed, a configuration, or its object has not moved).
  std::unique_ptr<WorkspaceGoal> goalForStart(const double* start) const;
  /// KPIECE's projection: the state space's default one (see WorldStateSpace).
  EndEffectorProjection& projection();

  const std::vector<double>& startState() const { return start_; }
  /// Why the start state is invalid, or Violation::None (the planners need a valid start).
  Violation startViolation() const { return startViolation_; }
  /// Pairs of things that interpenetrate at the start (more than 2 mm): a scene error.
  const std::vector<Overlap>& startOverlaps() const { return startOverlaps_; }
  /// Objects that do not rest where the start puts them (restlessObjects()): they would float
  /// asleep until touched. Not looked for when things interpenetrate at the start.
  const std::vector<RestlessObject>& restlessAtStart() const { return restlessAtStart_; }

 private:
  core::Problem problem_;
  std::size_t queryIndex_;
  std::shared_ptr<World> world_;
  std::shared_ptr<const WorldLayout> layout_;
  std::shared_ptr<WorldStateSpace> space_;
  ompl::control::SpaceInformationPtr si_;
  ompl::base::ProblemDefinitionPtr pdef_;
  std::shared_ptr<PhysicsPropagator> propagator_;
  std::shared_ptr<WorldValidityChecker> validity_;
  std::shared_ptr<WorldValidityChecker> knowledgeValidity_;
  std::shared_ptr<WorkspaceGoal> goal_;
  std::vector<double> start_;
  Violation startViolation_ = Violation::None;
  std::vector<Overlap> startOverlaps_;
  std::vector<RestlessObject> restlessAtStart_;
};

}  // namespace kautham::physics
