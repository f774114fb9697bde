// `kautham bench`: problems x planner configurations x runs, each run in child processes of
// this program, one result file per run, OMPL benchmark logs per problem. The parts:
// BenchSpec (what to run), BenchPreflight (bad input before any run), BenchRunner (children,
// jobs, resume, Ctrl-C), BenchRunResult and RunProperties (the result file), OmplBenchmarkLog.

#include <algorithm>
#include <limits>
#include <map>
#include <set>

#include <fmt/format.h>

#include "BenchLayout.h"
#include "BenchPreflight.h"
#include "BenchRunResult.h"
#include "BenchRunner.h"
#include "BenchSpec.h"
#include "Commands.h"
#include "NumberOption.h"
#include "OmplBenchmarkLog.h"
#include "OutputFile.h"
#include "kautham/core/InputError.h"
#include "kautham/planners/PluginLoader.h"

namespace kautham::apps {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kExitInterrupted = 130;  // the shell's code for a command ended by Ctrl-C

struct BenchOptions {
  BenchArguments spec;
  std::vector<std::string> planners;  ///< --planner NAME
  std::vector<std::string> configs;   ///< --config NAME=PLANNER[:PARAM=VALUE]...
  std::vector<std::string> inputs;    ///< problems, or with --merge-only result folders
  std::string file;
  std::string output = "out/bench";
  std::size_t jobs = 1;
  std::string shard = "1/1";
  bool mergeOnly = false;
  bool checkOnly = false;
};

/// The results in OUT that belong to the spec's runs, made with its setup.
std::vector<json> resultsOfSpec(const BenchSpec& spec, const Preflight& checked,
                                const BenchLayout& layout) {
  std::map<std::string, json> expected;
  for (const RunKey& key : allRuns(spec))
    expected[fmt::format("{}/{}/{}", problemName(spec.problems[key.problem]),
                         spec.configs[key.config].name, key.run)] =
        runSetup(spec, key, checked.timeLimits[key.problem][key.config]);
  std::vector<json> results;
  for (json& r : readRunResults(layout)) {
    const auto it = expected.find(runIdentity(r));
    if (it != expected.end() && r["setup"] == it->second) results.push_back(std::move(r));
  }
  return results;
}

/// Results of several folders, each run once: the first folder that has it wins.
std::vector<json> mergedResults(const std::vector<fs::path>& folders) {
  std::map<std::string, fs::path> seen;
  std::vector<json> results;
  for (const fs::path& folder : folders) {
    if (!fs::is_directory(BenchLayout(folder).runsFolder()))
      throw core::InputError({folder, 0}, "no runs/ folder of `kautham bench` results here");
    for (json& r : readRunResults(BenchLayout(folder))) {
      const auto [it, added] = seen.emplace(runIdentity(r), folder);
      if (added)
        results.push_back(std::move(r));
      else
        fmt::print(stderr, "warning: run {} is in {} and {}; kept the first\n", it->first,
                   it->second.string(), folder.string());
    }
  }
  return results;
}

/// "Crash: plan killed by signal 9 (Killed)" or "Exact solution: validate exit code 1".
std::string whyFailed(const json& result) {
  const json& validation = result.at("validation");
  const bool planWritten = result.at("plan").at("file").is_string();
  if (planWritten && validation.is_object())
    return result.value("status", "") + ": validate " + validation.value("exit", "");
  return result.value("status", "") + ": plan " + result.at("plan").value("exit", "");
}

/// Writes the logs and prints the runs that failed.
void writeLogs(const std::vector<json>& results, const BenchLayout& layout) {
  std::size_t failed = 0;
  for (const json& r : results)
    if (r.value("failed", false) && ++failed <= 10)
      fmt::print("failed    {}: {}; see {}\n", runIdentity(r), whyFailed(r),
                 (layout.root() / r.value("console", "")).string());
  if (failed > 10) fmt::print("failed    ... {} runs in all\n", failed);
  for (const fs::path& log : writeOmplBenchmarkLogs(results, layout.logsFolder()))
    fmt::print("wrote     {}\n", log.string());
}

int runMergeOnly(const BenchOptions& options) {
  const BenchArguments& s = options.spec;
  if (!options.file.empty() || !options.planners.empty() || !options.configs.empty() ||
      !s.sets.empty() || s.runs || s.seed || s.time || s.threads || s.validate ||
      options.shard != "1/1")
    throw std::invalid_argument("--merge-only runs nothing: it takes -o OUT and result folders");
  std::vector<fs::path> folders{options.output};
  std::set<fs::path> distinct;
  if (fs::exists(options.output)) distinct.insert(fs::weakly_canonical(options.output));
  for (const std::string& input : options.inputs)
    if (distinct.insert(fs::weakly_canonical(input)).second) folders.push_back(input);
  if (!fs::is_directory(BenchLayout(options.output).runsFolder())) folders.erase(folders.begin());
  if (folders.empty())
    throw std::invalid_argument("--merge-only: no folder with results (give OUT or DIR...)");
  const std::vector<json> results = mergedResults(folders);
  if (results.empty()) throw std::invalid_argument("--merge-only: the folders hold no results");
  std::size_t solved = 0;
  for (const json& r : results) solved += r.value("solved", false);
  fmt::print("merged    {} runs from {} folders; {} solved\n", results.size(), folders.size(),
             solved);
  writeLogs(results, BenchLayout(options.output));
  return kExitSolved;
}

/// "40 min", "3.3 h": a duration as a person plans a campaign by.
std::string roughDuration(double seconds) {
  if (seconds < 120.0) return fmt::format("{:.0f} s", seconds);
  if (seconds < 7200.0) return fmt::format("{:.0f} min", seconds / 60.0);
  return fmt::format("{:.1f} h", seconds / 3600.0);
}

/// What a campaign will do: its size, the runs OUT already has, how long planning can take.
void printPlan(const BenchSpec& spec, const Preflight& checked, const Shard& shard,
               std::size_t jobs, const std::vector<RunKey>& toMake, std::size_t resumed,
               const fs::path& output) {
  const std::size_t all = spec.problems.size() * spec.configs.size() * spec.runs;
  fmt::print("bench     {} problems x {} configurations x {} runs = {} runs{}, {} at a time\n",
             spec.problems.size(), spec.configs.size(), spec.runs, all,
             shard.count > 1 ? fmt::format(" (shard {}/{})", shard.index, shard.count) : "", jobs);
  if (resumed > 0)
    fmt::print("resume    {} of these runs have results in {} already; they are not run again\n",
               resumed, output.string());
  if (toMake.empty()) {
    fmt::print("limits    nothing left to run\n");
    return;
  }
  // Planning ends near each run's time limit at the latest; validation has no such bound. Runs
  // taken in turn by `workers` workers end within total / workers + (1 - 1 / workers) x the
  // longest.
  double total = 0.0, longest = 0.0;
  for (const RunKey& key : toMake) {
    total += checked.timeLimits[key.problem][key.config];
    longest = std::max(longest, checked.timeLimits[key.problem][key.config]);
  }
  const double workers = static_cast<double>(std::min(jobs, toMake.size()));
  fmt::print(
      "limits    planning the {} runs left takes at most about {} (their time limits, {} at "
      "a time){}\n",
      toMake.size(), roughDuration(total / workers + (1.0 - 1.0 / workers) * longest), jobs,
      spec.validate > 0 ? fmt::format("; validation ({} executions of each solved plan) "
                                      "comes on top",
                                      spec.validate)
                        : "");
}

/// --planner and --config in the order they were given: the order of the log's planners.
std::vector<BenchConfig> configsInOrder(const CLI::App& command, const BenchOptions& options) {
  std::vector<BenchConfig> configs;
  std::size_t planner = 0, config = 0;
  for (const CLI::Option* option : command.parse_order()) {
    if (option->check_lname("planner")) {
      const std::string& name = options.planners.at(planner++);
      configs.push_back({name, name, {}, {}, {}});
    } else if (option->check_lname("config")) {
      configs.push_back(parseConfig(options.configs.at(config++)));
    }
  }
  return configs;
}

int runBench(const CLI::App& command, BenchOptions options) {
  if (options.mergeOnly) return runMergeOnly(options);
  options.spec.configs = configsInOrder(command, options);
  if (!options.file.empty()) options.spec.file = options.file;
  options.spec.problems = options.inputs;
  const BenchSpec spec = makeBenchSpec(options.spec);
  const Shard shard = parseShard(options.shard);
  requireOutputFolder(options.output, "-o");
  const Preflight checked = preflight(spec);  // bad input stops here, before any run
  // Results of another setup in OUT stop it here too, before any run.
  const RunsInOutput runs = runsInOutput(spec, checked, options.output, shard);
  if (!spec.description.empty()) {
    const bool overridden = !options.inputs.empty() || !options.spec.configs.empty();
    fmt::print("about     {}{}\n", spec.description,
               overridden ? " (the file's; the command line replaced its problems or "
                            "configurations)"
                          : "");
  }
  printPlan(spec, checked, shard, options.jobs, runs.toMake, runs.made.size(), options.output);
  if (options.checkOnly) {
    fmt::print(
        "checked   every problem loads with a valid start, every configuration's planner, "
        "parameters and physics are accepted; nothing run\n");
    return kExitSolved;
  }

  const BenchRunOptions run{options.output, options.jobs, shard, fs::read_symlink("/proc/self/exe"),
                            planners::loadedPlugins()};
  const BenchSummary summary = runBenchmark(spec, checked, run);
  if (summary.interrupted) {
    fmt::print(
        "interrupted: {} of {} runs done ({} solved, {} failed); the same command "
        "resumes\n",
        summary.done, summary.total, summary.solved, summary.failed);
    return kExitInterrupted;
  }
  fmt::print("runs      {}: {} made now, {} resumed; {} solved, {} failed\n", summary.total,
             summary.done - summary.resumed, summary.resumed, summary.solved, summary.failed);
  const BenchLayout layout(options.output);
  writeLogs(resultsOfSpec(spec, checked, layout), layout);
  return summary.failed > 0 ? kExitNotSolved : kExitSolved;
}

void addSpecOptions(CLI::App& command, BenchOptions& options) {
  BenchArguments& s = options.spec;
  command.add_option(
      "--file", options.file,
      "benchmark file (JSON): name, description, problems, configs, runs, seed, time, "
      "threads, validate; or, named *.xml, Kautham's <Benchmark> file (docs/bench.md); the "
      "options below override it");
  command.add_option("--planner", options.planners, "a planner to run, shown under its own name")
      ->allow_extra_args(false);
  command
      .add_option("--config", options.configs,
                  "a named configuration NAME=PLANNER[:PARAM=VALUE]..., e.g. "
                  "\"pKP=p-KPIECE:uncertainty=0\"")
      ->allow_extra_args(false);
  command.add_option("--set", s.sets, "PARAM=VALUE for every configuration (repeatable)")
      ->allow_extra_args(false);
  command.add_option("--runs", s.runs, "runs per problem and configuration (default 10)")
      ->check(wholeNumberRange(1, std::numeric_limits<std::uint32_t>::max()));
  command.add_option("--seed", s.seed, "run r plans and validates with seed SEED + r (default 1)")
      ->check(seedRange(std::numeric_limits<std::uint32_t>::max()));
  command.add_option("--time", s.time, "planning time limit in seconds (default: the problem's)")
      ->check(numberRange(0.01, 86400.0));
  command
      .add_option("--threads", s.threads,
                  "worker processes for p-KPIECE's particles and whole-plan verification in "
                  "each run; the other planners run in one thread and ignore it")
      ->check(wholeNumberRange(1, 64));
  command
      .add_option("--validate", s.validate,
                  "execute each solved plan this many times under uncertainty (default 0)")
      ->check(wholeNumberRange(0, 100000000));
  command.add_option("--model-dir", s.modelDirs, "extra folder to search for models")
      ->check(CLI::ExistingDirectory)
      ->allow_extra_args(false);
}

}  // namespace

