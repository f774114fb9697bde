#include <cstdlib>
#include <filesystem>
#include <iostream>

#include <fmt/format.h>
#include <ompl/util/Console.h>

#include "Commands.h"
#include "kautham/core/InputError.h"
#include "kautham/core/Version.h"
#include "kautham/planners/Plugin.h"
#include "kautham/planners/PluginLoader.h"

namespace {

/// The folder of this program, as the system ran it (for the plugin folder next to it).
std::filesystem::path programFolder() {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::filesystem::path() : self.parent_path();
}

/// Loads every plugin: --plugin, KAUTHAM_PLUGIN_PATH, the folder next to the program.
void loadPlugins(const std::vector<std::string>& options) {
  const char* path = std::getenv("KAUTHAM_PLUGIN_PATH");
  for (const std::filesystem::path& file :
       kautham::planners::pluginFiles(options, path ? path : "", programFolder()))
    kautham::planners::loadPlannerPlugin(file);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"kautham: physics-based motion planning for grasping in clutter"};
  app.set_version_flag("--version",
                       fmt::format("kautham {} (planner plugin ABI {})", kautham::core::version(),
                                   KAUTHAM_PLUGIN_ABI_VERSION));
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 solved, 1 ran but not solved, 2 bad input.\n"
      "Example: kautham plan problems/pusher_cans_5.xml --seed 1 -o out/plan.json\n"
      "         kautham view out/plan.json -o out/plan.html\n"
      "Problem files: docs/problem-format.md. Planner plugins: docs/plugins.md");
  app.fallthrough();

  std::vector<std::string> plugins;
  app.add_option("--plugin", plugins,
                 "load planners from this plugin library (repeatable; also the folders and "
                 "files of KAUTHAM_PLUGIN_PATH, and ../lib/kautham/plugins next to the program)")
      ->allow_extra_args(false);
  // Before any subcommand runs: a plugin's planners are there for all of them.
  app.parse_complete_callback([&plugins] { loadPlugins(plugins); });

  // OMPL's informational messages would drown our summary; its warnings and errors stay.
  ompl::msg::setLogLevel(std::getenv("KAUTHAM_OMPL_DEBUG") ? ompl::msg::LOG_DEBUG
                                                           : ompl::msg::LOG_WARN);

  int exitCode = kautham::apps::kExitSolved;
  kautham::apps::addPlanCommand(app, exitCode);
  kautham::apps::addCheckCommand(app, exitCode);
  kautham::apps::addPlannersCommand(app, exitCode);
  kautham::apps::addGenerateCommand(app, exitCode);
  kautham::apps::addViewCommand(app, exitCode);
  kautham::apps::addValidateCommand(app, exitCode);
  kautham::apps::addBenchCommand(app, exitCode);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kautham::apps::kExitBadInput;
  } catch (const kautham::core::InputError& e) {  // a plugin that cannot be loaded
    fmt::print(stderr, "error: {}\n", e.what());
    return kautham::apps::kExitBadInput;
  }
  return exitCode;
}
