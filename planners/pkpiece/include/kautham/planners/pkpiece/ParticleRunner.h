#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <ompl/base/State.h>
#include <ompl/control/Control.h>
#include <Eigen/Core>

#include "kautham/physics/Execution.h"
#include "kautham/physics/PlanningContext.h"
#include "kautham/planners/pkpiece/ParticleJob.h"

namespace kautham::planners {

/// Runs motions through a planning context's propagator and full validity checker, one
/// propagation step per propagate call, so a motion stops at its first invalid state. Used for
/// nominal runs, particle jobs run inline, and particle jobs in worker processes (each with
/// its own copy made by fork): the same code everywhere.
class ParticleRunner {
 public:
  explicit ParticleRunner(physics::PlanningContext& context);
  ~ParticleRunner();
  ParticleRunner(const ParticleRunner&) = delete;
  ParticleRunner& operator=(const ParticleRunner&) = delete;

  /// One propagation step from `from` into `to`; returns whether the new state is valid.
  bool step(const double* from, const double* control, double* to,
            const Eigen::Vector3d& targetReference);
  /// Sets the job's contact parameters (they stay set: the caller restores its own) and steps
  /// the control from the start state until the first invalid state or `steps` steps; with
  /// the job's tiltLimit, a movable object tilted beyond it makes a state invalid too, and
  /// with its targetDriftLimit a target drifted beyond it. The
  /// state the run ends in is judged with its own contacts, as an execution's last state is
  /// (physics::addFinalContacts): a run that ends with the robot on the table or the target
  /// is invalid there.
  ParticleResult run(const ParticleJob& job);
  /// The first movable object tilted more than `limit` (rad) in `state`; none when limit <= 0.
  std::optional<std::size_t> tiltedBeyond(const double* state, double limit) const;
  /// Whether the target has drifted more than `limit` (m) from `reference` in `state`; never
  /// when limit <= 0 or the scene has no target.
  bool targetDriftedBeyond(const double* state, const Eigen::Vector3d& reference,
                           double limit) const;
  /// Executes the whole plan `controls` once in a world sampled with the stream `seed`, as
  /// `kautham validate` does (physics::execute with a std::mt19937_64 seeded by it): the same
  /// run in any process with a copy of the context.
  physics::ExecutionResult execute(const std::vector<physics::ControlStep>& controls,
                                   std::uint64_t seed);
  /// How far an execution of a plan of `controls` controls got (ExecutionOutcome).
  static ExecutionOutcome outcomeOf(const physics::ExecutionResult& run, std::size_t controls);

  physics::PlanningContext& context() { return context_; }
  std::size_t stateSize() const { return stateSize_; }
  std::size_t controlSize() const { return controlSize_; }

 private:
  /// The contacts of the state a valid run ended in, after `stepsRun` steps: touching a fixed
  /// obstacle or the target makes it invalid, and drops it from the recorded states.
  void judgeLastState(const ParticleJob& job, unsigned stepsRun, bool lastRecorded,
                      ParticleResult& result);

  physics::PlanningContext& context_;
  ompl::base::State* from_;
  ompl::base::State* to_;
  ompl::control::Control* control_;
  std::size_t stateSize_;
  std::size_t controlSize_;
  std::vector<std::size_t> movableBodies_;  ///< what tiltedBeyond looks at
};

}  // namespace kautham::planners