void addBenchCommand(CLI::App& app, int& exitCode) {
  auto options = std::make_shared<BenchOptions>();
  CLI::App* command = app.add_subcommand(
      "bench",
      "Run planners on problems many times, each run in a process of its own, and write OMPL "
      "benchmark logs (for ompl_benchmark_statistics and Planner Arena)");
  command->add_option("inputs", options->inputs,
                      "problem files (with --merge-only: folders of results to merge)");
  addSpecOptions(*command, *options);
  command->add_option("-o,--output", options->output, "output folder")->capture_default_str();
  command->add_option("--jobs", options->jobs, "runs at once")
      ->check(wholeNumberRange(1, 256))
      ->capture_default_str();
  command
      ->add_option("--shard", options->shard,
                   "i/n: only the runs whose index is i-1 modulo n (merge with --merge-only)")
      ->capture_default_str();
  CLI::Option* mergeOnly = command->add_flag(
      "--merge-only", options->mergeOnly,
      "run nothing: write OUT/logs from the results in OUT and the folders given");
  command
      ->add_flag("--check", options->checkOnly,
                 "run nothing: load every problem and check every configuration, as before a "
                 "campaign, then exit (0: it would start)")
      ->excludes(mergeOnly);
  command->footer(
      "Output: OUT/runs/PROBLEM/CONFIG/run-R.json (one result per run; a run that has one is\n"
      "not run again), OUT/plans/... (plans), OUT/console/... (what the runs printed),\n"
      "OUT/logs/PROBLEM.log (OMPL benchmark logs). See docs/bench.md.\n"
      "Exit codes: 0 every run finished (solved or not; with --check: the input is good),\n"
      "1 some run crashed or failed, 2 bad input, 130 interrupted.\n"
      "Example: kautham bench problems/pusher_free.xml --planner KPIECE --planner RRT --runs 5 \\\n"
      "           --time 10 -o out/bench\n"
      "         ompl_benchmark_statistics out/bench/logs/*.log -d out/bench/bench.db");
  command->callback([command, options, &exitCode] {
    exitCode = runReportingErrors([&] { return runBench(*command, *options); });
  });
}

}  // namespace kautham::apps
