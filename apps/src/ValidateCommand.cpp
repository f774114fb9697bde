// `kautham validate PROBLEM PLAN --runs N`: executes a plan open loop in N worlds sampled from
// the problem's <Uncertainty> and reports the success rate with a confidence interval.

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "Commands.h"
#include "JsonFileText.h"
#include "NumberOption.h"
#include "OutputFile.h"
#include "PackagePathOption.h"
#include "PlanControlCheck.h"
#include "PlanFile.h"
#include "kautham/core/PhysicsOverrides.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/core/Random.h"
#include "kautham/physics/Execution.h"
#include "kautham/physics/UncertaintySampler.h"

namespace kautham::apps {

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

/// The sources of uncertainty `--only` can keep.
const std::vector<std::string> kSources{"poses", "contact", "control"};

struct ValidateOptions {
  std::string problem;
  std::string plan;
  std::size_t runs = 0;
  std::uint64_t seed = 1;
  std::string json;
  std::vector<std::string> modelDirs;
  std::vector<std::string> packagePaths;
  /// The sources of uncertainty sampled (poses, contact, control); empty: all of them.
  std::vector<std::string> only;
  /// --physics NAME=VALUE: <Physics> attributes set after the plan's own (the plan in other
  /// physics than it was made in).
  std::vector<std::string> physics;
};

/// The problem's uncertainty less the sources `only` leaves out (none when it is empty): how
/// much of a plan's failures one source alone causes.
void keepOnly(core::Problem& problem, const std::vector<std::string>& only) {
  if (only.empty()) return;
  const auto kept = [&only](const char* source) {
    return std::find(only.begin(), only.end(), source) != only.end();
  };
  if (!kept("poses"))
    for (core::ObjectInstance& object : problem.objects) object.uncertainty = {};
  if (!kept("contact")) {
    problem.uncertainty.friction = 0.0;
    problem.uncertainty.erp = 0.0;
    problem.uncertainty.cfm = 0.0;
  }
  if (!kept("control")) problem.uncertainty.control = 0.0;
}

/// What validate needs of a plan file (PlanFile.cpp's format).
struct PlanControls {
  std::string problem;  ///< the name of the problem it was made for; empty: not recorded
  std::string query;    ///< the query's name; empty: the first query
  /// The <Physics> attributes `kautham plan --physics` set (NAME=VALUE), to be set again.
  std::vector<std::string> physics;
  double propagationStepSize = 0.0;
  std::vector<physics::ControlStep> controls;
};

/// Reads a plan file; every problem is an InputError naming the file and, as far as it can
/// be found in the text, the line.
class PlanReader {
 public:
  explicit PlanReader(fs::path file) : source_(std::move(file)) {}

  PlanControls read() {
    const json plan = source_.parse("the plan file", "not a JSON plan file: ");
    if (!plan.is_object() || plan.value("format", json()) != "kautham-plan")
      fail("", "not a kautham plan: \"format\" must be \"kautham-plan\"");
    if (!plan.contains("format_version") || plan["format_version"] != kPlanFormatVersion)
      fail("format_version",
           fmt::format("plan format version {} is not supported; this kautham "
                       "reads version {}",
                       plan.value("format_version", json()).dump(), kPlanFormatVersion));
    PlanControls result;
    const json problem = plan.value("problem", json::object());
    if (problem.is_object() && problem.value("name", json()).is_string())
      result.problem = problem["name"].get<std::string>();
    if (problem.is_object() && problem.contains("query")) {
      if (!problem["query"].is_string()) fail("query", "\"query\" must be a string");
      result.query = problem["query"].get<std::string>();
    }
    if (problem.is_object() && problem.contains("physics")) {
      const json& physics = problem["physics"];
      if (!physics.is_array()) fail("physics", "\"physics\" must be an array of \"NAME=VALUE\"");
      for (const json& assignment : physics) {
        if (!assignment.is_string()) fail("physics", "\"physics\" must hold strings NAME=VALUE");
        result.physics.push_back(assignment.get<std::string>());
      }
    }
    const json step = plan.value("propagation_step_size", json());
    if (!step.is_number() || !(step.get<double>() > 0.0))
      fail("propagation_step_size", "the plan needs a positive \"propagation_step_size\"");
    result.propagationStepSize = step.get<double>();

    if (!plan.contains("controls") || !plan["controls"].is_array())
      fail("controls", "the plan needs a \"controls\" array");
    const json& controls = plan["controls"];
    for (std::size_t i = 0; i < controls.size(); ++i) {
      const json& c = controls[i];
      auto bad = [&](const std::string& what) {
        throw core::InputError({source_.file(), controlLine(i)},
                               fmt::format("controls[{}]: {}", i, what));
      };
      if (const std::optional<std::string> error = planControlError(c, result.propagationStepSize))
        bad(*error);
      physics::ControlStep control;
      for (const json& v : c["values"]) control.values.push_back(v.get<double>());
      control.steps = static_cast<unsigned>(c["steps"].get<std::uint64_t>());
      readGripperAction(c, control, bad);
      result.controls.push_back(std::move(control));
    }
    return result;
  }

