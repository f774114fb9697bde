#pragma once

// Where `kautham bench` keeps things in its output folder OUT:
//   OUT/runs/PROBLEM/CONFIG/run-R.json      one result per run (resume skips those that exist)
//   OUT/plans/PROBLEM/CONFIG/run-R.json     the plan, for `kautham view` or `kautham validate`
//   OUT/plans/PROBLEM/CONFIG/run-R.validation.json   `kautham validate --json`
//   OUT/console/PROBLEM/CONFIG/run-R.txt    what the children printed
//   OUT/logs/PROBLEM.log                    the OMPL benchmark log of a problem

#include <cstddef>
#include <filesystem>
#include <string>

namespace kautham::apps {

class BenchLayout {
 public:
  explicit BenchLayout(std::filesystem::path root) : root_(std::move(root)) {}

  const std::filesystem::path& root() const { return root_; }
  std::filesystem::path runsFolder() const { return root_ / "runs"; }
  std::filesystem::path logsFolder() const { return root_ / "logs"; }

  std::filesystem::path result(const std::string& problem, const std::string& config,
                               std::size_t run) const {
    return file("runs", problem, config, run, ".json");
  }
  std::filesystem::path plan(const std::string& problem, const std::string& config,
                             std::size_t run) const {
    return file("plans", problem, config, run, ".json");
  }
  std::filesystem::path validation(const std::string& problem, const std::string& config,
                                   std::size_t run) const {
    return file("plans", problem, config, run, ".validation.json");
  }
  std::filesystem::path console(const std::string& problem, const std::string& config,
                                std::size_t run) const {
    return file("console", problem, config, run, ".txt");
  }
  std::filesystem::path log(const std::string& problem) const {
    return logsFolder() / (problem + ".log");
  }

 private:
  std::filesystem::path file(const char* kind, const std::string& problem,
                             const std::string& config, std::size_t run,
                             const char* extension) const {
    return root_ / kind / problem / config / ("run-" + std::to_string(run) + extension);
  }

  std::filesystem::path root_;
};

}  // namespace kautham::apps
