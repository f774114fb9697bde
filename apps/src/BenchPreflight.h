#pragma once

// Before `kautham bench` starts any run it checks its input in this process, the way `kautham
// plan` would: every problem loads and its start is valid, every configuration names a known
// planner and parameters it accepts. A mistake costs an error message, not a campaign of
// failed runs.

#include <cstddef>
#include <vector>

#include "BenchSpec.h"

namespace kautham::apps {

/// What the check learns that the runs need.
struct Preflight {
  /// timeLimits[problem][config]: the planning time limit a run will have (--time, or the
  /// problem file's own), for the result files, the log and the watchdog.
  std::vector<std::vector<double>> timeLimits;
};

/// Throws core::InputError (a bad problem file, naming it and the line) or
/// std::invalid_argument (an unknown planner or parameter, naming problem and configuration).
Preflight preflight(const BenchSpec& spec);

}  // namespace kautham::apps
