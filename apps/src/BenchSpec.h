#pragma once

// What `kautham bench` runs: problems x planner configurations x runs, read from a small JSON
// file and the command line (which overrides the file). It knows nothing of processes or logs.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace kautham::apps {

/// One planner configuration: a planner of the registry with parameter overrides, shown under
/// its own name (the planner's name in the OMPL log, so unique within a benchmark).
struct BenchConfig {
  std::string name;
  std::string planner;
  std::vector<std::string> sets;  ///< NAME=VALUE, applied in order after the problem's own
  /// NAME=VALUE attributes of the problems' <Physics> (`kautham plan --physics`): another
  /// solver setting measured without copies of the files.
  std::vector<std::string> physics;
  /// Set for a Kautham benchmark file's entries: the planner and its parameters are those of
  /// this problem file's <Planner> (`kautham plan --planner-from`); `planner` is its <Name>.
  std::optional<std::filesystem::path> plannerFile;
};

struct BenchSpec {
  std::string name;  ///< the campaign's name; empty: logs are named after their problem only
  /// What the campaign measures, for the person who runs it again: printed, never interpreted.
  std::string description;
  std::vector<std::filesystem::path> problems;
  std::vector<BenchConfig> configs;
  std::size_t runs = 10;
  std::uint32_t seed = 1;      ///< run r of every configuration plans with seed + r
  std::optional<double> time;  ///< planning time limit; unset: each problem file's own
  std::optional<unsigned> threads;
  std::size_t validate = 0;  ///< executions of each solved plan under uncertainty
  std::vector<std::string> modelDirs;
};

/// The command line's share of a spec. Every value is optional so that it can override the
/// file's: problems or configurations given here replace the file's lists.
struct BenchArguments {
  std::optional<std::filesystem::path> file;
  std::vector<std::string> problems;
  std::vector<BenchConfig> configs;  ///< --planner and --config, in command-line order
  std::vector<std::string> sets;     ///< --set PARAM=VALUE for every configuration
  std::optional<std::size_t> runs;
  std::optional<std::uint32_t> seed;
  std::optional<double> time;
  std::optional<unsigned> threads;
  std::optional<std::size_t> validate;
  std::vector<std::string> modelDirs;
};

/// The spec from the file (if any) and the command line. The file is JSON, or, named *.xml, a
/// Kautham benchmark file (KauthamBenchSpec.h). Throws core::InputError for a bad file (naming
/// it and the line) and std::invalid_argument for a bad command-line value.
BenchSpec makeBenchSpec(const BenchArguments& arguments);

/// `--config "pKP=p-KPIECE:uncertainty=0"`: name, planner and the overrides, ':'-separated.
BenchConfig parseConfig(const std::string& text);

/// A problem's name in output folders and logs: its file's stem.
std::string problemName(const std::filesystem::path& problem);

/// Whether a name of a benchmark, configuration or problem may hold `c`: letters, digits and
/// - _ . + (names become folder names and the planner's line in the OMPL log).
bool isNameCharacter(char c);

/// One run of the benchmark. `index` numbers the runs over problems x configurations x runs in
/// that order (runs innermost); shards pick runs by it, so it never depends on what ran.
struct RunKey {
  std::size_t problem = 0;
  std::size_t config = 0;
  std::size_t run = 0;
  std::size_t index = 0;
};

std::vector<RunKey> allRuns(const BenchSpec& spec);

/// `--shard i/n`: the runs whose index is i-1 modulo n.
struct Shard {
  std::size_t index = 1;
  std::size_t count = 1;

  bool contains(std::size_t runIndex) const { return runIndex % count == index - 1; }
};

Shard parseShard(const std::string& text);

}  // namespace kautham::apps
