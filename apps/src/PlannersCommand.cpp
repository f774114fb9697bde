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

/// Whether `all` begins with `inner`, spec for spec (goal-steering's parameters are
/// p-KPIECE's and one of its own).
bool beginsWith(const std::vector<core::ParameterSpec>& all,
                const std::vector<core::ParameterSpec>& inner) {
  if (inner.empty() || inner.size() > all.size()) return false;
  for (std::size_t i = 0; i < inner.size(); ++i)
    if (all[i].name != inner[i].name || all[i].type != inner[i].type ||
        all[i].formatValue(all[i].defaultValue) != inner[i].formatValue(inner[i].defaultValue) ||
        all[i].description != inner[i].description)
      return false;
  return true;
}

/// The planner listed after `entry` whose parameters `entry`'s begin with, listed in full
/// there: the last of such a group has the table.
const planners::PlannerRegistry::Entry* listedLaterWithItsParameters(
    const planners::PlannerRegistry::Entry& entry) {
  const planners::PlannerRegistry::Entry* last = nullptr;
  bool after = false;
  for (const auto* other : planners::plannerRegistry().entries()) {
    if (after && beginsWith(entry.parameters, other->parameters)) last = other;
    after = after || other == &entry;
  }
  return last;
}

/// `entry`'s parameters after those it shares with `shared` (listedLaterWithItsParameters).
std::vector<core::ParameterSpec> ownParameters(const planners::PlannerRegistry::Entry& entry,
                                               const planners::PlannerRegistry::Entry& shared) {
  return {entry.parameters.begin() + static_cast<std::ptrdiff_t>(shared.parameters.size()),
          entry.parameters.end()};
}

/// The same as the text listing, as markdown: docs/planners.md holds it (scripts/planner-docs.py).
void printMarkdown() {
  fmt::print("### Every planner\n\n");
  printMarkdownTable(planners::commonParameters());
  for (const auto* entry : planners::plannerRegistry().entries()) {
    fmt::print("\n### {}\n\n{}\n\n", entry->name, cell(entry->summary));
    const auto* shared = listedLaterWithItsParameters(*entry);
    if (!shared) {
      printMarkdownTable(entry->parameters);
      continue;
    }
    const std::vector<core::ParameterSpec> own = ownParameters(*entry, *shared);
    fmt::print("The parameters of {} (below){}\n", shared->name, own.empty() ? "." : ", and:\n");
    if (!own.empty()) printMarkdownTable(own);
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
      const auto* shared = listedLaterWithItsParameters(*entry);
      if (!shared) {
        printParameters(entry->parameters);
        continue;
      }
      const std::vector<core::ParameterSpec> own = ownParameters(*entry, *shared);
      fmt::print("    the parameters of {} (below){}\n", shared->name, own.empty() ? "" : ", and");
      printParameters(own);
    }
    exitCode = kExitSolved;
  });
}

}  // namespace kautham::apps
