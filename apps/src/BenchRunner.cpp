#include "BenchRunner.h"

#include <chrono>
#include <csignal>
#include <deque>
#include <fstream>
#include <memory>
#include <thread>

#include <fmt/format.h>
#include <ompl/tools/benchmark/MachineSpecs.h>

#include "BenchLayout.h"
#include "BenchProgress.h"
#include "BenchRunResult.h"
#include "ChildProcess.h"
#include "PlanFile.h"
#include "kautham/core/InputError.h"

namespace kautham::apps {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

volatile std::sig_atomic_t interruptSignal = 0;

extern "C" void onInterrupt(int signal) { interruptSignal = signal; }

/// Catches SIGINT and SIGTERM while it lives: the main loop sees the flag and stops cleanly.
class InterruptGuard {
 public:
  InterruptGuard() {
    interruptSignal = 0;
    struct sigaction action {};
    action.sa_handler = onInterrupt;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &oldInt_);
    sigaction(SIGTERM, &action, &oldTerm_);
  }
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
  ~InterruptGuard() {
    sigaction(SIGINT, &oldInt_, nullptr);
    sigaction(SIGTERM, &oldTerm_, nullptr);
  }
  bool raised() const { return interruptSignal != 0; }

 private:
  struct sigaction oldInt_ {};
  struct sigaction oldTerm_ {};
};

/// A run in progress: its plan child, then perhaps its validation child.
struct Job {
  RunKey key;
  json setup;
  RunEvidence evidence;
  RunPlace place;
  std::unique_ptr<ChildProcess> child;
  bool validating = false;
};

std::optional<json> readJsonIfThere(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  try {
    return json::parse(in);
  } catch (const json::parse_error&) {
    return std::nullopt;
  }
}

/// The command's line at the top of the run's console file.
void appendCommand(const fs::path& console, const std::vector<std::string>& command, bool fresh) {
  fs::create_directories(console.parent_path());
  std::ofstream out(console, fresh ? std::ios::trunc : std::ios::app);
  out << "$";
  for (const std::string& a : command) out << ' ' << a;
  out << '\n';
}

class BenchRunner {
 public:
  BenchRunner(const BenchSpec& spec, const Preflight& preflight, const BenchRunOptions& options)
      : spec_(spec), preflight_(preflight), options_(options), layout_(options.output) {}