  /// A control's "gripper" ("grasp" with its "body", or "release"): the task planner's plans.
  template <typename Bad>
  static void readGripperAction(const json& c, physics::ControlStep& control, const Bad& bad) {
    if (!c.contains("gripper")) return;
    const json action = c["gripper"];
    if (action == "release") {
      control.action = physics::GripperAction::Release;
    } else if (action == "grasp") {
      const json body = c.value("body", json());
      if (!body.is_number_unsigned() || body.get<std::uint64_t>() > 100000)
        bad("a \"grasp\" needs the \"body\" it takes hold of (an index of \"bodies\")");
      control.action = physics::GripperAction::Grasp;
      control.object = static_cast<int>(body.get<std::uint64_t>());
    } else {
      bad("\"gripper\" must be \"grasp\" or \"release\", not " + action.dump());
    }
  }

  [[noreturn]] void fail(const std::string& key, const std::string& message) const {
    throw core::InputError({source_.file(), key.empty() ? 1 : source_.keyLine(key)}, message);
  }
  /// The line of the i-th control, for an error about it.
  int controlLine(std::size_t index) const { return source_.elementLine("controls", index); }
  const fs::path& file() const { return source_.file(); }

 private:
  JsonFileText source_;
};

/// The reasons a run fails, as the report groups them.
enum class Failure { GoalMissed, TargetTouched, ObjectFell, TooFast, Other };
constexpr std::array<Failure, 5> kFailures{Failure::GoalMissed, Failure::TargetTouched,
                                           Failure::ObjectFell, Failure::TooFast, Failure::Other};

const char* label(Failure f) {
  switch (f) {
    case Failure::GoalMissed:
      return "goal missed";
    case Failure::TargetTouched:
      return "target touched";
    case Failure::ObjectFell:
      return "object fell or tipped";
    case Failure::TooFast:
      return "too fast";
    case Failure::Other:
      return "other";
  }
  return "";
}

const char* key(Failure f) {
  switch (f) {
    case Failure::GoalMissed:
      return "goal_missed";
    case Failure::TargetTouched:
      return "target_touched";
    case Failure::ObjectFell:
      return "object_fell_or_tipped";
    case Failure::TooFast:
      return "too_fast";
    case Failure::Other:
      return "other";
  }
  return "";
}

Failure classify(physics::Violation v) {
  using physics::Violation;
  switch (v) {
    case Violation::None:
      return Failure::GoalMissed;
    case Violation::RobotTouchedTarget:
    case Violation::TargetMoved:
      return Failure::TargetTouched;
    case Violation::ObjectTilted:
    case Violation::ObjectOffSupport:
      return Failure::ObjectFell;
    case Violation::ObjectTooFast:
    case Violation::JointTooFast:
    case Violation::LinkTooFast:
      return Failure::TooFast;
    case Violation::SimulationDiverged:
    case Violation::RobotTouchedFixed:
    case Violation::OutsideWorkspace:
    case Violation::JointLimit:
      return Failure::Other;
  }
  return Failure::Other;
}

struct Interval {
  double low = 0.0;
  double high = 0.0;
};

/// Wilson's score interval for a binomial proportion (successes of runs) at 95 %.
Interval wilson(std::size_t successes, std::size_t runs) {
  constexpr double z = 1.959963984540054;  // the normal's 97.5 % quantile
  const double n = static_cast<double>(runs);
  const double p = static_cast<double>(successes) / n;
  const double denominator = 1.0 + z * z / n;
  const double centre = (p + z * z / (2.0 * n)) / denominator;
  const double half = z / denominator * std::sqrt(p * (1.0 - p) / n + z * z / (4.0 * n * n));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

std::size_t findQuery(const core::Problem& problem, const std::string& name,
                      const PlanReader& reader) {
  if (name.empty()) return 0;
  for (std::size_t q = 0; q < problem.queries.size(); ++q)
    if (problem.queries[q].name == name) return q;
  reader.fail("query", "the plan is for query '" + name + "', which " +
                           problem.file.filename().string() + " does not have");
}

/// Keys (names, control indices) and counts, the most counted first (the smaller key among
/// equals).
template <typename Key>
std::vector<std::pair<Key, std::size_t>> mostCountedFirst(
    const std::map<Key, std::size_t>& counts) {
  std::vector<std::pair<Key, std::size_t>> sorted(counts.begin(), counts.end());
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  return sorted;
}

/// "can1 in 20, can21 in 12": runs per object, most often first.
std::string runsPerObject(const std::map<std::string, std::size_t>& counts) {
  std::string text;
  for (const auto& [name, runs] : mostCountedFirst(counts))
    text += fmt::format("{}{} in {}", text.empty() ? "" : ", ", name, runs);
  return text;
}

/// "can3 in 5 runs, cylinder in 2, ...": which objects broke a rule, most often first.
std::string describeOffenders(const std::map<std::string, std::size_t>& offenders) {
  const auto sorted = mostCountedFirst(offenders);
  std::string text;
  for (std::size_t i = 0; i < sorted.size(); ++i)
    text += fmt::format("{}{} in {}{}", i ? ", " : "", sorted[i].first, sorted[i].second,
                        i ? "" : (sorted[i].second == 1 ? " run" : " runs"));
  return text + " (the object that broke the rule)";
}

/// When each of a plan's controls starts and ends, in seconds of motion.
struct ControlWindow {
  double start = 0.0;
  double end = 0.0;
};

std::vector<ControlWindow> controlWindows(const PlanControls& plan) {
  std::vector<ControlWindow> windows;
  double t = 0.0;
  for (const physics::ControlStep& c : plan.controls) {
    const double end = t + c.steps * plan.propagationStepSize;
    windows.push_back({t, end});
    t = end;
  }
  return windows;
}

/// "control 12 (2.60-2.85 s) in 31 runs, control 11 (2.40-2.60 s) in 14, ... (`why`)": in how
/// many runs each control was the one (where a rule broke, say), most often first (the earlier
/// among equals), at most five.
std::string describeControls(const std::map<std::size_t, std::size_t>& counts,
                             const std::vector<ControlWindow>& windows, const std::string& why) {
  constexpr std::size_t kShown = 5;
  const auto sorted = mostCountedFirst(counts);
  std::string text;
  for (std::size_t i = 0; i < std::min(sorted.size(), kShown); ++i) {
    const auto [control, runs] = sorted[i];
    text += fmt::format("{}control {} ({:.2f}-{:.2f} s) in {}{}", i ? ", " : "", control,
                        windows[control].start, windows[control].end, runs,
                        i ? "" : (runs == 1 ? " run" : " runs"));
  }
  if (sorted.size() > kShown) text += fmt::format(", {} more", sorted.size() - kShown);
  return text + " (" + why + ")";
}

/// [{"control": 12, "start": 2.6, "end": 2.85, "runs": 31}, ...], in the controls' order.
json controlsJson(const std::map<std::size_t, std::size_t>& counts,
                  const std::vector<ControlWindow>& windows) {
  json byControl = json::array();
  for (const auto& [control, runs] : counts)
    byControl.push_back({{"control", control},
                         {"start", windows[control].start},
                         {"end", windows[control].end},
                         {"runs", runs}});
  return byControl;
}

/// The control in which a run's goal link moved furthest from the nominal execution's: where
/// the distance between the two, control end by control end, grew most (none without a
/// control run in full). The robot starts where the nominal does.
std::optional<std::size_t> strayedIn(const std::vector<Eigen::Vector3d>& run,
                                     const std::vector<Eigen::Vector3d>& nominal) {
  std::optional<std::size_t> strayed;
  double apartBefore = 0.0;
  double mostGrowth = -std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < std::min(run.size(), nominal.size()); ++c) {
    const double apart = (run[c] - nominal[c]).norm();
    if (apart - apartBefore > mostGrowth) {
      mostGrowth = apart - apartBefore;
      strayed = c;
    }
    apartBefore = apart;
  }
  return strayed;
}

/// What the robot touched in a number of runs (at some moment of each): runs per object, and
/// runs in which it touched nothing.
struct Touches {
  std::map<std::string, std::size_t> byObject;
  std::size_t nothing = 0;

