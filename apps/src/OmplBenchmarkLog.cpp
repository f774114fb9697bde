#include "OmplBenchmarkLog.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <locale>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <ompl/base/PlannerStatus.h>
#include <ompl/config.h>
#include <ompl/util/Time.h>

#include "OutputFile.h"

namespace kautham::apps {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// OMPL prints header numbers with a default ostream: 6 significant digits, classic locale.
std::string number(double value) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out << value;
  return out.str();
}

/// The parser reads the last word of "Experiment ..." and "Running on ...": no spaces.
std::string oneWord(std::string text) {
  std::replace_if(
      text.begin(), text.end(), [](unsigned char c) { return std::isspace(c); }, '_');
  return text.empty() ? "UNKNOWN" : text;
}

/// The results of one configuration, in run order.
struct Planner {
  std::string name;
  std::vector<const json*> runs;
};

std::vector<Planner> plannersOf(const std::vector<json>& results) {
  std::vector<const json*> sorted;
  for (const json& r : results) sorted.push_back(&r);
  auto order = [](const json* r) {
    return std::make_tuple(r->value("config_index", std::size_t{0}),
                           r->at("config").get<std::string>(), r->at("run").get<std::size_t>());
  };
  std::sort(sorted.begin(), sorted.end(),
            [&](const json* a, const json* b) { return order(a) < order(b); });
  std::vector<Planner> planners;
  for (const json* r : sorted) {
    if (planners.empty() || planners.back().name != r->at("config").get<std::string>())
      planners.push_back({r->at("config").get<std::string>(), {}});
    planners.back().runs.push_back(r);
  }
  return planners;
}

std::string describeSetup(const json& setup) {
  std::string sets;
  for (const json& s : setup.at("set")) sets += " " + s.get<std::string>();
  // A Kautham benchmark's entry plans with its own file's <Planner>: the log says which file.
  const std::string from =
      setup.contains("planner_file") ? " of " + setup.at("planner_file").get<std::string>() : "";
  return fmt::format("planner {}{}{}, time limit {} s, threads {}, {} executions per solved plan",
                     setup.at("planner").get<std::string>(), from,
                     sets.empty() ? "" : ", --set" + sets, number(setup.at("time_limit")),
                     setup.at("threads").is_null() ? "1" : setup.at("threads").dump(),
                     setup.at("validate_runs").dump());
}

/// What the runs were: the text between "<<<|" and "|>>>" (each line ends with a newline, or
/// the parser would not find the closing mark).
std::string setupText(const json& first, const std::vector<Planner>& planners) {
  std::string text = fmt::format("kautham {}: `kautham bench`, every run in processes of its own\n",
                                 first.value("kautham_version", "?"));
  text += "problem " + first.at("setup").at("problem_file").get<std::string>() + "\n";
  for (const Planner& p : planners)
    text += p.name + ": " + describeSetup(p.runs.front()->at("setup")) + "\n";
  text += fmt::format("run r of every configuration plans with seed {} + r\n",
                      first.value("bench_seed", std::uint64_t{1}));
  return text;
}

/// The hosts' processors: one host's as OMPL gives it, several under their host names.
std::string cpuText(const std::vector<json>& results) {
  std::map<std::string, std::string> hosts;
  for (const json& r : results) hosts.emplace(r.value("host", ""), r.value("cpu_info", ""));
  std::string text;
  for (const auto& [host, cpu] : hosts) {
    if (hosts.size() > 1) text += host + ":\n";
    text += cpu;
    if (!text.empty() && text.back() != '\n') text += '\n';
  }
  return text;
}

std::string hostsOf(const std::vector<json>& results) {
  std::set<std::string> hosts;
  for (const json& r : results) hosts.insert(r.value("host", ""));
  std::string joined;
  for (const std::string& h : hosts) joined += (joined.empty() ? "" : ",") + h;
  return oneWord(joined);
}

std::string startDate(const std::vector<json>& results) {
  double earliest = results.front().value("started_at", 0.0);
  for (const json& r : results) earliest = std::min(earliest, r.value("started_at", 0.0));
  const auto point = std::chrono::system_clock::time_point(
      std::chrono::duration_cast<std::chrono::system_clock::duration>(
          std::chrono::duration<double>(earliest)));
  return ompl::time::as_string(point);
}

