#pragma once

// Runs the runs of a benchmark, each in child processes of this same program: `kautham plan`,
// then `kautham validate` of a solved plan. ODE's state is process-wide, so a run never shares
// a process with another; `jobs` runs go at once. A run whose result file exists is skipped
// (resume). Ctrl-C or SIGTERM kills the children and removes what the unfinished runs left.

#include <cstddef>
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "BenchPreflight.h"
#include "BenchSpec.h"

namespace kautham::apps {

struct BenchRunOptions {
  std::filesystem::path output;  ///< OUT (see BenchLayout.h)
  std::size_t jobs = 1;          ///< runs at once
  Shard shard;
  std::filesystem::path program;               ///< the kautham binary the children run
  std::vector<std::filesystem::path> plugins;  ///< planner plugins the children load
};

struct BenchSummary {
  std::size_t total = 0;    ///< runs of this shard
  std::size_t resumed = 0;  ///< had a result before: not run again
  std::size_t done = 0;     ///< have a result now, resumed ones included
  std::size_t solved = 0;
  std::size_t failed = 0;  ///< a child crashed, failed or wrote nothing
  bool interrupted = false;
};

/// Where a shard's runs stand in OUT: those without a result yet, in order, and the results of
/// the others (resumed, not run again).
struct RunsInOutput {
  std::vector<RunKey> toMake;
  std::vector<nlohmann::json> made;
};

/// Reads only. Throws core::InputError when a result of the same run was made with another
/// setup (resuming would mix two experiments) or cannot be read.
RunsInOutput runsInOutput(const BenchSpec& spec, const Preflight& preflight,
                          const std::filesystem::path& output, const Shard& shard);

/// Throws core::InputError, before running anything, when OUT holds a result of the same run
/// made with another setup (resuming would mix two experiments) or one that cannot be read.
BenchSummary runBenchmark(const BenchSpec& spec, const Preflight& preflight,
                          const BenchRunOptions& options);

}  // namespace kautham::apps
