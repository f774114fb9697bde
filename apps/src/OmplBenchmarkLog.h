#pragma once

// OMPL benchmark logs from bench result files, in the text format of OMPL 1.5.2's
// ompl::tools::Benchmark::saveResultsToStream, so that Debian's ompl_benchmark_statistics
// builds the Planner Arena database from them unchanged. One log per problem, one "planner"
// per configuration, runs in run order: the log's content depends on the results alone, not
// on the order they were made in, so shards merge into the log of a whole run.

#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

namespace kautham::apps {

/// The log of one problem from the results of its runs (BenchRunResult.h).
std::string omplBenchmarkLog(const std::vector<nlohmann::json>& results);

/// Writes FOLDER/PROBLEM.log for every problem the results are of; returns the files.
std::vector<std::filesystem::path> writeOmplBenchmarkLogs(
    const std::vector<nlohmann::json>& results, const std::filesystem::path& folder);

}  // namespace kautham::apps
