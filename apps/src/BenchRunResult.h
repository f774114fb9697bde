#pragma once

// The result file of one benchmark run (OUT/runs/PROBLEM/CONFIG/run-R.json): which run it is,
// the setup it was made with, how its children ended, and its OMPL run properties. The logs
// are written from these files alone, so that shards made anywhere merge into one log.

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "BenchLayout.h"
#include "BenchSpec.h"
#include "RunProperties.h"

namespace kautham::apps {

constexpr int kRunResultFormatVersion = 1;

/// Everything that decides a run's outcome besides chance and the machine: problem file,
/// planner and overrides, seed, time limit, threads, validation runs. Resuming into a folder
/// whose result has another setup would mix two experiments, so bench refuses it.
nlohmann::json runSetup(const BenchSpec& spec, const RunKey& key, double timeLimit);

/// Where a run was made and when it started (seconds since the Unix epoch).
struct RunPlace {
  std::string host;
  std::string cpuInfo;
  double startedAt = 0.0;
};

/// The result file's content. `layout` makes the file names it records relative to OUT.
nlohmann::json makeRunResult(const BenchSpec& spec, const RunKey& key, const nlohmann::json& setup,
                             const RunEvidence& evidence, const RunPlace& place,
                             const BenchLayout& layout);

/// Reads a result file; throws core::InputError naming the file when it is not one.
nlohmann::json readRunResult(const std::filesystem::path& file);

/// Every result file under `folder`/runs, in no particular order.
std::vector<nlohmann::json> readRunResults(const BenchLayout& folder);

/// The identity of a run across folders: "PROBLEM/CONFIG/R".
std::string runIdentity(const nlohmann::json& result);

}  // namespace kautham::apps
