#pragma once

// Loading planner plugins (Plugin.h) into the registry. A plugin that cannot be loaded is bad
// input: core::InputError naming its file, which the program reports with exit code 2.

#include <filesystem>
#include <string>
#include <vector>

#include "kautham/planners/PlannerRegistry.h"

namespace kautham::planners {

/// Loads the plugin library `file` and adds its planners to `registry`. Throws
/// core::InputError naming the file when it is missing, not a loadable library, exports no
/// registration function, was built for another plugin ABI, throws while registering,
/// registers nothing, or registers a planner whose name is taken (a built-in or another
/// plugin's). Nothing of a failed plugin is registered. Loading the same file twice is a no-op.
void loadPlannerPlugin(const std::filesystem::path& file,
                       PlannerRegistry& registry = plannerRegistry());

/// The plugin files a program loads, in order: each `--plugin` path, then each entry of
/// `pluginPath` (KAUTHAM_PLUGIN_PATH: files or folders separated by ':'), then the folder
/// `programFolder`/../lib/kautham/plugins if it exists. A folder gives its `*.so` files in name
/// order; a path given twice appears once. A path that does not exist is an error (InputError),
/// except the folder next to the program.
std::vector<std::filesystem::path> pluginFiles(const std::vector<std::string>& options,
                                               const std::string& pluginPath,
                                               const std::filesystem::path& programFolder);

/// The plugin folder of a program in `programFolder`: ../lib/kautham/plugins from it.
std::filesystem::path pluginFolderOf(const std::filesystem::path& programFolder);

/// The files of the plugins loaded so far, absolute, in load order.
std::vector<std::filesystem::path> loadedPlugins();

/// The plugin that registered planner `name`, or an empty path for a built-in one.
std::filesystem::path pluginOfPlanner(const std::string& name);

}  // namespace kautham::planners
