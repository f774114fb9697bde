#include "BenchSpec.h"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "JsonFileText.h"
#include "KauthamBenchSpec.h"
#include "kautham/core/InputError.h"

namespace kautham::apps {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// Reads a benchmark file; every error names the file and, where the text shows it, the line.
class BenchFileReader {
 public:
  explicit BenchFileReader(fs::path file) : source_(std::move(file)) {}

  BenchSpec read() {
    const json root = source_.parse("the benchmark file", "not JSON: ");
    if (!root.is_object()) fail("", "a benchmark file holds one JSON object");
    static const std::set<std::string> known{"name", "description", "problems", "configs", "runs",
                                             "seed", "time",        "threads",  "validate"};
    for (const auto& [key, value] : root.items())
      if (known.count(key) == 0)
        fail(key, fmt::format("unknown key \"{}\"; known: name, description, problems, configs, "
                              "runs, seed, time, threads, validate",
                              key));
    BenchSpec spec;
    if (root.contains("name")) spec.name = text(root["name"], "name");
    if (root.contains("description")) spec.description = text(root["description"], "description");
    if (root.contains("problems")) spec.problems = problems(root["problems"]);
    if (root.contains("configs")) spec.configs = configs(root["configs"]);
    if (root.contains("runs")) spec.runs = whole(root["runs"], "runs", 1);
    if (root.contains("seed"))
      spec.seed = static_cast<std::uint32_t>(whole(root["seed"], "seed", 1));
    if (root.contains("time")) {
      if (!root["time"].is_number() || !(root["time"].get<double>() > 0.0))
        fail("time", "\"time\" must be a positive number of seconds");
      spec.time = root["time"].get<double>();
    }
    if (root.contains("threads"))
      spec.threads = static_cast<unsigned>(whole(root["threads"], "threads", 1, 4096));
    if (root.contains("validate")) spec.validate = whole(root["validate"], "validate", 0);
    return spec;
  }

 private:
  std::vector<fs::path> problems(const json& list) {
    if (!list.is_array()) fail("problems", "\"problems\" must be an array of file names");
    std::vector<fs::path> result;
    for (const json& p : list) {
      const fs::path path = text(p, "problems");
      // Relative to the benchmark file, so that the file works from any folder.
      result.push_back(
          path.is_absolute() ? path : (source_.file().parent_path() / path).lexically_normal());
    }
    return result;
  }

  std::vector<BenchConfig> configs(const json& list) {
    if (!list.is_array()) fail("configs", "\"configs\" must be an array of objects");
    std::vector<BenchConfig> result;
    for (const json& c : list) {
      if (!c.is_object() || !c.contains("planner"))
        fail("configs", "each configuration needs at least a \"planner\"");
      for (const auto& [key, value] : c.items())
        if (key != "name" && key != "planner" && key != "set" && key != "physics")
          fail(key, "unknown key \"" + key +
                        "\" in a configuration; known: name, planner, set, physics");
      BenchConfig config;
      config.planner = text(c["planner"], "planner");
      config.name = c.contains("name") ? text(c["name"], "name") : config.planner;
      config.sets = assignments(c, "set", "parameter names");
      config.physics = assignments(c, "physics", "<Physics> attributes");
      result.push_back(std::move(config));
    }
    return result;
  }

  /// A configuration's "set" or "physics": an object of names to values, as NAME=VALUE.
  std::vector<std::string> assignments(const json& config, const std::string& key,
                                       const std::string& names) {
    std::vector<std::string> result;
    if (!config.contains(key)) return result;
    if (!config[key].is_object()) fail(key, "\"" + key + "\" must map " + names + " to values");
    for (const auto& [name, value] : config[key].items())
      result.push_back(name + "=" + (value.is_string() ? value.get<std::string>() : value.dump()));
    return result;
  }

  std::string text(const json& value, const std::string& key) {
    if (!value.is_string()) fail(key, "\"" + key + "\" must be a string");
    return value.get<std::string>();
  }

  std::size_t whole(const json& value, const std::string& key, std::uint64_t smallest,
                    std::uint64_t largest = std::numeric_limits<std::uint32_t>::max()) {
    if (!value.is_number_unsigned() || value.get<std::uint64_t>() < smallest ||
        value.get<std::uint64_t>() > largest)
      fail(key, fmt::format("\"{}\" must be a whole number from {} to {}", key, smallest, largest));
    return static_cast<std::size_t>(value.get<std::uint64_t>());
  }

  [[noreturn]] void fail(const std::string& key, const std::string& message) const {
    throw core::InputError({source_.file(), key.empty() ? 0 : source_.keyLine(key)}, message);
  }

