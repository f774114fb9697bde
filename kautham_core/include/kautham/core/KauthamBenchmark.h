#pragma once

// A Kautham benchmark file: a <Benchmark> root with <Problem File=... PlannerAlias=...> entries
// and <Parameter Name=... Value=...> settings. Kautham runs it with ompl::tools::Benchmark: the
// first entry's problem gives the scene and the query, and every entry gives a planner, made
// from its own file's <Planner> block and named by its alias in the log. `kautham bench --file`
// runs it the same way (apps/KauthamBenchSpec.h); this reads and checks it.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "kautham/core/InputError.h"

namespace kautham::core {

struct KauthamBenchmarkEntry {
  std::filesystem::path problem;  ///< the entry's problem file, found from the benchmark's folder
  std::string planner;            ///< the <Name> of that file's <Planner>, as written there
  std::string alias;              ///< PlannerAlias; empty when the entry has none
  SourceLocation where;           ///< the entry's <Problem> element
};

/// A <Parameter> that Kautham's runs use but `kautham bench` has no counterpart for; the reader
/// of the file says what becomes of it.
struct KauthamBenchmarkSetting {
  std::string name;
  std::string value;
  SourceLocation where;
};

struct KauthamBenchmark {
  std::string name;  ///< the Name attribute; empty when there is none
  SourceLocation where;
  std::vector<KauthamBenchmarkEntry> entries;
  /// ompl::tools::Benchmark::Request's defaults, which Kautham keeps for a setting not given.
  double maxTime = 5.0;
  std::size_t runCount = 100;
  /// maxMem, timeBetweenUpdates, displayProgress, saveConsoleOutput and filename, as given.
  std::vector<KauthamBenchmarkSetting> unused;
};

/// Reads and checks a benchmark file: one <Benchmark>, at least one entry, every entry's file
/// there with a <Planner> that names its planner, each setting one Kautham knows with a value
/// of its type. Throws InputError naming the file, the line and what was expected.
KauthamBenchmark loadKauthamBenchmark(const std::filesystem::path& file);

}  // namespace kautham::core
