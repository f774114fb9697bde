#include "KauthamBenchSpec.h"

#include <algorithm>
#include <map>
#include <set>

#include <fmt/format.h>

#include "kautham/core/KauthamBenchmark.h"
#include "kautham/core/Log.h"

namespace kautham::apps {

namespace {

namespace fs = std::filesystem;

/// A name as `kautham bench` can use it for folders and the log: the characters other than
/// letters, digits and - _ . + become '_'. Kautham's names are free text ("PRM random").
std::string usableName(const std::string& name, const core::SourceLocation& where) {
  std::string usable = name;
  std::replace_if(
      usable.begin(), usable.end(), [](char c) { return !isNameCharacter(c); }, '_');
  if (usable != name)
    core::warning(where.str() + ": name '" + name + "' is used as '" + usable +
                  "' (it names folders and the log's planners)");
  return usable;
}

/// What `kautham bench` does instead of a Kautham setting it has no use for.
std::string insteadOf(const std::string& setting, const std::string& problem) {
  static const std::map<std::string, std::string> instead{
      {"maxMem", "not enforced: each run is a process of its own"},
      {"timeBetweenUpdates", "progress properties over time are not recorded"},
      {"displayProgress", "kautham bench always shows its progress"},
      {"saveConsoleOutput", "what each run prints is always kept, in OUT/console"},
  };
  if (setting == "filename")
    return "the log is OUT/logs/" + problem + ".log (kautham bench writes everything under -o OUT)";
  return instead.at(setting);
}

}  // namespace

BenchSpec kauthamBenchSpec(const fs::path& file) {
  const core::KauthamBenchmark benchmark = core::loadKauthamBenchmark(file);
  const fs::path& scene = benchmark.entries.front().problem;
  BenchSpec spec;
  spec.name = usableName(benchmark.name, benchmark.where);
  spec.description = fmt::format(
      "Kautham benchmark {}: the planners of its {} entries on the scene and query "
      "of the first, {}",
      file.filename().string(), benchmark.entries.size(), scene.filename().string());
  spec.problems = {scene};
  spec.runs = benchmark.runCount;
  spec.time = benchmark.maxTime;
  std::set<std::string> names;
  for (const core::KauthamBenchmarkEntry& entry : benchmark.entries) {
    BenchConfig config;
    config.name = usableName(entry.alias.empty() ? entry.planner : entry.alias, entry.where);
    config.planner = entry.planner;
    config.plannerFile = entry.problem;
    if (!names.insert(config.name).second)
      throw core::InputError(entry.where,
                             "a second entry named '" + config.name +
                                 "' (its PlannerAlias, or without one its planner): the two "
                                 "would share the log's planner and a folder; give each a "
                                 "PlannerAlias of its own");
    spec.configs.push_back(std::move(config));
  }
  for (const core::KauthamBenchmarkSetting& s : benchmark.unused)
    core::warning(s.where.str() + ": Kautham's " + s.name + " \"" + s.value + "\": ignored; " +
                  insteadOf(s.name, problemName(scene)));
  return spec;
}

}  // namespace kautham::apps