  void add(const std::vector<std::string>& touched) {
    nothing += touched.empty();
    for (const std::string& name : touched) ++byObject[name];
  }
  /// "can1 in 25, can5 in 2, nothing in 3": most often first.
  std::string describe() const {
    const std::string text = runsPerObject(byObject);
    if (nothing == 0) return text;
    return text + fmt::format("{}nothing in {}", text.empty() ? "" : ", ", nothing);
  }
};

/// Of the runs that ended off the goal pose: the control in which each strayed furthest from
/// the nominal execution (strayedIn), and what the robot touched during that control.
struct Strays {
  std::map<std::size_t, std::size_t> byControl;  ///< runs that strayed in each control
  Touches touched;                               ///< what the robot touched then

  /// Counts `run` (off the goal pose); the control it strayed in, and the objects touched then.
  std::optional<std::pair<std::size_t, std::vector<std::string>>> count(
      const physics::ExecutionResult& run, const physics::ExecutionResult& nominal,
      const physics::WorldLayout& layout) {
    const std::optional<std::size_t> control =
        strayedIn(run.linkAfterControl, nominal.linkAfterControl);
    if (!control) return std::nullopt;
    ++byControl[*control];
    std::vector<std::string> names;
    for (const int body : run.touchedInControl.at(*control))
      names.push_back(layout.bodies.at(static_cast<std::size_t>(body)).name);
    touched.add(names);
    return std::make_pair(*control, names);
  }

