// `kautham planners`: every registered planner with its parameters.

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "Commands.h"
#include "kautham/planners/PlanRequest.h"
#include "kautham/planners/PlannerRegistry.h"
#include "kautham/planners/PluginLoader.h"

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

/// A markdown table cell: '|' would end it.
std::string cell(const std::string& text) {
  std::string escaped;
  for (char c : text) escaped += c == '|' ? std::string("\\|") : std::string(1, c);
  return escaped;
}

void printMarkdownTable(const std::vector<core::ParameterSpec>& specs) {
  if (specs.empty()) {
    fmt::print("No parameters of its own.\n");
    return;
  }
  fmt::print("| parameter | type | default | range | also accepted | meaning |\n");
  fmt::print("| --- | --- | --- | --- | --- | --- |\n");
  for (const core::ParameterSpec& s : specs) {
    const std::string range = s.type == core::ParameterType::Boolean
                                  ? "true, false"
                                  : "[" + s.formatValue(s.min) + ", " + s.formatValue(s.max) + "]";
    std::string aliases;
    for (const std::string& alias : s.aliases)
      aliases += (aliases.empty() ? "" : ", ") + ("`" + alias + "`");
    fmt::print("| `{}` | {} | {} | {} | {} | {} |\n", s.name, typeName(s.type),
               s.formatValue(s.defaultValue), range, cell(aliases), cell(s.description));
  }
}

bool sameParameters(const std::vector<core::ParameterSpec>& a,
                    const std::vector<core::ParameterSpec>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].name != b[i].name || a[i].type != b[i].type ||
        a[i].formatValue(a[i].defaultValue) != b[i].formatValue(b[i].defaultValue) ||
        a[i].description != b[i].description)
      return false;
  return !a.empty();
}

/// The planner listed after `entry` whose parameters are the same as its own (goal-steering
/// takes p-KPIECE's), listed in full there: the last of such a group has the table.
const planners::PlannerRegistry::Entry* listedLaterWithSameParameters(
    const planners::PlannerRegistry::Entry& entry) {
  const planners::PlannerRegistry::Entry* last = nullptr;
  bool after = false;
  for (const auto* other : planners::plannerRegistry().entries()) {
    if (after && sameParameters(entry.parameters, other->parameters)) last = other;
    after = after || other == &entry;
  }
  return last;
}

/// The same as the text listing, as markdown: docs/planners.md holds it (scripts/planner-docs.py).
void printMarkdown() {
  fmt::print("### Every planner\n\n");
  printMarkdownTable(planners::commonParameters());
  for (const auto* entry : planners::plannerRegistry().entries()) {
    fmt::print("\n### {}\n\n{}\n\n", entry->name, cell(entry->summary));
    if (const auto* same = listedLaterWithSameParameters(*entry))
      fmt::print("The parameters of {} (below).\n", same->name);
    else
      printMarkdownTable(entry->parameters);
  }
}

}  // namespace

void addPlannersCommand(CLI::App& app, int& exitCode) {
  CLI::App* command = app.add_subcommand("planners", "List the planners and their parameters");
  auto markdown = std::make_shared<bool>(false);
  command->add_flag("--markdown", *markdown,
                    "print markdown tables (docs/planners.md is made from them)");
  command->footer("Exit codes: 0 listed, 2 a plugin that does not load.");
  command->callback([&exitCode, markdown] {
    if (*markdown) {
      printMarkdown();
      exitCode = kExitSolved;
      return;
    }
    fmt::print("Parameters of every planner (set with --set NAME=VALUE or <Parameter name>):\n");
    printParameters(planners::commonParameters());
    for (const auto* entry : planners::plannerRegistry().entries()) {
      fmt::print("\n{}: {}\n", entry->name, entry->summary);
      const std::filesystem::path plugin = planners::pluginOfPlanner(entry->name);
      if (!plugin.empty()) fmt::print("    from plugin {}\n", plugin.string());
      if (const auto* same = listedLaterWithSameParameters(*entry))
        fmt::print("    the parameters of {} (below)\n", same->name);
      else
        printParameters(entry->parameters);
    }
    exitCode = kExitSolved;
  });
}

}  // namespace kautham::apps
