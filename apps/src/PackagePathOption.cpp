#include "PackagePathOption.h"

#include <filesystem>
#include <map>
#include <stdexcept>

#include "kautham/core/PackagePaths.h"

namespace kautham::apps {

void addPackagePathOption(CLI::App& command, std::vector<std::string>& values) {
  command
      .add_option("--package-path", values,
                  "NAME=DIR: the folder of ROS package NAME, for package://NAME/... mesh paths "
                  "(also found through ROS_PACKAGE_PATH and a package.xml above the URDF)")
      ->allow_extra_args(false);
}

void applyPackagePaths(const std::vector<std::string>& values) {
  std::map<std::string, std::filesystem::path> paths;
  for (const std::string& value : values) {
    auto [name, dir] = core::parsePackagePath(value);
    std::error_code ignored;
    if (!std::filesystem::is_directory(dir, ignored))
      throw std::invalid_argument("--package-path " + value + ": '" + dir.string() +
                                  "' is not a folder");
    paths[name] = std::filesystem::absolute(dir);
  }
  core::setPackagePaths(std::move(paths));
}

}  // namespace kautham::apps