  /// "control 21 (4.65-4.90 s) in 28 runs, ... (...); the robot touching can1 in 25, nothing
  /// in 3 during it"
  std::string describe(const std::vector<ControlWindow>& windows) const {
    return describeControls(byControl, windows,
                            "of the runs off the goal pose, the control in which the gripper "
                            "moved furthest from the nominal execution's") +
           "; the robot touching " + touched.describe() + " during it";
  }
};

/// "the free space not clear in 30 runs: can1 in 20, can21 in 12": of the runs that ended with
/// the gripper where the goal asks, how many had objects between the fingers, and which, most
/// often first.
std::string describeBlockedFreeSpace(std::size_t runs,
                                     const std::map<std::string, std::size_t>& objects) {
  return fmt::format("the free space not clear in {} {}: {}", runs, runs == 1 ? "run" : "runs",
                     runsPerObject(objects));
}

/// Of the valid runs that ended off the goal pose, how many missed each part of it, and what
/// the robot touched where each ended (what held it up short, if anything did).
struct PoseMisses {
  std::size_t runs = 0;
  std::size_t position = 0;
  std::size_t approach = 0;
  std::size_t level = 0;
  Touches touchedThere;  ///< what the robot touched where each run ended

  void count(const physics::ExecutionResult& run) {
    const physics::WorkspaceGoal::PoseMiss& miss = run.poseMissed;
    if (!miss.any()) return;
    ++runs;
    position += miss.position;
    approach += miss.approach;
    level += miss.level;
    touchedThere.add(run.touchedOffThePose);
  }
};

/// ["position", "approach"]: what one run's gripper missed of the goal pose.
json poseMissNames(const physics::WorkspaceGoal::PoseMiss& miss) {
  json names = json::array();
  if (miss.position) names.push_back("position");
  if (miss.approach) names.push_back("approach");
  if (miss.level) names.push_back("level");
  return names;
}

/// "the gripper off the goal pose in 15 runs: 5 beyond the 2 cm tolerance, 10 turned beyond the
/// 0.3 rad approach tolerance" (a run may miss more than one).
std::string describePoseMisses(const PoseMisses& misses, const physics::GoalSpec& spec) {
  std::string parts;
  if (misses.position)
    parts +=
        fmt::format(", {} beyond the {:g} cm tolerance", misses.position, 100.0 * spec.tolerance);
  if (misses.approach)
    parts += fmt::format(", {} turned beyond the {:g} rad approach tolerance", misses.approach,
                         spec.approachTolerance);
  if (misses.level)
    parts += fmt::format(", {} with the level axis tilted beyond the {:g} rad approach tolerance",
                         misses.level, spec.approachTolerance);
  return fmt::format("the gripper off the goal pose in {} {}: {}; the robot touching there {}",
                     misses.runs, misses.runs == 1 ? "run" : "runs", parts.substr(2),
                     misses.touchedThere.describe());
}

std::string describeUncertainty(const core::Problem& problem,
                                const physics::UncertaintySampler& sampler) {
  if (!sampler.hasUncertainty()) return "none (every standard deviation is zero)";
  std::size_t uncertain = 0;
  core::PoseUncertainty largest;
  for (const core::ObjectInstance& o : problem.objects) {
    if (o.uncertainty.isZero()) continue;
    ++uncertain;
    largest.x = std::max(largest.x, o.uncertainty.x);
    largest.y = std::max(largest.y, o.uncertainty.y);
    largest.yaw = std::max(largest.yaw, o.uncertainty.yaw);
  }
  const core::ContactUncertainty& u = problem.uncertainty;
  return fmt::format(
      "poses of {} objects (sd up to x {} m, y {} m, yaw {} rad); sd of friction {}, erp {}, "
      "cfm {}; control sd {}",
      uncertain, largest.x, largest.y, largest.yaw, u.friction, u.erp, u.cfm, u.control);
}

/// "overRelaxation=1.7 (the plan's), then friction=0.3 (--physics)".
std::string describePhysicsOverrides(const std::vector<std::string>& fromPlan,
                                     const std::vector<std::string>& fromCommandLine) {
  std::string text;
  if (!fromPlan.empty()) text = fmt::format("{} (the plan's)", fmt::join(fromPlan, " "));
  if (!fromPlan.empty() && !fromCommandLine.empty()) text += ", then ";
  if (!fromCommandLine.empty())
    text += fmt::format("{} (--physics)", fmt::join(fromCommandLine, " "));
  return text;
}

int runValidate(const ValidateOptions& options) {
  if (!options.json.empty()) requireOutputFile(options.json, "--json");
  applyPackagePaths(options.packagePaths);
  std::vector<fs::path> modelDirs(options.modelDirs.begin(), options.modelDirs.end());
  core::Problem problem = core::loadProblem(options.problem, modelDirs);
  keepOnly(problem, options.only);
  PlanReader reader(options.plan);
  const PlanControls plan = reader.read();
  // A variant of the problem (other uncertainty, say) is a fair test of a plan, and is named
  // otherwise: warn, do not refuse.
  if (!plan.problem.empty() && plan.problem != problem.name)
    fmt::print(stderr,
               "warning: {} was made for the problem '{}', not '{}' ({}); its controls are "
               "executed as they are\n",
               options.plan, plan.problem, problem.name, options.problem);
  try {
    core::applyPhysicsOverrides(problem.physics, plan.physics);
  } catch (const std::invalid_argument& e) {
    reader.fail("physics", std::string(e.what()) + " (the plan's \"physics\")");
  }
  core::applyPhysicsOverrides(problem.physics, options.physics);
  const std::size_t query = findQuery(problem, plan.query, reader);

  physics::PropagationSettings settings;
  settings.propagationStepSize = plan.propagationStepSize;
  settings.minControlSteps = 1;
  settings.maxControlSteps = 1;
  for (const physics::ControlStep& c : plan.controls)
    settings.maxControlSteps = std::max(settings.maxControlSteps, c.steps);
  std::unique_ptr<physics::PlanningContext> owner;
  try {
    owner = std::make_unique<physics::PlanningContext>(problem, query, settings);
  } catch (const std::invalid_argument& e) {
    reader.fail("propagation_step_size", e.what());
  }
  physics::PlanningContext& context = *owner;
  if (!context.startOverlaps().empty() || context.startViolation() != physics::Violation::None)
    throw core::InputError(problem.queries[query].where,
                           "the start state is invalid or things interpenetrate (see `kautham "
                           "check`): there is nothing to validate");
  const std::size_t controlSize = context.propagator().mapping().size();
  for (std::size_t i = 0; i < plan.controls.size(); ++i)
    if (plan.controls[i].values.size() != controlSize)
      throw core::InputError(
          {reader.file(), reader.controlLine(i)},
          fmt::format("controls[{}] has {} values, but the robot of {} has {} controls", i,
                      plan.controls[i].values.size(), problem.file.filename().string(),
                      controlSize));

  const physics::UncertaintySampler sampler(problem, context.layout());
  const bool progress = isatty(STDERR_FILENO);
  std::size_t successes = 0;
  std::size_t rejectedStarts = 0;
  std::map<Failure, std::size_t> failures;
  std::map<physics::Violation, std::size_t> violations;
  std::map<std::string, std::size_t> offenders;       ///< runs in which each object broke a rule
  std::map<std::size_t, std::size_t> brokenControls;  ///< runs that broke a rule in each control
  Strays strays;
  const std::vector<ControlWindow> windows = controlWindows(plan);
  std::mt19937_64 nominalRng(core::runSeed(options.seed, 0));
  const physics::ExecutionResult nominal =
      physics::execute(context, plan.controls, nominalRng, false);
  /// Valid runs that ended with the gripper where the goal asks, missing it only because the
  /// free space between the fingers was not clear; and in how many of them each object was.
  std::size_t runsWithFreeSpaceNotClear = 0;
  std::map<std::string, std::size_t> leftInFreeSpace;
  PoseMisses poseMisses;
  double distanceSum = 0.0;
  json perRun = json::array();
  for (std::size_t run = 0; run < options.runs; ++run) {
    std::mt19937_64 rng(core::runSeed(options.seed, run));
    const physics::ExecutionResult r = physics::execute(context, plan.controls, rng, true);
    rejectedStarts += r.rejectedStarts;
    distanceSum += r.finalGoalDistance;
    json runJson = {{"reached_goal", r.reachedGoal},
                    {"violation", physics::toString(r.firstViolation)},
                    {"final_goal_distance", r.finalGoalDistance},
                    {"time", r.time}};
    if (r.offendingObject) {
      const std::string& name = context.layout().bodies[*r.offendingObject].name;
      runJson["object"] = name;
      ++offenders[name];
    }
    if (r.brokenInControl) {
      runJson["control"] = *r.brokenInControl;
      ++brokenControls[*r.brokenInControl];
    }
    if (!r.leftInFreeSpace.empty()) {
      runJson["left_in_free_space"] = r.leftInFreeSpace;
      ++runsWithFreeSpaceNotClear;
      for (const std::string& name : r.leftInFreeSpace) ++leftInFreeSpace[name];
    }
    if (r.poseMissed.any()) {
      runJson["pose_missed"] = poseMissNames(r.poseMissed);
      runJson["touching_off_the_pose"] = r.touchedOffThePose;
      if (const auto strayed = strays.count(r, nominal, context.layout())) {
        runJson["strayed_in_control"] = strayed->first;
        runJson["touched_while_straying"] = strayed->second;
      }
    }
    poseMisses.count(r);
    perRun.push_back(std::move(runJson));
    if (r.reachedGoal) {
      ++successes;
    } else {
      ++failures[classify(r.firstViolation)];
      if (r.firstViolation != physics::Violation::None) ++violations[r.firstViolation];
    }
    if (progress) {
      fmt::print(stderr, "\r  run {:>6}/{}  {} successes ", run + 1, options.runs, successes);
      std::fflush(stderr);
    }
  }
  if (progress) fmt::print(stderr, "\r{:60}\r", "");

  const Interval ci = wilson(successes, options.runs);
  const double rate = static_cast<double>(successes) / static_cast<double>(options.runs);
  const double motion = windows.empty() ? 0.0 : windows.back().end;
  fmt::print("problem      {} ({}), query {}\n", problem.name, problem.file.string(),
             problem.queries[query].name);
  fmt::print("plan         {}: {} controls, {:.2f} s of motion\n", options.plan,
             plan.controls.size(), motion);
  fmt::print("uncertainty  {}{}\n", describeUncertainty(problem, sampler),
             options.only.empty() ? "" : fmt::format(" (only {})", fmt::join(options.only, ", ")));
  if (!plan.physics.empty() || !options.physics.empty())
    fmt::print("physics      {} (over the file's <Physics>)\n",
               describePhysicsOverrides(plan.physics, options.physics));
  fmt::print("runs         {} (seed {})\n", options.runs, options.seed);
  fmt::print("success      {}/{} = {:.1f} %, 95 % Wilson interval [{:.1f} %, {:.1f} %]\n",
             successes, options.runs, 100.0 * rate, 100.0 * ci.low, 100.0 * ci.high);
  fmt::print("failures     {}\n", options.runs - successes);
  for (Failure f : kFailures) {
    std::string detail;
    for (const auto& [violation, count] : violations)
      if (classify(violation) == f)
        detail += fmt::format(", {} {}", physics::toString(violation), count);
    // The goal's two kinds of miss, each a list of its own: "; " between them.
    if (f == Failure::GoalMissed && !leftInFreeSpace.empty())
      detail += "; " + describeBlockedFreeSpace(runsWithFreeSpaceNotClear, leftInFreeSpace);
    if (f == Failure::GoalMissed && poseMisses.runs > 0)
      detail += "; " + describePoseMisses(poseMisses, context.goal().spec());
    fmt::print("  {:<22} {:>6}{}\n", label(f), failures[f],
               detail.empty() ? "" : " (" + detail.substr(2) + ")");
  }
  if (!offenders.empty()) fmt::print("objects      {}\n", describeOffenders(offenders));
  if (!brokenControls.empty())
    fmt::print("when         {}\n", describeControls(brokenControls, windows,
                                                     "the control during which the rule broke"));
  if (!strays.byControl.empty()) fmt::print("strayed      {}\n", strays.describe(windows));
  fmt::print("goal distance {:.1f} cm on average at the end\n",
             100.0 * distanceSum / static_cast<double>(options.runs));
  if (rejectedStarts > 0)
    fmt::print("starts       {} sampled starts redrawn (things interpenetrated)\n", rejectedStarts);

  if (!options.json.empty()) {
    json byReason = json::object();
    for (Failure f : kFailures) byReason[key(f)] = failures[f];
    json byViolation = json::object();
    for (const auto& [violation, count] : violations)
      byViolation[physics::toString(violation)] = count;
    const json report = {
        {"format", "kautham-validation"},
        {"problem", {{"name", problem.name}, {"file", problem.file.string()}}},
        {"query", problem.queries[query].name},
        {"plan", options.plan},
        {"runs", options.runs},
        {"seed", options.seed},
        {"sources", options.only.empty() ? json(kSources) : json(options.only)},
        {"physics", {{"plan", plan.physics}, {"command_line", options.physics}}},
        {"successes", successes},
        {"success_rate", rate},
        {"confidence_interval",
         {{"method", "wilson"}, {"level", 0.95}, {"low", ci.low}, {"high", ci.high}}},
        {"failures", byReason},
        {"violations", byViolation},
        {"broken_in_control", controlsJson(brokenControls, windows)},
        {"strayed_in_control", controlsJson(strays.byControl, windows)},
        {"strayed_touching",
         {{"by_object", strays.touched.byObject}, {"nothing", strays.touched.nothing}}},
        {"free_space_not_clear",
         {{"runs", runsWithFreeSpaceNotClear}, {"by_object", leftInFreeSpace}}},
        {"goal_pose_missed",
         {{"runs", poseMisses.runs},
          {"position", poseMisses.position},
          {"approach", poseMisses.approach},
          {"level", poseMisses.level},
          {"touching", poseMisses.touchedThere.byObject},
          {"touching_nothing", poseMisses.touchedThere.nothing}}},
        {"mean_final_goal_distance", distanceSum / static_cast<double>(options.runs)},
        {"redrawn_starts", rejectedStarts},
        {"results", perRun},
    };
    writeJsonFile(options.json, report);
    fmt::print("wrote        {}\n", options.json);
  }
  return kExitSolved;
}

}  // namespace

