#include "kautham/planners/MotionEvaluator.h"

#include <algorithm>

#include <ompl/control/spaces/RealVectorControlSpace.h>

#include "kautham/physics/WorldStateSpace.h"

namespace kautham::planners {

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

NominalRun MotionEvaluator::runNominal(const double* start, const double* control, unsigned steps) {
  NominalRun run;
  run.end.assign(start, start + stateSize_);
  std::vector<double> next(stateSize_);
  for (unsigned i = 0; i < steps; ++i) {
    if (!runner_.step(run.end.data(), control, next.data(),
                      context_.validityChecker().targetStart()))
      break;
    run.end.swap(next);
    run.states.push_back(run.end);
    run.steps = i + 1;
    if (context_.goal().reached(run.end.data())) {
      run.reachedGoal = true;
      break;
    }
  }
  return run;
}

Eigen::Vector3d MotionEvaluator::targetPosition(const double* state) const {
  // A particle's target stands where its start was sampled; without a target nothing drifts.
  const auto target = context_.validityChecker().targetBody();
  return target ? physics::WorldLayout::position(state, *target)
                : context_.validityChecker().targetStart();
}

bool MotionEvaluator::displacementWithinLimit(const double* start, const double* end) const {
  for (std::size_t b : objectBodies_) {
    const Eigen::Vector3d a = physics::WorldLayout::position(start, b);
    const Eigen::Vector3d c = physics::WorldLayout::position(end, b);
    if ((c - a).norm() > maxDisplacement_) return false;
  }
  return true;
}

ParticleVerdict MotionEvaluator::judgeNominal(const double* start, const double* end) const {
  ParticleVerdict verdict;
  verdict.interaction = displacementWithinLimit(start, end) ? 1.0 : 0.0;
  return verdict;
}

std::vector<ParticleJob> MotionEvaluator::particleJobs(const double* start, const double* control,
                                                       unsigned steps,
                                                       const ObjectPoseBelief& belief,
                                                       unsigned particles,
                                                       std::uint64_t streamSeed) const {
  std::vector<ParticleJob> jobs(particles);
  for (unsigned p = 0; p < particles; ++p) {
    ParticleJob& job = jobs[p];
    std::mt19937_64 rng(streamSeed + p);
    job.start.assign(start, start + stateSize_);
    belief.samplePoses(job.start.data(), rng);
    job.contact = sampler_.sampleContact(rng);
    job.control.resize(controlSize_);
    sampler_.perturbControl(control, job.control.data(), controlSize_, rng);
    job.steps = steps;
    job.targetReference = targetPosition(job.start.data());
  }
  return jobs;
}

ParticleVerdict MotionEvaluator::runParticles(const double* start, const double* control,
                                              unsigned steps, const ObjectPoseBelief& belief,
                                              unsigned particles, std::uint64_t streamSeed) {
  ParticleVerdict verdict;
  if (particles == 0) return verdict;
  const std::vector<ParticleJob> jobs =
      particleJobs(start, control, steps, belief, particles, streamSeed);
  physics::World& world = context_.world();
  const physics::ContactParameters mean = world.contactParameters();
  std::vector<ParticleResult> results;
  try {
    if (workers_) {
      results = workers_->run(jobs);
    } else {
      results.reserve(jobs.size());
      for (const ParticleJob& job : jobs) results.push_back(runner_.run(job));
    }
  } catch (...) {
    world.setContactParameters(mean);
    throw;
  }
  world.setContactParameters(mean);
  unsigned validStates = 0;
  unsigned validInteractions = 0;
  unsigned inGoal = 0;
  for (std::size_t p = 0; p < jobs.size(); ++p) {
    validStates += results[p].valid ? 1 : 0;
    inGoal += results[p].valid && context_.goal().reached(results[p].end.data()) ? 1 : 0;
    validInteractions +=
        displacementWithinLimit(jobs[p].start.data(), results[p].end.data()) ? 1 : 0;
    verdict.ends.push_back(std::move(results[p].end));
  }
  particleCount_ += particles;
  verdict.stateValidity = static_cast<double>(validStates) / particles;
  verdict.interaction = static_cast<double>(validInteractions) / particles;
  verdict.goal = static_cast<double>(inGoal) / particles;
  return verdict;
}

}  // namespace kautham::planners
