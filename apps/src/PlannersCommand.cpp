// `kautham planners`: every registered planner with its parameters.

#include <iostream>

#include <fmt/format.h>

#include "Commands.h"
#include "kautham/planners/PlanRequest.h"
#include "kautham/planners/PlannerRegistry.h"

namespace kautham::apps {

namespace {

const char* typeName(core::ParameterType type) {
  switch (type) {
    case core::ParameterType::Real:
      return "real";
    case core::ParameterType::Integer:
      return "integer";
    case core::ParameterType::Boolean:
      return "bool";
  }
  return "?";
}

void printParameters(const std::vector<core::ParameterSpec>& specs) {
  for (const core::ParameterSpec& s : specs) {
    std::string range = s.type == core::ParameterType::Boolean
                            ? "true|false"
                            : "[" + s.formatValue(s.min) + ", " + s.formatValue(s.max) + "]";
    fmt::print("    {:<24} {:<8} default {:<8} {:<18} {}\n", s.name, typeName(s.type),
               s.formatValue(s.defaultValue), range, s.description);
    for (const std::string& alias : s.aliases) fmt::print("    {:<24} (also \"{}\")\n", "", alias);
  }
}

}  // namespace

void addPlannersCommand(CLI::App& app, int& exitCode) {
  CLI::App* command = app.add_subcommand("planners", "List the planners and their parameters");
  command->callback([&exitCode] {
    fmt::print("Parameters of every planner (set with --set NAME=VALUE or <Parameter name>):\n");
    printParameters(planners::commonParameters());
    for (const auto* entry : planners::plannerRegistry().entries()) {
      fmt::print("\n{}: {}\n", entry->name, entry->summary);
      printParameters(entry->parameters);
    }
    exitCode = kExitSolved;
  });
}

}  // namespace kautham::apps
