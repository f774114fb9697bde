#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include "kautham/physics/PlanningContext.h"
#include "kautham/physics/UncertaintySampler.h"
#include "kautham/planners/pkpiece/FailureTally.h"
#include "kautham/planners/pkpiece/ObjectPoseBelief.h"
#include "kautham/planners/pkpiece/ParticleRunner.h"
#include "kautham/planners/pkpiece/ParticleVerdict.h"
#include "kautham/planners/pkpiece/ParticleWorkers.h"
#include "kautham/planners/pkpiece/RobotSpread.h"

namespace kautham::planners {

/// A candidate motion run nominally: the mean contact parameters, the exact control and the
/// start state as the tree has it.
struct NominalRun {
  std::vector<double> end;                  ///< the last valid state
  std::vector<std::vector<double>> states;  ///< the state after each valid step (back() == end)
  unsigned steps = 0;        ///< valid propagation steps (0: the first step was invalid)
  bool reachedGoal = false;  ///< it entered the goal region
  /// Steps after which it was first in the goal (0: never). Run through the goal, it goes on
  /// while it stays inside, so states goalFrom..steps are all in the goal.
  unsigned goalFrom = 0;
  /// The rule its first invalid state broke (None: every state was valid), and the object that
  /// broke it (none for the robot's rules).
  physics::Violation stoppedBy = physics::Violation::None;
  std::optional<std::size_t> stoppedOn;
};

/// A candidate's control, held for up to `steps` propagation steps.
struct NominalMotion {
  std::vector<double> control;
  unsigned steps = 0;
};

/// The control `oneStep` (a whole motion done in one propagation step) spread over the fewest
/// steps that bring `largest` (its largest ratio to a control or speed limit) to at most 1 and
/// keep the link, `distance` (m) from its aim, below `maxSpeed` (m/s; 0: no limit); the longest
/// duration, scaled down, when none does. None when `largest` is not a positive number.
std::optional<NominalMotion> pacedMotion(const ompl::control::SpaceInformation& si,
                                         std::vector<double> oneStep, double largest,
                                         double distance, double maxSpeed);

/// A candidate motion to judge with particles, and where its particles start.
struct ParticleRequest {
  const double* start = nullptr;  ///< the tree's state the candidate starts from
  const double* control = nullptr;
  unsigned steps = 0;
  const ObjectPoseBelief* poses = nullptr;  ///< U_rgn at the start (required)
  /// The robot states the parent's particles reached; null: every particle starts with the
  /// robot as in `start`.
  const RobotSpread* robots = nullptr;
  std::vector<unsigned> recordAfter;  ///< steps after which each particle's state is kept
  unsigned particles = 0;             ///< n_p
  /// A sequential test: once this many particles have run and every one ended valid with its
  /// objects moved at most d, the rest are not run and these judge the motion (0: all n_p).
  unsigned certainAfter = 0;
  std::uint64_t streamSeed = 0;  ///< particle i draws from the stream streamSeed + i
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

  /// Propagates `control` from `start` for up to `steps` steps, keeping the valid prefix. It
  /// stops at the first state in the goal, or, `throughGoal`, at the last one before the
  /// motion leaves the goal again.
  NominalRun runNominal(const double* start, const double* control, unsigned steps,
                        bool throughGoal = false);
  /// runNominal for several motions from one start, spread over the worker processes like
  /// particles (the same runs as one by one, in the order given).
  std::vector<NominalRun> runNominals(const double* start,
                                      const std::vector<NominalMotion>& motions, bool throughGoal);

  /// Nominal runs keep every movable object within `tiltMargin` times the scene's maxTilt
  /// (tilt_margin: the plan keeps away from tipping cans) and the target within `targetMargin`
  /// times its targetTolerance of its start (target_margin: the pushes keep off the target): a
  /// state beyond either breaks the scene's rule. 1: the scene's limit. Particles and
  /// whole-plan executions judge by the scene's rules.
  void setNominalMargins(double tiltMargin, double targetMargin);

  /// Spreads particle jobs over `threads` processes: this one and threads - 1 forked workers
  /// (ParticleWorkers). 1: every job runs inline. Workers from an earlier call are reaped.
  void useWorkers(unsigned threads);
  unsigned threads() const { return workers_ ? static_cast<unsigned>(workers_->size()) + 1 : 1; }
  /// Executes the whole plan `controls` once per seed in sampled worlds, as `kautham validate`
  /// does (physics::execute, a std::mt19937_64 seeded by it), over the threads() processes;
  /// whether each reached the goal and how far through the plan it got, in the order of
  /// `seeds`, the same for any threads().
  std::vector<ExecutionOutcome> runExecutions(const std::vector<physics::ControlStep>& controls,
                                              const std::vector<std::uint64_t>& seeds);

