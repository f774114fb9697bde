#pragma once

#include <optional>
#include <string>
#include <vector>

#include "kautham/planners/PlanRequest.h"

namespace kautham::apps {

/// The parameter overrides of a `kautham plan` command line: each --set NAME=VALUE, then
/// --time and --threads when given. `kautham bench` builds the same list for its pre-flight
/// check, so both agree on what a run will use. Throws std::invalid_argument for a --set
/// without a name or an '='.
std::vector<planners::ParameterOverride> parameterOverrides(const std::vector<std::string>& sets,
                                                            std::optional<double> time,
                                                            std::optional<unsigned> threads);

}  // namespace kautham::apps