/// The seconds the runs' children took, added up (they may have run side by side).
double totalSeconds(const std::vector<json>& results) {
  double seconds = 0.0;
  for (const json& r : results) {
    seconds += r.at("plan").value("wall_time", 0.0);
    if (r.at("validation").is_object()) seconds += r.at("validation").value("wall_time", 0.0);
  }
  return seconds;
}

std::string experimentName(const json& first) {
  const std::string benchmark = first.value("benchmark", "");
  const std::string problem = first.at("problem").get<std::string>();
  return oneWord(benchmark.empty() ? problem : benchmark + "/" + problem);
}

std::string statusEnum() {
  std::string line = "status";
  for (int i = 0; i < ompl::base::PlannerStatus::TYPE_COUNT; ++i)
    line +=
        "|" +
        ompl::base::PlannerStatus(static_cast<ompl::base::PlannerStatus::StatusType>(i)).asString();
  return line;
}

/// The planner's settings, as OMPL's Benchmark takes them from Planner::params(): "name = value"
/// lines, sorted by name. Every run of a configuration has the same; the first run that
/// planned gives them (runs whose plan child wrote nothing have none).
std::vector<std::string> commonProperties(const Planner& planner) {
  std::vector<std::string> lines;
  for (const json* run : planner.runs) {
    const json parameters = run->value("planner_parameters", json::object());
    if (parameters.empty()) continue;
    for (const auto& [name, value] : parameters.items())
      lines.push_back(name + " = " + value.get<std::string>());
    break;
  }
  return lines;
}

void writePlanner(std::ostream& out, const Planner& planner) {
  std::set<std::string> properties;  // sorted, as OMPL sorts them
  for (const json* run : planner.runs)
    for (const auto& [name, value] : run->at("properties").items()) properties.insert(name);
  const std::vector<std::string> common = commonProperties(planner);
  out << planner.name << '\n' << common.size() << " common properties\n";
  for (const std::string& line : common) out << line << '\n';
  out << properties.size() << " properties for each run\n";
  for (const std::string& p : properties) out << p << '\n';
  out << planner.runs.size() << " runs\n";
  for (const json* run : planner.runs) {
    const json& values = run->at("properties");
    for (const std::string& p : properties)
      out << (values.contains(p) ? values.at(p).get<std::string>() : "") << "; ";
    out << '\n';
  }
  out << ".\n";  // control planners report no progress properties
}

}  // namespace

std::string omplBenchmarkLog(const std::vector<json>& results) {
  const std::vector<Planner> planners = plannersOf(results);
  const json& first = *planners.front().runs.front();
  double timeLimit = 0.0;
  std::size_t runs = 0;
  for (const json& r : results) {
    timeLimit = std::max(timeLimit, r.at("setup").value("time_limit", 0.0));
    runs = std::max(runs, r.value("runs_per_config", std::size_t{0}));
  }
  std::ostringstream out;
  out.imbue(std::locale::classic());
  // Debian's ompl/config.h leaves OMPL_VERSION empty; the numbers are there.
  out << "OMPL version " << OMPL_MAJOR_VERSION << '.' << OMPL_MINOR_VERSION << '.'
      << OMPL_PATCH_VERSION << '\n';
  out << "Experiment " << experimentName(first) << '\n';
  out << "0 experiment properties\n";
  out << "Running on " << hostsOf(results) << '\n';
  out << "Starting at " << startDate(results) << '\n';
  out << "<<<|\n" << setupText(first, planners) << "|>>>\n";
  out << "<<<|\n" << cpuText(results) << "|>>>\n";
  out << first.value("bench_seed", std::uint64_t{1}) << " is the random seed\n";
  out << number(timeLimit) << " seconds per run\n";
  out << "0 MB per run\n";  // bench sets no memory limit
  out << runs << " runs per planner\n";
  out << number(totalSeconds(results)) << " seconds spent to collect the data\n";
  out << "1 enum type\n" << statusEnum() << '\n';
  out << planners.size() << " planners\n";
  for (const Planner& p : planners) writePlanner(out, p);
  return out.str();
}

std::vector<fs::path> writeOmplBenchmarkLogs(const std::vector<json>& results,
                                             const fs::path& folder) {
  std::map<std::string, std::vector<json>> byProblem;
  for (const json& r : results) byProblem[r.at("problem").get<std::string>()].push_back(r);
  std::vector<fs::path> files;
  for (const auto& [problem, problemResults] : byProblem) {
    files.push_back(folder / (problem + ".log"));
    writeTextFile(files.back(), omplBenchmarkLog(problemResults));
  }
  return files;
}

}  // namespace kautham::apps
