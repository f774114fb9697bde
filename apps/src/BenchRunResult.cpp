#include "BenchRunResult.h"

#include <fstream>

#include <fmt/format.h>
#include <ompl/base/PlannerStatus.h>

#include "kautham/core/InputError.h"
#include "kautham/core/Version.h"

namespace kautham::apps {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json childJson(const ChildExit& exit, const fs::path& file, bool wroteFile) {
  return {{"exit", exit.describe()},     {"exit_code", exit.exitCode},
          {"signal", exit.signal},       {"wall_time", exit.wallTime},
          {"max_rss_mb", exit.maxRssMb}, {"file", wroteFile ? json(file.string()) : json(nullptr)}};
}

std::string statusName(int status) {
  return ompl::base::PlannerStatus(static_cast<ompl::base::PlannerStatus::StatusType>(status))
      .asString();
}

json plannerParameters(const RunEvidence& evidence) {
  if (!evidence.planFile) return json::object();
  const json& planner = evidence.planFile->at("planner");
  return planner.contains("ompl_parameters") ? planner.at("ompl_parameters") : json::object();
}

}  // namespace

json runSetup(const BenchSpec& spec, const RunKey& key, double timeLimit) {
  const BenchConfig& config = spec.configs[key.config];
  json setup = {{"problem_file", spec.problems[key.problem].string()},
                {"planner", config.planner},
                {"set", config.sets},
                {"seed", spec.seed + key.run},
                {"time_limit", timeLimit},
                {"threads", spec.threads ? json(*spec.threads) : json(nullptr)},
                {"validate_runs", spec.validate}};
  // Only when given: the results of earlier campaigns, without the key, still resume.
  if (!config.physics.empty()) setup["physics"] = config.physics;
  if (config.plannerFile) setup["planner_file"] = config.plannerFile->string();
  return setup;
}

json makeRunResult(const BenchSpec& spec, const RunKey& key, const json& setup,
                   const RunEvidence& evidence, const RunPlace& place, const BenchLayout& layout) {
  const std::string problem = problemName(spec.problems[key.problem]);
  const std::string config = spec.configs[key.config].name;
  auto relative = [&](const fs::path& file) { return file.lexically_relative(layout.root()); };
  const int status = runStatus(evidence);
  json validation = nullptr;
  if (evidence.validation) {
    validation =
        childJson(*evidence.validation, relative(layout.validation(problem, config, key.run)),
                  evidence.validationFile.has_value());
    if (evidence.validated()) {
      validation["successes"] = evidence.validationFile->at("successes");
      validation["runs"] = evidence.validationFile->at("runs");
    }
  }
  return {{"format", "kautham-bench-run"},
          {"format_version", kRunResultFormatVersion},
          {"benchmark", spec.name},
          {"problem", problem},
          {"problem_index", key.problem},
          {"config", config},
          {"config_index", key.config},
          {"run", key.run},
          {"index", key.index},
          {"runs_per_config", spec.runs},
          {"bench_seed", spec.seed},
          {"setup", setup},
          {"status", statusName(status)},
          {"solved", evidence.solved()},
          {"failed", evidence.failed()},
          {"plan", childJson(evidence.plan, relative(layout.plan(problem, config, key.run)),
                             evidence.planFile.has_value())},
          {"validation", validation},
          {"console", relative(layout.console(problem, config, key.run)).string()},
          {"host", place.host},
          {"cpu_info", place.cpuInfo},
          {"started_at", place.startedAt},
          {"kautham_version", core::version()},
          {"properties", runProperties(evidence)},
          // The planner's settings as its OMPL parameter set held them (the log's common
          // properties); none when the plan child wrote no plan.
          {"planner_parameters", plannerParameters(evidence)}};
}

json readRunResult(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw core::InputError({file, 0}, "cannot open the result file");
  json result;
  try {
    result = json::parse(in);
  } catch (const json::parse_error& e) {
    throw core::InputError({file, 0}, std::string("not a JSON result file: ") + e.what());
  }
  bool valid = false;
  try {
    valid = result.is_object() && result.value("format", "") == "kautham-bench-run" &&
            result.value("format_version", 0) == kRunResultFormatVersion &&
            result.at("properties").is_object() && result.at("setup").is_object() &&
            result.at("problem").is_string() && result.at("config").is_string() &&
            result.at("run").is_number_unsigned();
  } catch (const json::exception&) {  // a key missing or of another type
  }
  if (!valid)
    throw core::InputError({file, 0}, fmt::format("not a kautham-bench-run result of format "
                                                  "version {}",
                                                  kRunResultFormatVersion));
  return result;
}

std::vector<json> readRunResults(const BenchLayout& folder) {
  std::vector<json> results;
  if (!fs::is_directory(folder.runsFolder())) return results;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(folder.runsFolder()))
    if (entry.is_regular_file() && entry.path().extension() == ".json")  // not *.json.tmp
      results.push_back(readRunResult(entry.path()));
  return results;
}

std::string runIdentity(const json& result) {
  return fmt::format("{}/{}/{}", result["problem"].get<std::string>(),
                     result["config"].get<std::string>(), result["run"].get<std::size_t>());
}

}  // namespace kautham::apps
