// `kautham plan PROBLEM`: load, plan, replay to verify, print a summary, write the plan file.

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "Commands.h"
#include "KauthamPlanners.h"
#include "NumberOption.h"
#include "OutputFile.h"
#include "PackagePathOption.h"
#include "ParameterOverrides.h"
#include "PlanFile.h"
#include "PlanViewer.h"
#include "PlannerFromFile.h"
#include "StartCheck.h"
#include "kautham/core/PhysicsOverrides.h"
#include "kautham/core/ProblemLoader.h"

namespace kautham::apps {

namespace {

std::atomic<bool> interrupted{false};

struct PlanOptions {
  std::string problem;
  std::optional<std::string> planner;
  std::string plannerFrom;  ///< --planner-from: another problem file whose <Planner> to use
  std::optional<double> time;
  std::optional<unsigned> threads;
  std::uint32_t seed = 1;
  std::vector<std::string> sets;
  std::vector<std::string> physics;  ///< --physics NAME=VALUE: <Physics> attributes set
  std::string output;
  std::string html;
  std::string threeDir;
  std::vector<std::string> modelDirs;
  std::vector<std::string> packagePaths;
  std::size_t query = 0;
};

/// A one-line progress display, only on a terminal (pipes and CI logs stay clean).
planners::SolveHooks terminalHooks() {
  planners::SolveHooks hooks;
  hooks.stop = [] { return interrupted.load(); };
  if (isatty(STDERR_FILENO))
    hooks.progress = [](const planners::Progress& p) {
      fmt::print(stderr,
                 "\r  planning {:6.1f} s  {:>9} propagations  {:>10} physics steps  closest "
                 "{:5.1f} cm ",
                 p.elapsed, p.propagations, p.physicsSteps, 100.0 * p.bestGoalDistance);
      std::fflush(stderr);
    };
  return hooks;
}

/// How many runs failed, over every reason and object.
std::uint64_t failureTotal(const std::vector<planners::FailureCount>& failures) {
  std::uint64_t total = 0;
  for (const planners::FailureCount& f : failures) total += f.count;
  return total;
}

/// Why the planner's runs (particles, or candidates' nominal runs) failed, by reason, each with
/// its three most frequent objects:
/// "object tilted 1523 (can3 800, can4 400, can1 300, 2 more), target moved 210 (glass)".
std::string failureSummary(const std::vector<planners::FailureCount>& failures) {
  std::vector<std::string> order;  // reasons, most frequent first (failures is sorted so)
  std::map<std::string, std::uint64_t> total;
  std::map<std::string, std::vector<const planners::FailureCount*>> objects;
  for (const planners::FailureCount& f : failures) {
    if (total.count(f.reason) == 0) order.push_back(f.reason);
    total[f.reason] += f.count;
    if (!f.object.empty()) objects[f.reason].push_back(&f);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](const std::string& a, const std::string& b) { return total[a] > total[b]; });
  std::string text;
  for (const std::string& reason : order) {
    text += fmt::format("{}{} {}", text.empty() ? "" : ", ", reason, total[reason]);
    const auto& named = objects[reason];
    if (named.empty()) continue;
    std::string list;
    for (std::size_t i = 0; i < std::min<std::size_t>(3, named.size()); ++i)
      list += fmt::format("{}{} {}", i ? ", " : "", named[i]->object, named[i]->count);
    if (named.size() > 3) list += fmt::format(", {} more", named.size() - 3);
    text += " (" + list + ")";
  }
  return text;
}

void printSummary(const physics::PlanningContext& context, const planners::PlanRequest& request,
                  const planners::PlanOutcome& outcome, const physics::ReplayResult& replay) {
  const auto& stats = outcome.statistics;
  fmt::print("problem   {} ({}), query {}\n", context.problem().name,
             context.problem().file.string(), context.query().name);
  fmt::print("planner   {}, seed {}, time limit {} s\n", request.planner, request.seed,
             request.timeLimit());
  fmt::print("solved    {} in {:.2f} s\n",
             outcome.solved ? "yes" : (outcome.approximate ? "no (approximate solution)" : "no"),
             stats.planningTime);
  fmt::print("tree      {} states, {} propagations, {} physics steps ({:.0f} steps/s)\n",
             stats.treeStates, stats.propagations, stats.physicsSteps,
             stats.physicsSteps / std::max(stats.planningTime, 1e-9));
  if (!stats.plannerProperties.empty()) {
    std::string properties;
    // OMPL's properties say "nan" for a value not measured yet (no goal candidate, say): a
    // person reads "-" as that, "nan" as a fault.
    for (const auto& [name, value] : stats.plannerProperties)
      properties += (properties.empty() ? "" : ", ") + name + " " + (value == "nan" ? "-" : value);
    fmt::print("planner   {}\n", properties);
  }
  if (!outcome.sampledFailures.empty()) {
    const std::uint64_t failed = failureTotal(outcome.sampledFailures);
    fmt::print("failed    {} particles: {}\n", failed, failureSummary(outcome.sampledFailures));
  }
  // What cut the tree's candidate motions short, and how much of it the goal steering's.
  if (!outcome.candidateFailures.empty()) {
    fmt::print("broke     {} candidate motions stopped at a rule: {}\n",
               failureTotal(outcome.candidateFailures), failureSummary(outcome.candidateFailures));
    if (!outcome.steeredFailures.empty())
      fmt::print("          {} of them steered: {}\n", failureTotal(outcome.steeredFailures),
                 failureSummary(outcome.steeredFailures));
  }
  // A tree that hardly grows: say which rules rejected the states the planner tried.
  const auto rejections = context.rejections();
  if (!outcome.solved && !rejections.empty()) {
    std::uint64_t total = 0;
    std::string reasons;
    for (const auto& [violation, count] : rejections) {
      total += count;
      reasons +=
          fmt::format("{}{} {}", reasons.empty() ? "" : ", ", physics::toString(violation), count);
    }
    fmt::print("rejected  {} states: {}\n", total, reasons);
  }
  if (outcome.controls.empty()) return;
  fmt::print("plan      {} controls, {:.2f} s of motion\n", outcome.controls.size(),
             replay.frames.back().time);
  std::string moved;
  for (const auto& m : physics::movedObjects(context.layout(), replay))
    moved += fmt::format(" {} {:.1f} cm,", m.name, 100.0 * m.distance);
  if (!moved.empty()) moved.pop_back();
  fmt::print("replay    {}, goal distance {:.1f} cm, {}\n",
             replay.reachedGoal ? "reaches the goal" : "does NOT reach the goal",
             100.0 * replay.finalGoalDistance,
             replay.firstViolation == physics::Violation::None
                 ? "no constraint violated"
                 : std::string("violation: ") + physics::toString(replay.firstViolation));
  fmt::print("moved    {}\n", moved.empty() ? " nothing" : moved);
}

int runPlan(const PlanOptions& options) {
  // Before planning, so that a missing three.js or a mistyped output does not cost the
  // planning time.
  if (!options.output.empty()) requireOutputFile(options.output, "-o");
  if (!options.html.empty()) requireOutputFile(options.html, "--html");
  const std::filesystem::path threeDir =
      options.html.empty() ? std::filesystem::path() : findThreeDir(options.threeDir);
  applyPackagePaths(options.packagePaths);
  std::vector<std::filesystem::path> modelDirs(options.modelDirs.begin(), options.modelDirs.end());
  core::Problem problem = core::loadProblem(options.problem, modelDirs);
  if (!options.plannerFrom.empty())
    problem = withPlannerOf(std::move(problem), options.plannerFrom, modelDirs);
  core::applyPhysicsOverrides(problem.physics, options.physics);
  if (!options.physics.empty())
    fmt::print("physics   {} (--physics, over the file's <Physics>)\n",
               fmt::join(options.physics, " "));
  if (options.query >= problem.queries.size())
    throw std::invalid_argument(fmt::format("--query {}: the problem has {} queries", options.query,
                                            problem.queries.size()));
  const planners::PlanRequest request =
      planners::makeRequest(problem, plannerToUse(problem, options.planner, /*lenient=*/false),
                            parameterOverrides(options.sets, options.time, options.threads),
                            planners::seedRandomness(options.seed));

  const auto contextOwner = makeCheckedContext(problem, options.query, request);
  physics::PlanningContext& context = *contextOwner;

  std::signal(SIGINT, [](int) { interrupted = true; });
  const planners::PlanOutcome outcome = planners::solve(context, request, terminalHooks());
  std::signal(SIGINT, SIG_DFL);
  if (isatty(STDERR_FILENO)) fmt::print(stderr, "\r{:100}\r", "");

  const physics::ReplayResult replay = physics::replay(context, outcome.controls);
  printSummary(context, request, outcome, replay);
  if (!options.output.empty() || !options.html.empty()) {
    nlohmann::json plan = planToJson(context, request, outcome, replay);
    // validate reads them back, so that it executes the plan in the physics it was made in.
    if (!options.physics.empty()) plan["problem"]["physics"] = options.physics;
    if (!options.output.empty()) {
      writeJsonFile(options.output, plan);
      fmt::print("wrote     {}\n", options.output);
    }
    if (!options.html.empty()) {
      checkPlanForView(plan, "the plan");
      writeTextFile(options.html, planToHtml(plan, threeDir));
      fmt::print("wrote     {}\n", options.html);
    }
  }
  if (outcome.solved && replay.firstViolation != physics::Violation::None)
    fmt::print(stderr,
               "warning: the replayed plan breaks a constraint ({}): expected of a planner that "
               "checks fewer of them (o-KPIECE knows only whom the robot may touch)\n",
               physics::toString(replay.firstViolation));
  else if (outcome.solved && !replay.reachedGoal)
    fmt::print(stderr, "warning: the replayed plan does not reach the goal; please report this\n");
  return outcome.solved && replay.reachedGoal ? kExitSolved : kExitNotSolved;
}

}  // namespace

