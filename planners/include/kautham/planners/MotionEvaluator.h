#pragma once

#include <memory>
#include <random>
#include <vector>

#include "kautham/physics/PlanningContext.h"
#include "kautham/physics/UncertaintySampler.h"
#include "kautham/planners/ObjectPoseBelief.h"
#include "kautham/planners/ParticleJob.h"
#include "kautham/planners/ParticleWorkers.h"

namespace kautham::planners {

/// A candidate motion run nominally: the mean contact parameters, the exact control and the
/// start state as the tree has it.
struct NominalRun {
  std::vector<double> end;                  ///< the last valid state
  std::vector<std::vector<double>> states;  ///< the state after each valid step (back() == end)
  unsigned steps = 0;        ///< valid propagation steps (0: the first step was invalid)
  bool reachedGoal = false;  ///< the run stopped at the first step inside the goal
};

/// What the particles of a candidate said (the paper's Algorithm 2, lines 5-17).
struct ParticleVerdict {
  double stateValidity = 1.0;  ///< P_state: fraction of particles whose states were all valid
  double interaction = 1.0;    ///< P_int: fraction whose objects moved at most d
  std::vector<std::vector<double>> ends;  ///< each particle's final state
  double goal = 1.0;  ///< fraction of particles that end valid inside the goal region
  double belief() const { return stateValidity * interaction; }
};

/// Runs candidate motions through the physics for p-KPIECE: nominally, and as particle
/// motions under sampled uncertainty. Steps one propagation step at a time, so a motion stops
/// at its first invalid state and at the first state that reaches the goal, and a plan replays
/// exactly as it was planned (physics::replay steps the same way).
///
/// Particle motions are drawn here, in particle order, and run as self-contained jobs: inline,
/// or spread over worker processes (useWorkers) with bit-identical results.
class MotionEvaluator {
 public:
  MotionEvaluator(physics::PlanningContext& context, double maxDisplacement);
  ~MotionEvaluator();
  MotionEvaluator(const MotionEvaluator&) = delete;
  MotionEvaluator& operator=(const MotionEvaluator&) = delete;

  /// Propagates `control` from `start` for up to `steps` steps, keeping the valid prefix.
  NominalRun runNominal(const double* start, const double* control, unsigned steps);

  /// Spreads particle jobs over `threads` processes: this one and threads - 1 forked workers
  /// (ParticleWorkers). 1: every job runs inline. Workers from an earlier call are reaped.
  void useWorkers(unsigned threads);
  unsigned threads() const { return workers_ ? static_cast<unsigned>(workers_->size()) + 1 : 1; }

  /// Runs `particles` particle motions of the candidate: start poses drawn from `belief`,
  /// contact parameters and control noise from the problem's uncertainty; particle i uses the
  /// random stream `streamSeed + i`, so the verdict does not depend on evaluation order.
  ParticleVerdict runParticles(const double* start, const double* control, unsigned steps,
                               const ObjectPoseBelief& belief, unsigned particles,
                               std::uint64_t streamSeed);

  /// The particle jobs of a candidate: everything random drawn, in particle order, from the
  /// streams `streamSeed + i`.
  std::vector<ParticleJob> particleJobs(const double* start, const double* control, unsigned steps,
                                        const ObjectPoseBelief& belief, unsigned particles,
                                        std::uint64_t streamSeed) const;

  /// The verdict of a nominal run alone: its states are valid (it was kept); the interaction
  /// evaluator judges how far it moved the objects.
  ParticleVerdict judgeNominal(const double* start, const double* end) const;

  const physics::UncertaintySampler& sampler() const { return sampler_; }
  /// Movable objects and the target: the bodies whose poses are uncertain.
  const std::vector<std::size_t>& objectBodies() const { return objectBodies_; }
  std::uint64_t particleCount() const { return particleCount_; }

 private:
  Eigen::Vector3d targetPosition(const double* state) const;
  bool displacementWithinLimit(const double* start, const double* end) const;

  physics::PlanningContext& context_;
  physics::UncertaintySampler sampler_;
  double maxDisplacement_;
  std::vector<std::size_t> objectBodies_;
  ParticleRunner runner_;
  std::unique_ptr<ParticleWorkers> workers_;  ///< none: jobs run inline
  std::size_t stateSize_;
  std::size_t controlSize_;
  std::uint64_t particleCount_ = 0;
};

}  // namespace kautham::planners
