#include "kautham/planners/pkpiece/MotionEvaluator.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include <ompl/control/spaces/RealVectorControlSpace.h>

#include "kautham/physics/WorldStateSpace.h"

namespace kautham::planners {

std::optional<NominalMotion> pacedMotion(const ompl::control::SpaceInformation& si,
                                         std::vector<double> oneStep, double largest,
                                         double distance, double maxSpeed) {
  if (!std::isfinite(largest) || largest <= 0.0) return std::nullopt;
  const double slowest = maxSpeed > 0.0 ? distance / (maxSpeed * si.getPropagationStepSize()) : 0.0;
  NominalMotion motion;
  motion.steps = std::clamp(static_cast<unsigned>(std::ceil(std::max(largest, slowest))),
                            si.getMinControlDuration(), si.getMaxControlDuration());
  motion.control = std::move(oneStep);
  for (double& u : motion.control) u /= std::max(static_cast<double>(motion.steps), largest);
  return motion;
}

MotionEvaluator::MotionEvaluator(physics::PlanningContext& context, double maxDisplacement)
    : context_(context),
      sampler_(context.problem(), context.layout()),
      maxDisplacement_(maxDisplacement),
      runner_(context),
      stateSize_(runner_.stateSize()),
      controlSize_(runner_.controlSize()) {
  const auto& bodies = context.layout().bodies;
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (bodies[b].role != physics::BodyRole::Robot) objectBodies_.push_back(b);
}

MotionEvaluator::~MotionEvaluator() = default;

void MotionEvaluator::useWorkers(unsigned threads) {
  workers_.reset();
  if (threads > 1) workers_ = std::make_unique<ParticleWorkers>(runner_, threads - 1);
}

std::vector<ExecutionOutcome> MotionEvaluator::runExecutions(
    const std::vector<physics::ControlStep>& controls, const std::vector<std::uint64_t>& seeds) {
  if (workers_) return workers_->execute(controls, seeds);
  std::vector<ExecutionOutcome> outcomes;
  for (std::uint64_t seed : seeds)
    outcomes.push_back(ParticleRunner::outcomeOf(runner_.execute(controls, seed), controls.size()));
  return outcomes;
}

void MotionEvaluator::setNominalMargins(double tiltMargin, double targetMargin) {
  // 0 in a job: the scene's own limit, which the validity checker applies anyway.
  const core::InteractionConstraints& scene = context_.problem().interaction;
  nominalTiltLimit_ = tiltMargin < 1.0 ? tiltMargin * scene.maxTilt : 0.0;
  nominalTargetDriftLimit_ = targetMargin < 1.0 ? targetMargin * scene.targetTolerance : 0.0;
}

ParticleJob MotionEvaluator::nominalJob(const double* start, const NominalMotion& motion,
                                        bool throughGoal) const {
  ParticleJob job;
  job.start.assign(start, start + stateSize_);
  job.control = motion.control;
  job.steps = motion.steps;
  job.contact = context_.world().contactParameters();
  job.targetReference = context_.validityChecker().targetStart();
  job.tiltLimit = nominalTiltLimit_;
  job.targetDriftLimit = nominalTargetDriftLimit_;
  for (unsigned s = 1; s <= motion.steps; ++s) job.recordAfter.push_back(s);
  job.goalStop = throughGoal ? GoalStop::Leaving : GoalStop::Entering;
  return job;
}

std::pair<physics::Violation, std::optional<std::size_t>> MotionEvaluator::brokenRule(
    const ParticleJob& job, const double* state) const {
  // Judged against the job's own target reference, as the run judged it.
  const physics::WorldValidityChecker& checker = context_.validityChecker();
  const physics::Violation violation = checker.check(state, job.targetReference);
  if (violation == physics::Violation::None) {  // within the scene's rules, not the job's margins
    if (const auto tilted = runner_.tiltedBeyond(state, job.tiltLimit))
      return {physics::Violation::ObjectTilted, tilted};
    if (runner_.targetDriftedBeyond(state, job.targetReference, job.targetDriftLimit))
      return {physics::Violation::TargetMoved, checker.targetBody()};
  }
  return {violation, physics::isObjectRule(violation)
                         ? checker.offendingObject(state, job.targetReference, std::nullopt)
                         : std::nullopt};
}

NominalRun MotionEvaluator::nominalRun(const double* start, const ParticleJob& job,
                                       ParticleResult&& result) const {
  NominalRun run;
  if (!result.valid && !result.end.empty())
    std::tie(run.stoppedBy, run.stoppedOn) = brokenRule(job, result.end.data());
  run.steps = static_cast<unsigned>(result.recorded.size());
  run.states = std::move(result.recorded);
  run.end = run.states.empty() ? std::vector<double>(start, start + stateSize_) : run.states.back();
  run.goalFrom = result.goalFrom;
  run.reachedGoal = result.goalFrom > 0;
  return run;
}

NominalRun MotionEvaluator::runNominal(const double* start, const double* control, unsigned steps,
                                       bool throughGoal) {
  const NominalMotion motion{std::vector<double>(control, control + controlSize_), steps};
  const ParticleJob job = nominalJob(start, motion, throughGoal);
  return nominalRun(start, job, runner_.run(job));
}

std::vector<NominalRun> MotionEvaluator::runNominals(const double* start,
                                                     const std::vector<NominalMotion>& motions,
                                                     bool throughGoal) {
  std::vector<ParticleJob> jobs;
  for (const NominalMotion& motion : motions)
    jobs.push_back(nominalJob(start, motion, throughGoal));
  std::vector<ParticleResult> results = runJobs(jobs);
  std::vector<NominalRun> runs;
  for (std::size_t i = 0; i < results.size(); ++i)
    runs.push_back(nominalRun(start, jobs[i], std::move(results[i])));
  return runs;
}

Eigen::Vector3d MotionEvaluator::targetPosition(const double* state) const {
  // A particle's target stands where its start was sampled; without a target nothing drifts.
  const auto target = context_.validityChecker().targetBody();
  return target ? physics::WorldLayout::position(state, *target)
                : context_.validityChecker().targetStart();
}

std::optional<std::size_t> MotionEvaluator::movedTooFar(const double* start,
                                                        const double* end) const {
  for (std::size_t b : objectBodies_) {
    const Eigen::Vector3d a = physics::WorldLayout::position(start, b);
    const Eigen::Vector3d c = physics::WorldLayout::position(end, b);
    if ((c - a).norm() > maxDisplacement_) return b;
  }
  return std::nullopt;
}

bool MotionEvaluator::displacementWithinLimit(const double* start, const double* end) const {
  return !movedTooFar(start, end);
}

void MotionEvaluator::resetCounts() {
  particleCount_ = 0;
  certainEarly_ = 0;
  failures_ = FailureTally{};
}

void MotionEvaluator::addCounts(std::uint64_t particles, std::uint64_t certainEarly,
                                const FailureTally& failures) {
  particleCount_ += particles;
  certainEarly_ += certainEarly;
  for (const FailureTally::Entry& entry : failures.entries()) failures_.add(entry);
}

void MotionEvaluator::tallyLastFailure(const ParticleJob& job, const ParticleVerdict& verdict) {
  const double* end = verdict.ends.back().data();
  if (!verdict.endValid.back()) {
    // The run stopped at its first invalid state: the rule it broke.
    const auto [violation, object] = brokenRule(job, end);
    failures_.addViolation(violation, object);
  } else if (!verdict.endInteractionOk.back()) {
    failures_.addDisplacement(*movedTooFar(job.start.data(), end));
  }
}

ParticleVerdict MotionEvaluator::judgeNominal(const double* start, const double* end) const {
  ParticleVerdict verdict;
  verdict.interaction = displacementWithinLimit(start, end) ? 1.0 : 0.0;
  return verdict;
}

std::vector<ParticleJob> MotionEvaluator::particleJobs(const ParticleRequest& request) const {
  std::vector<ParticleJob> jobs(request.particles);
  for (unsigned p = 0; p < request.particles; ++p) {
    ParticleJob& job = jobs[p];
    std::mt19937_64 rng(request.streamSeed + p);
    job.start.assign(request.start, request.start + stateSize_);
    // The sampled poses first: an object the spread carries takes its particle's state.
    request.poses->samplePoses(job.start.data(), rng);
    if (request.robots) request.robots->apply(p, job.start.data());
    job.contact = sampler_.sampleContact(rng);
    job.control.resize(controlSize_);
    sampler_.perturbControl(request.control, job.control.data(), controlSize_, rng);
    job.steps = request.steps;
    job.targetReference = targetPosition(job.start.data());
    job.recordAfter = request.recordAfter;
  }
  return jobs;
}

std::vector<ParticleResult> MotionEvaluator::runJobs(const std::vector<ParticleJob>& jobs) {
  if (workers_) return workers_->run(jobs);
  std::vector<ParticleResult> results;
  results.reserve(jobs.size());
  for (const ParticleJob& job : jobs) results.push_back(runner_.run(job));
  return results;
}

ParticleVerdict MotionEvaluator::runParticles(const ParticleRequest& request, double toBeat) {
  ParticleVerdict verdict;
  const unsigned particles = request.particles;
  verdict.particles = particles;
  if (particles == 0) return verdict;
  const std::vector<ParticleJob> jobs = particleJobs(request);
  physics::World& world = context_.world();
  const physics::ContactParameters mean = world.contactParameters();
  // Batches only serve pruning: with nothing to beat every particle runs, so all go out at
  // once and no process waits at a batch's end for another's last job (the same results).
  const std::size_t batch =
      toBeat < 0.0 ? jobs.size() : std::max<std::size_t>(kParticleBatch, threads());
  // The sequential test's batch is fixed, whatever the threads, so the work done is too.
  const std::size_t certainAfter = request.certainAfter < particles ? request.certainAfter : 0;
  std::size_t ran = 0;
  try {
    while (ran < jobs.size()) {
      const std::size_t size = ran == 0 && certainAfter > 0 ? certainAfter : batch;
      const std::size_t end = std::min(jobs.size(), ran + size);
      std::vector<ParticleResult> results =
          runJobs(std::vector<ParticleJob>(jobs.begin() + ran, jobs.begin() + end));
      for (std::size_t p = ran; p < end; ++p) {
        addOutcome(verdict, jobs[p].start.data(), std::move(results[p - ran]));
        tallyLastFailure(jobs[p], verdict);
      }
      ran = end;
      if (ran == certainAfter && allSucceeded(verdict)) {
        verdict.particles = static_cast<unsigned>(ran);
        ++certainEarly_;
        break;
      }
      // Every remaining particle valid is the best case; computed as belief() computes, so
      // that equal counts round equally and a pruned candidate could at most tie.
      const auto bestFraction = [&](const std::vector<char>& flags) {
        const auto count = std::count(flags.begin(), flags.end(), 1);
        return static_cast<double>(count + (jobs.size() - ran)) / particles;
      };
      const double bound = bestFraction(verdict.endValid) * bestFraction(verdict.endInteractionOk);
      if (ran < jobs.size() && bound <= toBeat) {
        verdict.pruned = true;
        break;
      }
    }
  } catch (...) {
    world.setContactParameters(mean);
    throw;
  }
  world.setContactParameters(mean);
  particleCount_ += ran;
  verdict.tally();
  return verdict;
}

bool MotionEvaluator::allSucceeded(const ParticleVerdict& verdict) {
  const auto all = [](const std::vector<char>& flags) {
    return std::all_of(flags.begin(), flags.end(), [](char f) { return f == 1; });
  };
  return all(verdict.endValid) && all(verdict.endInteractionOk);
}

void MotionEvaluator::addOutcome(ParticleVerdict& verdict, const double* start,
                                 ParticleResult&& result) const {
  // The pre-grasp pose follows the target: a particle whose target was sampled elsewhere must
  // reach the goal around it, as an execution in `kautham validate` must.
  const std::unique_ptr<physics::WorkspaceGoal> moved = context_.goalForStart(start);
  const physics::WorkspaceGoal& goal = moved ? *moved : context_.goal();
  const auto judge = [&](const std::vector<double>& state, bool valid, auto& interactionOk,
                         auto& inGoal) {
    const bool ok = displacementWithinLimit(start, state.data());
    interactionOk.push_back(ok);
    inGoal.push_back(valid && ok && goal.reached(state.data()));
  };
  judge(result.end, result.valid, verdict.endInteractionOk, verdict.endInGoal);
  verdict.endValid.push_back(result.valid);
  std::vector<char> recordedInGoal;
  std::vector<char> recordedInteractionOk;
  for (const std::vector<double>& state : result.recorded)
    judge(state, true, recordedInteractionOk, recordedInGoal);
  verdict.starts.emplace_back(start, start + stateSize_);
  verdict.ends.push_back(std::move(result.end));
  verdict.recorded.push_back(std::move(result.recorded));
  verdict.recordedInGoal.push_back(std::move(recordedInGoal));
  verdict.recordedInteractionOk.push_back(std::move(recordedInteractionOk));
}

}  // namespace kautham::planners
