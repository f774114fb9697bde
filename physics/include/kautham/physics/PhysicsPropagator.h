#pragma once

#include <cstdint>
#include <memory>

#include <ompl/control/SpaceInformation.h>
#include <ompl/control/StatePropagator.h>

#include "kautham/physics/ControlMapping.h"
#include "kautham/physics/World.h"

namespace kautham::physics {

/// Work done by the physics, for statistics and benchmarks.
struct PropagationCounters {
  std::uint64_t propagations = 0;
  std::uint64_t physicsSteps = 0;
};

/// OMPL state propagator that runs the ODE world: writes the start state into the world,
/// sets the joint velocity targets the control maps to (ControlMapping), and steps for the
/// given duration.
/// The result is a function of (state, control, duration) only, whatever ran before:
/// the full state is written and ODE's solver seed is reset on every call.
class PhysicsPropagator : public ompl::control::StatePropagator {
 public:
  PhysicsPropagator(const ompl::control::SpaceInformationPtr& si, std::shared_ptr<World> world,
                    ControlMapping mapping);

  void propagate(const ompl::base::State* state, const ompl::control::Control* control,
                 double duration, ompl::base::State* result) const override;
  bool canPropagateBackward() const override { return false; }

  /// Physics steps that make up `duration` seconds (at least one).
  unsigned stepsFor(double duration) const;
  const PropagationCounters& counters() const { return counters_; }
  /// Counts work done for this propagator elsewhere: by copies of it in worker processes
  /// (p-KPIECE's particles, planners::ParticleWorkers), so statistics do not depend on them.
  void addCounters(const PropagationCounters& work) const {
    counters_.propagations += work.propagations;
    counters_.physicsSteps += work.physicsSteps;
  }
  const ControlMapping& mapping() const { return mapping_; }

 private:
  std::shared_ptr<World> world_;
  ControlMapping mapping_;
  mutable std::vector<double> velocities_;  ///< scratch: one per joint
  mutable PropagationCounters counters_;
};

}  // namespace kautham::physics