  /// Runs the request's particle motions: start poses drawn from its pose belief, the robot
  /// from its robot spread, contact parameters and control noise from the problem's
  /// uncertainty; particle i uses the random stream `streamSeed + i`, so the verdict does not
  /// depend on evaluation order or on threads().
  ///
  /// Particles run in batches of kParticleBatch (or threads(), if more). After each batch the
  /// best belief the remaining particles could still give is bounded; once it cannot exceed
  /// `toBeat`, the run stops and the verdict is `pruned`. A negative `toBeat` never prunes,
  /// and then all the particles run as one batch.
  /// With the request's certainAfter m (0 < m < n_p), the first m particles run as a batch
  /// of their own; if all succeed, the verdict rests on them (`particles` m, belief 1).
  /// A particle counts as in the goal only if it is valid and moved the objects at most d.
  ParticleVerdict runParticles(const ParticleRequest& request, double toBeat = -1.0);
  /// The particle jobs of a request: everything random drawn, in particle order.
  std::vector<ParticleJob> particleJobs(const ParticleRequest& request) const;
  /// Particles run between two pruning checks: fixed, so the work done (and so every
  /// statistic) is the same for any number of threads up to this many.
  static constexpr std::size_t kParticleBatch = 4;
  /// The verdict of a nominal run alone: its states are valid (it was kept); the interaction
  /// evaluator judges how far it moved the objects.
  ParticleVerdict judgeNominal(const double* start, const double* end) const;

  const physics::UncertaintySampler& sampler() const { return sampler_; }
  /// Movable objects and the target: the bodies whose poses are uncertain.
  const std::vector<std::size_t>& objectBodies() const { return objectBodies_; }
  std::uint64_t particleCount() const { return particleCount_; }
  /// Candidate judgements the sequential test ended early, on their first particles alone.
  std::uint64_t certainEarly() const { return certainEarly_; }
  /// Why the particles run so far failed (a diagnosis; nothing reads it back).
  const FailureTally& particleFailures() const { return failures_; }
  /// Forgets the particles run so far and their failures (the planner's clear()).
  void resetCounts();
  /// Adds particles run elsewhere (a tree grown in a process of its own) to the counts.
  void addCounts(std::uint64_t particles, std::uint64_t certainEarly, const FailureTally& failures);

 private:
  Eigen::Vector3d targetPosition(const double* state) const;
  bool displacementWithinLimit(const double* start, const double* end) const;
  /// The first object that moved more than d between the two states, if any.
  std::optional<std::size_t> movedTooFar(const double* start, const double* end) const;
  /// Adds the verdict's last particle (run as `job`) to particleFailures(), if it failed.
  void tallyLastFailure(const ParticleJob& job, const ParticleVerdict& verdict);
  /// A nominal run as a job: the mean contact parameters, the exact control, every state kept.
  ParticleJob nominalJob(const double* start, const NominalMotion& motion, bool throughGoal) const;
  NominalRun nominalRun(const double* start, const ParticleJob& job, ParticleResult&& result) const;
  /// The rule `state` breaks, judged as `job` judged it, and the object that broke it.
  std::pair<physics::Violation, std::optional<std::size_t>> brokenRule(const ParticleJob& job,
                                                                       const double* state) const;
  /// Every particle so far ended valid with its objects moved at most d.
  static bool allSucceeded(const ParticleVerdict& verdict);
  /// Appends a particle's outcome, judged against its own start, to the verdict.
  void addOutcome(ParticleVerdict& verdict, const double* start, ParticleResult&& result) const;
  std::vector<ParticleResult> runJobs(const std::vector<ParticleJob>& jobs);

  physics::PlanningContext& context_;
  physics::UncertaintySampler sampler_;
  double maxDisplacement_;
  double nominalTiltLimit_ = 0.0;
  double nominalTargetDriftLimit_ = 0.0;
  std::vector<std::size_t> objectBodies_;
  ParticleRunner runner_;
  std::unique_ptr<ParticleWorkers> workers_;  ///< none: jobs run inline
  std::size_t stateSize_;
  std::size_t controlSize_;
  std::uint64_t particleCount_ = 0;
  std::uint64_t certainEarly_ = 0;
  FailureTally failures_;
};

}  // namespace kautham::planners
