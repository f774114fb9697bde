#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "kautham/core/Parameter.h"
#include "kautham/core/Problem.h"
#include "kautham/physics/PlanningContext.h"

namespace kautham::planners {

/// A `--set NAME=VALUE` from the command line.
using ParameterOverride = std::pair<std::string, std::string>;

/// Everything that decides a planning run: which planner, its parameters, the settings every
/// planner shares (time limit, propagation), and the random seed.
struct PlanRequest {
  std::string planner;
  core::ParameterSet common;      ///< commonParameters()
  core::ParameterSet parameters;  ///< the planner's own, from the registry
  std::uint32_t seed = 1;

  physics::PropagationSettings propagation() const;
  double timeLimit() const { return common.real("time_limit"); }
  /// Cores a planner may use (p-KPIECE's particle processes); others plan in one thread.
  unsigned threads() const { return static_cast<unsigned>(common.integer("threads")); }
};

/// Parameters that every planner has: time limit, how controls are propagated, threads.
std::vector<core::ParameterSpec> commonParameters();

/// Builds a request from the problem's <Planner> block, then applies the command line:
/// `plannerOverride` replaces the file's planner, `overrides` its parameter values.
/// Errors in the file are InputError with the parameter's line; errors on the command line
/// are std::invalid_argument.
PlanRequest makeRequest(const core::Problem& problem,
                        const std::optional<std::string>& plannerOverride,
                        const std::vector<ParameterOverride>& overrides, std::uint32_t seed);

}  // namespace kautham::planners