  BenchSummary run() {
    std::deque<RunKey> pending = runsToMake();
    const InterruptGuard interrupt;
    BenchProgress progress(summary_.total, summary_.resumed);
    host_ = ompl::machine::getHostname();
    cpuInfo_ = ompl::machine::getCPUInfo();
    while ((!pending.empty() || !jobs_.empty()) && !interrupt.raised()) {
      while (jobs_.size() < options_.jobs && !pending.empty()) {
        startPlan(pending.front());
        pending.pop_front();
      }
      advanceJobs();
      progress.show(summary_.done, summary_.solved, summary_.failed);
      if (!jobs_.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    progress.clear();
    if (interrupt.raised()) abandonJobs();
    summary_.interrupted = interrupt.raised();
    return summary_;
  }

 private:
  std::string problem(const RunKey& key) const { return problemName(spec_.problems[key.problem]); }
  const BenchConfig& config(const RunKey& key) const { return spec_.configs[key.config]; }
  fs::path planFile(const RunKey& key) const {
    return layout_.plan(problem(key), config(key).name, key.run);
  }
  fs::path validationFile(const RunKey& key) const {
    return layout_.validation(problem(key), config(key).name, key.run);
  }
  fs::path consoleFile(const RunKey& key) const {
    return layout_.console(problem(key), config(key).name, key.run);
  }
  json setupOf(const RunKey& key) const {
    return runSetup(spec_, key, preflight_.timeLimits[key.problem][key.config]);
  }

  /// This shard's runs without a result; those with one are counted as done.
  std::deque<RunKey> runsToMake() {
    const RunsInOutput runs = runsInOutput(spec_, preflight_, options_.output, options_.shard);
    summary_.total = runs.toMake.size() + runs.made.size();
    summary_.resumed = runs.made.size();
    for (const json& result : runs.made) count(result);
    return std::deque<RunKey>(runs.toMake.begin(), runs.toMake.end());
  }

  void count(const json& result) {
    ++summary_.done;
    summary_.solved += result.value("solved", false);
    summary_.failed += result.value("failed", false);
  }

  std::vector<std::string> planCommand(const RunKey& key) const {
    const BenchConfig& c = config(key);
    std::vector<std::string> command{options_.program.string(), "plan",
                                     spec_.problems[key.problem].string()};
    if (c.plannerFile)
      command.insert(command.end(), {"--planner-from", c.plannerFile->string()});
    else
      command.insert(command.end(), {"--planner", c.planner});
    command.insert(command.end(), {"--seed", std::to_string(spec_.seed + key.run)});
    if (spec_.time) command.insert(command.end(), {"--time", fmt::format("{}", *spec_.time)});
    if (spec_.threads) command.insert(command.end(), {"--threads", std::to_string(*spec_.threads)});
    for (const std::string& set : c.sets) command.insert(command.end(), {"--set", set});
    for (const std::string& physics : c.physics)
      command.insert(command.end(), {"--physics", physics});
    for (const std::string& dir : spec_.modelDirs)
      command.insert(command.end(), {"--model-dir", dir});
    command.insert(command.end(), {"-o", planFile(key).string()});
    addPlugins(command);
    return command;
  }

  std::vector<std::string> validateCommand(const RunKey& key) const {
    std::vector<std::string> command{options_.program.string(),
                                     "validate",
                                     spec_.problems[key.problem].string(),
                                     planFile(key).string(),
                                     "--runs",
                                     std::to_string(spec_.validate),
                                     "--seed",
                                     std::to_string(spec_.seed + key.run),
                                     "--json",
                                     validationFile(key).string()};
    for (const std::string& dir : spec_.modelDirs)
      command.insert(command.end(), {"--model-dir", dir});
    addPlugins(command);
    return command;
  }

  /// The children load the plugins this process loaded, whichever way it found them.
  void addPlugins(std::vector<std::string>& command) const {
    for (const std::filesystem::path& plugin : options_.plugins)
      command.insert(command.end(), {"--plugin", plugin.string()});
  }

  void startPlan(const RunKey& key) {
    removeRunFiles(key);  // what an interrupted earlier attempt may have left
    auto job = std::make_unique<Job>();
    job->key = key;
    job->setup = setupOf(key);
    job->evidence.seed = spec_.seed + static_cast<std::uint32_t>(key.run);
    job->place = {
        host_, cpuInfo_,
        std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count()};
    const std::vector<std::string> command = planCommand(key);
    appendCommand(consoleFile(key), command, true);
    job->child = std::make_unique<ChildProcess>(command, consoleFile(key));
    jobs_.push_back(std::move(job));
  }

  void startValidation(Job& job) {
    const std::vector<std::string> command = validateCommand(job.key);
    appendCommand(consoleFile(job.key), command, false);
    job.child = std::make_unique<ChildProcess>(command, consoleFile(job.key));
    job.validating = true;
  }

  /// A planner that overruns its limit by far is taken for hung: OMPL's benchmark gives up on
  /// a run at 1.25 times the limit; loading, replay and writing the plan take time on top.
  double watchdogSeconds(const RunKey& key) const {
    return 1.5 * preflight_.timeLimits[key.problem][key.config] + 60.0;
  }

  void advanceJobs() {
    for (auto it = jobs_.begin(); it != jobs_.end();) {
      Job& job = **it;
      if (!job.validating && job.child->elapsed() > watchdogSeconds(job.key)) killHungPlanner(job);
      if (!job.child->finished()) {
        ++it;
        continue;
      }
      if (!job.validating && childEnded(job)) {
        startValidation(job);
        ++it;
        continue;
      }
      if (job.validating) validationEnded(job);
      finish(job);
      it = jobs_.erase(it);
    }
  }

  void killHungPlanner(Job& job) {
    job.child->kill();
    std::ofstream(consoleFile(job.key), std::ios::app) << fmt::format(
        "kautham bench: killed the planner after {:.0f} s (time limit {} s)\n",
        job.child->exit().wallTime, preflight_.timeLimits[job.key.problem][job.key.config]);
  }

  /// Records the plan child's end; true if the plan is to be validated next.
  bool childEnded(Job& job) {
    job.evidence.plan = job.child->exit();
    job.evidence.planFile = readJsonIfThere(planFile(job.key));
    try {
      runProperties(job.evidence);  // a plan file that lacks what the log needs counts as none
    } catch (const json::exception&) {
      job.evidence.planFile.reset();
    }
    return spec_.validate > 0 && job.evidence.solved();
  }

  void validationEnded(Job& job) {
    job.evidence.validation = job.child->exit();
    job.evidence.validationFile = readJsonIfThere(validationFile(job.key));
    try {
      runProperties(job.evidence);
    } catch (const json::exception&) {
      job.evidence.validationFile.reset();
    }
  }

  void finish(const Job& job) {
    const json result = makeRunResult(spec_, job.key, job.setup, job.evidence, job.place, layout_);
    writeJsonFile(layout_.result(problem(job.key), config(job.key).name, job.key.run), result);
    count(result);
  }

  void removeRunFiles(const RunKey& key) {
    std::error_code ignored;
    for (const fs::path& file : {planFile(key), validationFile(key)}) {
      fs::remove(file, ignored);
      fs::remove(file.string() + ".tmp", ignored);
    }
  }

  /// Ctrl-C: the unfinished runs leave nothing a resume could take for a result.
  void abandonJobs() {
    for (const auto& job : jobs_) {
      job->child->kill();
      removeRunFiles(job->key);
    }
    jobs_.clear();
  }

  const BenchSpec& spec_;
  const Preflight& preflight_;
  const BenchRunOptions& options_;
  BenchLayout layout_;
  std::string host_;
  std::string cpuInfo_;
  std::vector<std::unique_ptr<Job>> jobs_;
  BenchSummary summary_;
};

}  // namespace

RunsInOutput runsInOutput(const BenchSpec& spec, const Preflight& preflight, const fs::path& output,
                          const Shard& shard) {
  const BenchLayout layout(output);
  RunsInOutput runs;
  for (const RunKey& key : allRuns(spec)) {
    if (!shard.contains(key.index)) continue;
    const fs::path file = layout.result(problemName(spec.problems[key.problem]),
                                        spec.configs[key.config].name, key.run);
    if (!fs::exists(file)) {
      runs.toMake.push_back(key);
      continue;
    }
    const json setup = runSetup(spec, key, preflight.timeLimits[key.problem][key.config]);
    json result = readRunResult(file);
    if (result["setup"] != setup)
      throw core::InputError(
          {file, 0}, fmt::format("this result was made with another setup ({}, now {}); give "
                                 "another output folder, or delete the result to run it again",
                                 result["setup"].dump(), setup.dump()));
    runs.made.push_back(std::move(result));
  }
  return runs;
}

BenchSummary runBenchmark(const BenchSpec& spec, const Preflight& preflight,
                          const BenchRunOptions& options) {
  return BenchRunner(spec, preflight, options).run();
}

}  // namespace kautham::apps
