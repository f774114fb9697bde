#include "kautham/physics/PhysicsPropagator.h"

#include <algorithm>
#include <cmath>

#include <ompl/control/spaces/RealVectorControlSpace.h>

#include "kautham/physics/WorldStateSpace.h"

namespace kautham::physics {

PhysicsPropagator::PhysicsPropagator(const ompl::control::SpaceInformationPtr& si,
                                     std::shared_ptr<World> world, ControlMapping mapping)
    : StatePropagator(si),
      world_(std::move(world)),
      mapping_(std::move(mapping)),
      velocities_(world_->actuators().size()) {}

unsigned PhysicsPropagator::stepsFor(double duration) const {
  const double steps = std::round(duration / world_->settings().stepSize);
  return static_cast<unsigned>(std::max(1.0, steps));
}

void PhysicsPropagator::propagate(const ompl::base::State* state,
                                  const ompl::control::Control* control, double duration,
                                  ompl::base::State* result) const {
  World& world = *world_;
  world.writeState(WorldStateSpace::values(state));
  mapping_.jointVelocities(
      control->as<ompl::control::RealVectorControlSpace::ControlType>()->values,
      velocities_.data());
  world.setJointVelocities(velocities_.data());
  world.resetSolverSeed();
  world.takeEvents();

  const unsigned steps = stepsFor(duration);
  unsigned done = 0;
  unsigned events = kNoEvent;
  // Stop at the first step that blows up: a diverged world is never stepped further.
  while (done < steps && !(events & kSimulationDiverged)) {
    world.step();
    events |= world.takeEvents();
    ++done;
  }
  double* out = WorldStateSpace::values(result);
  world.readState(out);
  out[world.layout().flagsIndex()] = static_cast<double>(events);

  counters_.propagations += 1;
  counters_.physicsSteps += done;
}

}  // namespace kautham::physics