void addPlanCommand(CLI::App& app, int& exitCode) {
  auto options = std::make_shared<PlanOptions>();
  CLI::App* command = app.add_subcommand("plan", "Plan a query of a problem file");
  command->add_option("problem", options->problem, "problem file (XML)")->required();
  CLI::Option* planner =
      command->add_option("--planner", options->planner, "planner name (see `kautham planners`)");
  command
      ->add_option("--planner-from", options->plannerFrom,
                   "plan with the planner and parameters of another problem file's <Planner> "
                   "(this problem's scene and query), as a Kautham benchmark file does")
      ->excludes(planner);
  command->add_option("--time", options->time, "planning time limit in seconds")
      ->check(numberRange(0.01, 86400.0));
  command
      ->add_option("--threads", options->threads,
                   "worker processes for p-KPIECE's particles and its whole-plan verification, "
                   "same as --set threads=N (the plan does not depend on it); the other "
                   "planners run in one thread and ignore it")
      ->check(wholeNumberRange(1, 64));
  command->add_option("--seed", options->seed, "random seed (0: pick one)")
      ->capture_default_str()
      ->check(seedRange(std::numeric_limits<std::uint32_t>::max()));
  command
      ->add_option("--set", options->sets,
                   "set a planner parameter, NAME=VALUE (repeatable; see `kautham planners`)")
      ->allow_extra_args(false);
  command
      ->add_option("--physics", options->physics,
                   "set an attribute of the problem's <Physics>, NAME=VALUE (repeatable; e.g. "
                   "overRelaxation=1.7; recorded in the plan file, which validate follows)")
      ->allow_extra_args(false);
  command->add_option("-o,--output", options->output, "write the plan to this JSON file");
  command->add_option("--html", options->html,
                      "write the plan as an animated HTML page too (see `kautham view`)");
  command->add_option("--three-dir", options->threeDir,
                      "three.js folder for --html (default: " + kDefaultThreeDir.string() +
                          ", from Debian's libjs-three)");
  command->add_option("--model-dir", options->modelDirs, "extra folder to search for models")
      ->check(CLI::ExistingDirectory)
      ->allow_extra_args(false);
  addPackagePathOption(*command, options->packagePaths);
  command->add_option("--query", options->query, "index of the query to plan")
      ->capture_default_str()
      ->check(wholeNumberRange(0, std::numeric_limits<std::uint32_t>::max()));
  command->callback(
      [options, &exitCode] { exitCode = runReportingErrors([&] { return runPlan(*options); }); });
}

}  // namespace kautham::apps
