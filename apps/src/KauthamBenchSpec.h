#pragma once

// `kautham bench --file benchmark.xml`: a Kautham benchmark file read as a campaign. As in
// Kautham, the first entry's problem is the scene and the query, and each entry a configuration
// that plans with its own file's planner and parameters (`kautham plan --planner-from`), named
// by its PlannerAlias; maxTime and runCount are the time limit and the runs per configuration.

#include <filesystem>

#include "BenchSpec.h"

namespace kautham::apps {

/// Throws core::InputError naming the file and the line for a bad file; warns, with the line,
/// about the settings `kautham bench` does otherwise (maxMem, filename, ...).
BenchSpec kauthamBenchSpec(const std::filesystem::path& file);

}  // namespace kautham::apps