  JsonFileText source_;
};

/// Names become folder names and the planner's line in the OMPL log.
void checkName(const std::string& name, const std::string& what) {
  const bool safe = !name.empty() && name != "." && name != ".." &&
                    std::all_of(name.begin(), name.end(), isNameCharacter);
  if (!safe)
    throw std::invalid_argument(fmt::format(
        "{} '{}': use letters, digits and - _ . + only (it names folders and log entries)", what,
        name));
}

void checkSpec(const BenchSpec& spec) {
  if (spec.problems.empty())
    throw std::invalid_argument("no problem to run: give problem files or --file");
  if (spec.configs.empty())
    throw std::invalid_argument("no planner to run: give --planner, --config or --file");
  if (spec.runs == 0) throw std::invalid_argument("--runs must be at least 1");
  if (spec.seed == 0)
    throw std::invalid_argument("--seed must be at least 1 (run r plans with seed + r)");
  // The seeds are 32-bit (plan --seed): the last run's must be one too.
  if (spec.seed - 1ull + spec.runs > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument(
        fmt::format("--seed {} with --runs {}: the last run would plan with seed {}, above {}; "
                    "use a smaller seed",
                    spec.seed, spec.runs, spec.seed - 1ull + spec.runs,
                    std::numeric_limits<std::uint32_t>::max()));
  if (spec.time && !(*spec.time > 0.0)) throw std::invalid_argument("--time must be positive");
  if (spec.threads && *spec.threads == 0) throw std::invalid_argument("--threads must be >= 1");
  if (!spec.name.empty()) checkName(spec.name, "benchmark name");
  std::set<std::string> names;
  for (const BenchConfig& c : spec.configs) {
    checkName(c.name, "configuration name");
    if (!names.insert(c.name).second)
      throw std::invalid_argument("configuration name '" + c.name +
                                  "' is used twice; names must be unique");
  }
  std::set<std::string> problems;
  for (const fs::path& p : spec.problems) {
    checkName(problemName(p), "problem name");
    if (!problems.insert(problemName(p)).second)
      throw std::invalid_argument("two problems are named '" + problemName(p) +
                                  "'; their results would share a folder");
  }
}

}  // namespace

BenchConfig parseConfig(const std::string& text) {
  const std::size_t equals = text.find('=');
  const std::size_t colon = text.find(':');
  if (equals == std::string::npos || equals == 0 || (colon != std::string::npos && colon < equals))
    throw std::invalid_argument("--config expects NAME=PLANNER[:PARAM=VALUE]..., got '" + text +
                                "'");
  BenchConfig config;
  config.name = text.substr(0, equals);
  std::istringstream rest(text.substr(equals + 1));
  std::getline(rest, config.planner, ':');
  if (config.planner.empty())
    throw std::invalid_argument("--config '" + text + "' names no planner");
  for (std::string set; std::getline(rest, set, ':');) {
    if (set.find('=') == std::string::npos || set.front() == '=')
      throw std::invalid_argument("--config '" + text + "': '" + set + "' is not PARAM=VALUE");
    config.sets.push_back(set);
  }
  return config;
}

BenchSpec makeBenchSpec(const BenchArguments& arguments) {
  BenchSpec spec;
  if (arguments.file)
    spec = arguments.file->extension() == ".xml" ? kauthamBenchSpec(*arguments.file)
                                                 : BenchFileReader(*arguments.file).read();
  if (!arguments.problems.empty())
    spec.problems.assign(arguments.problems.begin(), arguments.problems.end());
  if (!arguments.configs.empty()) spec.configs = arguments.configs;
  // --set applies to every configuration, before the configuration's own overrides.
  for (BenchConfig& c : spec.configs)
    c.sets.insert(c.sets.begin(), arguments.sets.begin(), arguments.sets.end());
  if (arguments.runs) spec.runs = *arguments.runs;
  if (arguments.seed) spec.seed = *arguments.seed;
  if (arguments.time) spec.time = arguments.time;
  if (arguments.threads) spec.threads = arguments.threads;
  if (arguments.validate) spec.validate = *arguments.validate;
  spec.modelDirs = arguments.modelDirs;
  checkSpec(spec);
  return spec;
}

std::string problemName(const std::filesystem::path& problem) { return problem.stem().string(); }

bool isNameCharacter(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' ||
         c == '+';
}

std::vector<RunKey> allRuns(const BenchSpec& spec) {
  std::vector<RunKey> runs;
  for (std::size_t p = 0; p < spec.problems.size(); ++p)
    for (std::size_t c = 0; c < spec.configs.size(); ++c)
      for (std::size_t r = 0; r < spec.runs; ++r) runs.push_back({p, c, r, runs.size()});
  return runs;
}

Shard parseShard(const std::string& text) {
  Shard shard;
  char slash = 0;
  std::istringstream in(text);
  if (!(in >> shard.index >> slash >> shard.count) || slash != '/' || !in.eof() ||
      shard.count == 0 || shard.index == 0 || shard.index > shard.count)
    throw std::invalid_argument("--shard expects i/n with 1 <= i <= n, got '" + text + "'");
  return shard;
}

}  // namespace kautham::apps
