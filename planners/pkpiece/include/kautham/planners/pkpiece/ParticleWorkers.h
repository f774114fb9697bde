#pragma once

#include <sys/types.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "kautham/physics/Replay.h"
#include "kautham/planners/pkpiece/ParticleRunner.h"

namespace kautham::planners {

/// Worker processes that run particle jobs, so that p-KPIECE's particles use every core.
///
/// Threads cannot do this: ODE's QuickStep reorders constraints with a process-wide random
/// seed, so two threads stepping at once are not reproducible (DESIGN.md section 4). Each
/// worker is a fork() of the planner's process made once the planning context exists: it owns
/// its copy of the ODE world and runs only a job loop (read a job from its socket, run it with
/// its copy of the ParticleRunner, write the result back) until the socket closes. A job writes
/// the full state, sets its contact parameters and resets ODE's solver seed on every step, so
/// a worker's result is bit-identical to running the job in this process.
///
/// run() spreads the jobs over the workers and this process and returns the results in job
/// order; execute() does the same for whole-plan executions (PlanVerifier), each one
/// physics::execute on the worker's copy of the context with its own random stream. A worker that
/// dies is an error (std::runtime_error naming it), never a hang; after that the pool refuses work.
/// The destructor closes the sockets and reaps every worker.
class ParticleWorkers {
 public:
  /// Forks `workers` processes (at least one); `runner` runs this process's share of the jobs.
  ParticleWorkers(ParticleRunner& runner, unsigned workers);
  ~ParticleWorkers();
  ParticleWorkers(const ParticleWorkers&) = delete;
  ParticleWorkers& operator=(const ParticleWorkers&) = delete;

  /// Runs every job, in workers and inline; results in the order of `jobs`. The physics work
  /// the workers did is added to the context's propagator counters, so statistics count it.
  std::vector<ParticleResult> run(const std::vector<ParticleJob>& jobs);
  /// Executes the whole plan `controls` once per seed, in sampled worlds (physics::execute with
  /// a std::mt19937_64 seeded by it), in workers and inline; whether each run reached the goal
  /// and how far through the plan it got, in the order of `seeds`. A run gives the same answer
  /// in any process.
  std::vector<ExecutionOutcome> execute(const std::vector<physics::ControlStep>& controls,
                                        const std::vector<std::uint64_t>& seeds);

  std::size_t size() const { return workers_.size(); }
  /// The workers' process ids (for tests).
  std::vector<pid_t> pids() const;

 private:
  struct Worker {
    pid_t pid = -1;
    int fd = -1;  ///< this process's end of the worker's socket
    unsigned inFlight = 0;
    bool reaped = false;
  };

  /// How one batch of work goes out: job i to a worker, or run here; a result's most recorded
  /// states.
  struct Batch {
    std::size_t size = 0;
    std::function<void(Worker&, std::size_t)> send;
    std::function<ParticleResult(std::size_t)> runHere;
    std::function<std::size_t(std::size_t)> maxRecords;
  };

  [[noreturn]] void serve(int fd);
  bool serveParticle(int fd);
  bool serveExecution(int fd);
  std::vector<ParticleResult> dispatch(const Batch& batch);
  void send(Worker& worker, std::size_t index, const ParticleJob& job);
  void sendExecution(Worker& worker, std::size_t index,
                     const std::vector<physics::ControlStep>& controls, std::uint64_t seed);
  void transmit(Worker& worker);
  void receive(Worker& worker, const Batch& batch, std::vector<ParticleResult>& results);
  [[noreturn]] void fail(Worker& worker, const char* what);
  void shutdown() noexcept;

  ParticleRunner& runner_;
  std::vector<Worker> workers_;
  std::vector<unsigned char> buffer_;  ///< one message
  bool broken_ = false;
};

}  // namespace kautham::planners
