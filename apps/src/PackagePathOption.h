#pragma once

// `--package-path NAME=DIR`: where a ROS package named in `package://NAME/...` mesh paths is.

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace kautham::apps {

void addPackagePathOption(CLI::App& command, std::vector<std::string>& values);

/// Hands the option's values to the URDF loader (core/PackagePaths.h); throws
/// std::invalid_argument for a value that is not NAME=DIR or whose DIR is not a folder.
void applyPackagePaths(const std::vector<std::string>& values);

}  // namespace kautham::apps
