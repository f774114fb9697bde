#pragma once
// A plan file's controls (from `kautham plan -o`), for the benchmark programs that run a plan.

#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace kautham::benchmarks {

struct PlanControl {
  std::vector<double> values;  ///< the normalized control
  unsigned steps = 0;          ///< propagation steps
  double duration = 0.0;       ///< seconds
};

inline std::vector<PlanControl> readControls(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file + ": cannot be read");
  const nlohmann::json plan = nlohmann::json::parse(in);
  std::vector<PlanControl> controls;
  for (const auto& c : plan.at("controls"))
    controls.push_back({c.at("values").get<std::vector<double>>(), c.at("steps").get<unsigned>(),
                        c.at("duration").get<double>()});
  if (controls.empty()) throw std::runtime_error(file + ": the plan has no controls");
  return controls;
}

}  // namespace kautham::benchmarks
