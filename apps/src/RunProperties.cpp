#include "RunProperties.h"

#include <cmath>
#include <cstdlib>

#include <ompl/base/PlannerStatus.h>
#include <ompl/util/String.h>

namespace kautham::apps {

namespace {

using nlohmann::json;
using Status = ompl::base::PlannerStatus;

/// OMPL writes reals with ompl::toString (classic locale, full precision): so do we.
std::string real(double value) { return ompl::toString(value); }
std::string integer(std::uint64_t value) { return std::to_string(value); }
std::string boolean(bool value) { return value ? "1" : "0"; }

/// A planner statistic of the plan file ("cells", "particles", ...) as a number, if it has one.
std::optional<double> plannerStatistic(const json& plan, const std::string& name) {
  const json& statistics = plan.at("statistics").at("planner");
  if (!statistics.contains(name) || !statistics[name].is_string()) return std::nullopt;
  const std::string text = statistics[name].get<std::string>();
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || !std::isfinite(value)) return std::nullopt;  // "nan": none yet
  return value;
}

/// The plan's motion in seconds: what OMPL's PathControl::length() sums (control durations).
double motionDuration(const json& plan) {
  double seconds = 0.0;
  for (const json& control : plan.at("controls")) seconds += control.at("duration").get<double>();
  return seconds;
}

std::size_t treeMotions(const json& plan) {
  std::size_t motions = 0;
  for (const json& parent : plan.at("tree").at("parent")) motions += parent.get<int>() >= 0;
  return motions;
}

/// What `kautham plan` measured: the search and, when it found a path, the path and its replay.
void addPlanProperties(const json& plan, RunProperties& properties) {
  const json& result = plan.at("result");
  const json& statistics = plan.at("statistics");
  properties["time REAL"] = real(plan.at("timing").at("planning_time").get<double>());
  properties["solved BOOLEAN"] = boolean(result.at("solved").get<bool>());
  properties["graph states INTEGER"] = integer(statistics.at("tree_states").get<std::uint64_t>());
  properties["graph motions INTEGER"] = integer(treeMotions(plan));
  properties["propagations INTEGER"] = integer(statistics.at("propagations").get<std::uint64_t>());
  properties["physics steps INTEGER"] =
      integer(statistics.at("physics_steps").get<std::uint64_t>());
  if (const auto cells = plannerStatistic(plan, "cells"))
    properties["cells INTEGER"] = integer(static_cast<std::uint64_t>(*cells));
  if (const auto particles = plannerStatistic(plan, "particles"))
    properties["particles INTEGER"] = integer(static_cast<std::uint64_t>(*particles));
  if (const auto restarts = plannerStatistic(plan, "restarts"))
    properties["restarts INTEGER"] = integer(static_cast<std::uint64_t>(*restarts));
  if (const auto spent = plannerStatistic(plan, "motion_budget_spent"))
    properties["motion budget spent BOOLEAN"] = boolean(*spent != 0.0);

  if (plan.at("controls").empty()) return;  // no path, not even an approximate one
  const json& replay = result.at("replay");
  const bool violated = replay.at("violation").get<std::string>() != "none";
  properties["approximate solution BOOLEAN"] = boolean(result.at("approximate").get<bool>());
  properties["solution difference REAL"] = real(result.at("goal_distance").get<double>());
  properties["solution length REAL"] = real(motionDuration(plan));
  properties["solution segments INTEGER"] = integer(plan.at("controls").size());
  // The replay re-runs the controls in the physics and checks every step: "correct" when it
  // breaks no constraint, "strict" when it also ends in the goal region.
  properties["correct solution BOOLEAN"] = boolean(!violated);
  properties["correct solution strict BOOLEAN"] =
      boolean(!violated && replay.at("reached_goal").get<bool>());
  properties["simplification time REAL"] = real(0.0);  // control paths are not simplified
  properties["objects moved INTEGER"] = integer(replay.at("moved_objects").size());
  // The planner's own estimate that the plan succeeds when executed (p-KPIECE's). Not the
  // path belief times best_goal_confidence: that counts the path twice (until 2026-11-23).
  const auto confidence = plannerStatistic(plan, "solution_confidence");
  if (result.at("solved").get<bool>() && confidence)
    properties["estimated success REAL"] = real(*confidence);
}

}  // namespace

bool RunEvidence::solved() const {
  return planned() && (*planFile).at("result").at("solved").get<bool>();
}

int runStatus(const RunEvidence& evidence) {
  if (!evidence.planned()) return evidence.plan.signal != 0 ? Status::CRASH : Status::UNKNOWN;
  const json& result = (*evidence.planFile).at("result");
  if (result.at("solved").get<bool>()) return Status::EXACT_SOLUTION;
  if (result.at("approximate").get<bool>()) return Status::APPROXIMATE_SOLUTION;
  return Status::TIMEOUT;
}

RunProperties runProperties(const RunEvidence& evidence) {
  RunProperties properties;
  properties["status ENUM"] = std::to_string(runStatus(evidence));
  properties["seed INTEGER"] = integer(evidence.seed);
  properties["memory REAL"] = real(evidence.plan.maxRssMb);
  if (!evidence.planned()) {
    properties["solved BOOLEAN"] = boolean(false);
    properties["time REAL"] = real(evidence.plan.wallTime);
    return properties;
  }
  addPlanProperties(*evidence.planFile, properties);
  if (evidence.validated()) {
    const json& report = *evidence.validationFile;
    properties["execution success REAL"] =
        real(report.at("successes").get<double>() / report.at("runs").get<double>());
  }
  return properties;
}

}  // namespace kautham::apps
