#pragma once

// The properties of one benchmark run, as ompl::tools::Benchmark records them for control
// planners ("time REAL", "status ENUM", "solved BOOLEAN", ...), plus kautham's own (particles,
// cells, estimated and execution success, objects moved, seed, propagations, physics steps).
// They come from what the run's children left: the plan file and the validation report.

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "ChildProcess.h"

namespace kautham::apps {

/// "name TYPE" -> value as text, sorted by name as OMPL's log lists them. A property a run
/// does not have is absent (an empty cell in the log).
using RunProperties = std::map<std::string, std::string>;

/// What a run's children left behind.
struct RunEvidence {
  std::uint32_t seed = 0;
  ChildExit plan;
  std::optional<nlohmann::json> planFile;  ///< the plan, if `kautham plan` wrote one
  std::optional<ChildExit> validation;     ///< set if `kautham validate` ran
  std::optional<nlohmann::json> validationFile;

  /// The plan child ended normally (exit 0 solved, 1 not solved) and wrote its plan.
  bool planned() const { return planFile && (plan.exited(0) || plan.exited(1)); }
  bool solved() const;
  /// The validation ran to its end and wrote its report.
  bool validated() const { return validation && validation->exited(0) && validationFile; }
  /// A child crashed, exited with an error or wrote nothing: the run failed.
  bool failed() const { return !planned() || (validation && !validated()); }
};

/// OMPL's status of the run (ompl::base::PlannerStatus::StatusType): exact or approximate
/// solution, timeout; crash when a child was killed by a signal, unknown when it failed else.
int runStatus(const RunEvidence& evidence);

RunProperties runProperties(const RunEvidence& evidence);

}  // namespace kautham::apps