void addValidateCommand(CLI::App& app, int& exitCode) {
  auto options = std::make_shared<ValidateOptions>();
  CLI::App* command = app.add_subcommand(
      "validate",
      "Execute a plan open loop in worlds sampled from the problem's <Uncertainty>: success rate "
      "with a 95 % confidence interval, and why runs failed");
  command->add_option("problem", options->problem, "problem file (XML)")->required();
  command->add_option("plan", options->plan, "plan file (JSON, from `kautham plan -o`)")
      ->required();
  command->add_option("--runs", options->runs, "number of sampled executions")
      ->required()
      ->check(wholeNumberRange(1, 100000000));
  command->add_option("--seed", options->seed, "random seed; run i draws from its own stream")
      ->capture_default_str()
      ->check(seedRange(std::numeric_limits<std::uint64_t>::max()));
  command->add_option("--json", options->json, "write the numbers to this JSON file");
  command
      ->add_option("--physics", options->physics,
                   "set an attribute of the problem's <Physics>, NAME=VALUE, after those the "
                   "plan file records (repeatable): the plan executed in other physics")
      ->allow_extra_args(false);
  command->add_option("--model-dir", options->modelDirs, "extra folder to search for models")
      ->check(CLI::ExistingDirectory)
      ->allow_extra_args(false);
  command
      ->add_option("--only", options->only,
                   "sample only this source of uncertainty (repeatable): poses (objects' and the "
                   "target's start poses), contact (friction, ERP, CFM) or control (noise); the "
                   "others stay at their means")
      ->check(CLI::IsMember(kSources))
      ->allow_extra_args(false);
  addPackagePathOption(*command, options->packagePaths);
  command->footer(
      "Exit codes: 0 it ran (whatever the success rate), 2 bad input.\n"
      "Example: kautham validate problems/pusher_cans_5.xml out/plan.json --runs 100\n"
      "Which source makes it fail: ... --runs 100 --only control, then --only poses");
  command->callback([options, &exitCode] {
    exitCode = runReportingErrors([&] { return runValidate(*options); });
  });
}

}  // namespace kautham::apps
