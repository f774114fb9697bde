#include "kautham/planners/pkpiece/ParticleWorkers.h"

#include "ProcessIo.h"

#include <poll.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>

namespace kautham::planners {

using namespace process_io;

namespace {

// Jobs a worker holds at once: one running, one waiting, so it never idles while this process
// runs a job of its own before handing out the next.
constexpr unsigned kJobsPerWorker = 2;

// Messages. A job starts with its kind (uint64).
// - A particle job is [index, steps, goal stop, n] (uint64), contact (3 doubles), target
//   reference (3), tilt limit (1), target drift limit (1), start state, control, then its n
//   record steps (uint64).
// - An execution job is [index, seed, m] (uint64), then m controls, each [steps, gripper
//   action, object + 1, k] (uint64) and its k values (doubles).
// A result, of either, is [index, valid, goal from, propagations, physics steps, n] (uint64),
// end state, then its n recorded states (an execution: valid is "reached the goal", n = 0).
// Each is read as its fixed part, then the items that part announces.
enum class JobKind : std::uint64_t { Particle = 0, Execution = 1 };
constexpr std::size_t kJobHeader = 4 * sizeof(std::uint64_t) + 8 * sizeof(double);
constexpr std::size_t kExecutionHeader = 3 * sizeof(std::uint64_t);
constexpr std::size_t kControlHeader = 4 * sizeof(std::uint64_t);
constexpr std::size_t kResultHeader = 6 * sizeof(std::uint64_t);

std::size_t jobSize(const ParticleRunner& runner) {
  return kJobHeader + (runner.stateSize() + runner.controlSize()) * sizeof(double);
}

std::size_t resultSize(const ParticleRunner& runner) {
  return kResultHeader + runner.stateSize() * sizeof(double);
}

// Items announced by a message: more than a motion has steps (or a plan controls, or a control
// values) is a corrupt message.
constexpr std::uint64_t kMaxRecords = 1u << 16;
constexpr std::uint64_t kMaxControlValues = 1u << 10;

}  // namespace

ParticleWorkers::ParticleWorkers(ParticleRunner& runner, unsigned workers) : runner_(runner) {
  if (workers == 0) throw std::invalid_argument("ParticleWorkers: at least one worker");
  try {
    for (unsigned i = 0; i < workers; ++i) {
      const Forked forked = forkWithSocket("particle workers");
      if (forked.pid == 0) {
        // The worker: keeps only its own socket.
        for (const Worker& w : workers_) ::close(w.fd);
        serve(forked.fd);
      }
      Worker worker;
      worker.pid = forked.pid;
      worker.fd = forked.fd;
      workers_.push_back(worker);
    }
  } catch (...) {
    shutdown();
    throw;
  }
}

ParticleWorkers::~ParticleWorkers() { shutdown(); }

std::vector<pid_t> ParticleWorkers::pids() const {
  std::vector<pid_t> pids;
  for (const Worker& w : workers_) pids.push_back(w.pid);
  return pids;
}

void ParticleWorkers::serve(int fd) {
  // Ctrl-C reaches the whole process group: the planner's process decides what it means, and
  // this one ends when its socket closes.
  std::signal(SIGINT, SIG_IGN);
  int code = 0;
  try {
    for (;;) {
      std::uint64_t kind = 0;
      const Io in = readAll(fd, &kind, sizeof kind);
      if (in != Io::Ok) {
        code = in == Io::Closed ? 0 : 1;
        break;
      }
      const bool served = kind == static_cast<std::uint64_t>(JobKind::Particle) ? serveParticle(fd)
                          : kind == static_cast<std::uint64_t>(JobKind::Execution)
                              ? serveExecution(fd)
                              : false;
      if (!served) {
        code = 1;
        break;
      }
    }
  } catch (...) {
    code = 2;
  }
  // Never return into the planner's code, never run its destructors or atexit handlers.
  ::_exit(code);
}

namespace {

/// A result message's fixed part and end state (both kinds of job end with one).
void packResult(Packer& pack, std::uint64_t index, bool valid, unsigned goalFrom,
                const physics::PropagationCounters& work, std::size_t records,
                const std::vector<double>& end) {
  pack.put(index);
  pack.put(std::uint64_t{valid ? 1u : 0u});
  pack.put(std::uint64_t{goalFrom});
  pack.put(std::uint64_t{work.propagations});
  pack.put(std::uint64_t{work.physicsSteps});
  pack.put(std::uint64_t{records});
  pack.put(end.data(), end.size() * sizeof(double));
}

physics::PropagationCounters workSince(const physics::PhysicsPropagator& propagator,
                                       const physics::PropagationCounters& before) {
  const physics::PropagationCounters after = propagator.counters();
  physics::PropagationCounters work;
  work.propagations = after.propagations - before.propagations;
  work.physicsSteps = after.physicsSteps - before.physicsSteps;
  return work;
}

}  // namespace

bool ParticleWorkers::serveParticle(int fd) {
  const std::size_t stateSize = runner_.stateSize();
  const std::size_t controlSize = runner_.controlSize();
  ParticleJob job;
  job.start.resize(stateSize);
  job.control.resize(controlSize);
  buffer_.resize(jobSize(runner_));
  if (readAll(fd, buffer_.data(), buffer_.size()) != Io::Ok) return false;
  Unpacker unpack(buffer_);
  const std::uint64_t index = unpack.u64();
  job.steps = static_cast<unsigned>(unpack.u64());
  job.goalStop = static_cast<GoalStop>(unpack.u64());
  const std::uint64_t records = unpack.u64();
  job.contact.friction = unpack.real();
  job.contact.erp = unpack.real();
  job.contact.cfm = unpack.real();
  for (int k = 0; k < 3; ++k) job.targetReference[k] = unpack.real();
  job.tiltLimit = unpack.real();
  job.targetDriftLimit = unpack.real();
  unpack.get(job.start.data(), stateSize * sizeof(double));
  unpack.get(job.control.data(), controlSize * sizeof(double));
  if (records > kMaxRecords) return false;
  std::vector<std::uint64_t> steps(records);
  if (readAll(fd, steps.data(), records * sizeof(std::uint64_t)) != Io::Ok) return false;
  job.recordAfter.assign(steps.begin(), steps.end());

  const physics::PhysicsPropagator& propagator = runner_.context().propagator();
  const physics::PropagationCounters before = propagator.counters();
  const ParticleResult result = runner_.run(job);
  Packer pack(buffer_);
  packResult(pack, index, result.valid, result.goalFrom, workSince(propagator, before),
             result.recorded.size(), result.end);
  for (const std::vector<double>& state : result.recorded)
    pack.put(state.data(), stateSize * sizeof(double));
  return writeAll(fd, buffer_.data(), buffer_.size()) == Io::Ok;
}

bool ParticleWorkers::serveExecution(int fd) {
  buffer_.resize(kExecutionHeader);
  if (readAll(fd, buffer_.data(), buffer_.size()) != Io::Ok) return false;
  Unpacker header(buffer_);
  const std::uint64_t index = header.u64();
  const std::uint64_t seed = header.u64();
  const std::uint64_t count = header.u64();
  if (count > kMaxRecords) return false;
  std::vector<physics::ControlStep> controls(count);
  for (physics::ControlStep& control : controls) {
    buffer_.resize(kControlHeader);
    if (readAll(fd, buffer_.data(), buffer_.size()) != Io::Ok) return false;
    Unpacker unpack(buffer_);
    control.steps = static_cast<unsigned>(unpack.u64());
    control.action = static_cast<physics::GripperAction>(unpack.u64());
    control.object = static_cast<int>(unpack.u64()) - 1;
    const std::uint64_t values = unpack.u64();
    if (values > kMaxControlValues) return false;
    control.values.resize(values);
    if (readAll(fd, control.values.data(), values * sizeof(double)) != Io::Ok) return false;
  }

  const physics::PhysicsPropagator& propagator = runner_.context().propagator();
  const physics::PropagationCounters before = propagator.counters();
  const physics::ExecutionResult run = runner_.execute(controls, seed);
  // The particle result's goalFrom slot carries how far through the plan the run got.
  const ExecutionOutcome outcome = ParticleRunner::outcomeOf(run, controls.size());
  Packer pack(buffer_);
  packResult(pack, index, outcome.reached, outcome.controlsPassed, workSince(propagator, before), 0,
             run.finalState);
  return writeAll(fd, buffer_.data(), buffer_.size()) == Io::Ok;
}

void ParticleWorkers::send(Worker& worker, std::size_t index, const ParticleJob& job) {
  Packer pack(buffer_);
  pack.put(static_cast<std::uint64_t>(JobKind::Particle));
  pack.put(std::uint64_t{index});
  pack.put(std::uint64_t{job.steps});
  pack.put(static_cast<std::uint64_t>(job.goalStop));
  pack.put(std::uint64_t{job.recordAfter.size()});
  pack.put(job.contact.friction);
  pack.put(job.contact.erp);
  pack.put(job.contact.cfm);
  for (int k = 0; k < 3; ++k) pack.put(job.targetReference[k]);
  pack.put(job.tiltLimit);
  pack.put(job.targetDriftLimit);
  pack.put(job.start.data(), runner_.stateSize() * sizeof(double));
  pack.put(job.control.data(), runner_.controlSize() * sizeof(double));
  for (unsigned step : job.recordAfter) pack.put(std::uint64_t{step});
  transmit(worker);
}

void ParticleWorkers::sendExecution(Worker& worker, std::size_t index,
                                    const std::vector<physics::ControlStep>& controls,
                                    std::uint64_t seed) {
  Packer pack(buffer_);
  pack.put(static_cast<std::uint64_t>(JobKind::Execution));
  pack.put(std::uint64_t{index});
  pack.put(seed);
  pack.put(std::uint64_t{controls.size()});
  for (const physics::ControlStep& control : controls) {
    pack.put(std::uint64_t{control.steps});
    pack.put(static_cast<std::uint64_t>(control.action));
    pack.put(static_cast<std::uint64_t>(control.object + 1));
    pack.put(std::uint64_t{control.values.size()});
    pack.put(control.values.data(), control.values.size() * sizeof(double));
  }
  transmit(worker);
}

void ParticleWorkers::transmit(Worker& worker) {
  const Io out = writeAll(worker.fd, buffer_.data(), buffer_.size());
  if (out != Io::Ok) fail(worker, out == Io::Closed ? "closed its socket" : "cannot be written to");
  ++worker.inFlight;
}

void ParticleWorkers::receive(Worker& worker, const Batch& batch,
                              std::vector<ParticleResult>& results) {
  buffer_.resize(resultSize(runner_));
  const Io in = readAll(worker.fd, buffer_.data(), buffer_.size());
  if (in != Io::Ok) fail(worker, in == Io::Closed ? "closed its socket" : "cannot be read from");
  Unpacker unpack(buffer_);
  const std::uint64_t index = unpack.u64();
  if (index >= results.size()) fail(worker, "answered a job it was not given");
  ParticleResult& result = results[index];
  result.valid = unpack.u64() != 0;
  result.goalFrom = static_cast<unsigned>(unpack.u64());
  physics::PropagationCounters work;
  work.propagations = unpack.u64();
  work.physicsSteps = unpack.u64();
  const std::uint64_t records = unpack.u64();
  if (records > batch.maxRecords(index))
    fail(worker, "announced more recorded states than its job asked for");
  result.end.resize(runner_.stateSize());
  unpack.get(result.end.data(), runner_.stateSize() * sizeof(double));
  result.recorded.assign(records, std::vector<double>(runner_.stateSize()));
  for (std::vector<double>& state : result.recorded) {
    const Io more = readAll(worker.fd, state.data(), state.size() * sizeof(double));
    if (more != Io::Ok)
      fail(worker, more == Io::Closed ? "closed its socket" : "cannot be read from");
  }
  runner_.context().propagator().addCounters(work);
  --worker.inFlight;
}

void ParticleWorkers::fail(Worker& worker, const char* what) {
  broken_ = true;
  std::string how = "still running";
  if (!worker.reaped) {
    // A worker that closed its socket is exiting: give it a moment to become a zombie, so the
    // report says how it ended; one that does not is killed (a pool never waits unbounded).
    int status = 0;
    pid_t r = 0;
    for (int tries = 0; tries < 100 && (r = waitFor(worker.pid, &status, WNOHANG)) == 0; ++tries)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (r == 0) {
      ::kill(worker.pid, SIGKILL);
      r = waitFor(worker.pid, &status, 0);
      how = "did not exit and was killed";
    } else if (r == worker.pid) {
      how = describeStatus(status);
    } else {
      how = "cannot be waited for";
    }
    worker.reaped = true;
  }
  const std::size_t number = static_cast<std::size_t>(&worker - workers_.data());
  throw std::runtime_error("particle worker " + std::to_string(number) + " (pid " +
                           std::to_string(worker.pid) + ") " + what + ": " + how);
}

std::vector<ParticleResult> ParticleWorkers::run(const std::vector<ParticleJob>& jobs) {
  Batch batch;
  batch.size = jobs.size();
  batch.send = [&](Worker& worker, std::size_t i) { send(worker, i, jobs[i]); };
  batch.runHere = [&](std::size_t i) { return runner_.run(jobs[i]); };
  batch.maxRecords = [&](std::size_t i) { return jobs[i].recordAfter.size(); };
  return dispatch(batch);
}

std::vector<ExecutionOutcome> ParticleWorkers::execute(
    const std::vector<physics::ControlStep>& controls, const std::vector<std::uint64_t>& seeds) {
  Batch batch;
  batch.size = seeds.size();
  batch.send = [&](Worker& worker, std::size_t i) { sendExecution(worker, i, controls, seeds[i]); };
  batch.runHere = [&](std::size_t i) {
    const physics::ExecutionResult run = runner_.execute(controls, seeds[i]);
    const ExecutionOutcome outcome = ParticleRunner::outcomeOf(run, controls.size());
    ParticleResult result;
    result.valid = outcome.reached;
    result.goalFrom = outcome.controlsPassed;
    result.end = run.finalState;
    return result;
  };
  batch.maxRecords = [](std::size_t) { return std::size_t{0}; };
  const std::vector<ParticleResult> results = dispatch(batch);
  std::vector<ExecutionOutcome> outcomes(results.size());
  for (std::size_t i = 0; i < results.size(); ++i) {
    outcomes[i].reached = results[i].valid;
    if (results[i].goalFrom > controls.size())
      throw std::runtime_error(
          "particle workers: an execution passed more controls than its plan has");
    outcomes[i].controlsPassed = results[i].goalFrom;
  }
  return outcomes;
}

std::vector<ParticleResult> ParticleWorkers::dispatch(const Batch& batch) {
  if (broken_) throw std::runtime_error("particle workers: unusable since a worker died");
  std::vector<ParticleResult> results(batch.size);
  for (Worker& w : workers_) w.inFlight = 0;
  std::size_t next = 0;
  std::size_t done = 0;
  // Round by round, one job per worker, keeping the last job for this process: a batch of
  // four on three processes runs as 1 + 2 + 1, not 2 + 2 + 0.
  const auto handOut = [&] {
    for (unsigned round = 0; round < kJobsPerWorker; ++round)
      for (Worker& w : workers_)
        if (w.inFlight <= round && batch.size - next > 1) {
          batch.send(w, next);
          ++next;
        }
  };
  std::vector<pollfd> fds(workers_.size());
  handOut();
  while (done < batch.size) {
    if (next < batch.size) {
      results[next] = batch.runHere(next);
      ++next;
      ++done;
    }
    bool busy = false;
    for (std::size_t i = 0; i < workers_.size(); ++i) {
      fds[i].fd = workers_[i].inFlight > 0 ? workers_[i].fd : -1;  // poll skips negative fds
      fds[i].events = POLLIN;
      fds[i].revents = 0;
      busy = busy || workers_[i].inFlight > 0;
    }
    if (busy) {
      // Wait only when this process has no job left to run itself.
      const int ready = ::poll(fds.data(), fds.size(), next < batch.size ? 0 : -1);
      if (ready < 0 && errno != EINTR)
        throw std::system_error(errno, std::generic_category(), "particle workers: poll");
      for (std::size_t i = 0; ready > 0 && i < workers_.size(); ++i)
        if (fds[i].fd >= 0 && (fds[i].revents & (POLLIN | POLLHUP | POLLERR))) {
          receive(workers_[i], batch, results);
          ++done;
        }
    }
    handOut();
  }
  return results;
}

void ParticleWorkers::shutdown() noexcept {
  for (Worker& w : workers_)
    if (w.fd >= 0) {
      ::close(w.fd);
      w.fd = -1;
    }
  // Each worker sees its socket close after the job it is running, if any, and exits.
  for (Worker& w : workers_)
    if (!w.reaped) {
      int status = 0;
      waitFor(w.pid, &status, 0);
      w.reaped = true;
    }
}

}  // namespace kautham::planners
