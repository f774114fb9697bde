#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace kautham::core {

/// Where the folder of a ROS package named in a `package://NAME/...` mesh path is looked for,
/// in this order:
///   1. the folders given with `--package-path NAME=DIR` (setPackagePaths);
///   2. the folders of the ROS_PACKAGE_PATH environment variable (colon separated): a folder that
///      is the package (its package.xml names NAME) or holds it, up to three levels down;
///   3. the URDF's own folder and its ancestors: one whose package.xml names NAME, or which has a
///      subfolder NAME with such a package.xml (a package beside the robot's package).
/// Returns the package's folder, or nothing.
std::optional<std::filesystem::path> findPackage(const std::string& name,
                                                 const std::filesystem::path& urdfFile);

/// Sets the folders of `--package-path NAME=DIR` (replacing earlier ones).
void setPackagePaths(std::map<std::string, std::filesystem::path> paths);
const std::map<std::string, std::filesystem::path>& packagePaths();

/// Parses "NAME=DIR"; throws std::invalid_argument with a message when it is not of that form.
std::pair<std::string, std::filesystem::path> parsePackagePath(const std::string& text);

/// The <name> of a package.xml, or nothing when it cannot be read.
std::optional<std::string> packageXmlName(const std::filesystem::path& packageXml);

}  // namespace kautham::core
