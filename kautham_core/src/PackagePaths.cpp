#include "kautham/core/PackagePaths.h"

#include <cstdlib>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include <tinyxml2.h>

namespace kautham::core {

namespace fs = std::filesystem;

namespace {

std::mutex pathsMutex;
std::map<std::string, fs::path>& given() {
  static std::map<std::string, fs::path> paths;
  return paths;
}

bool isPackage(const fs::path& dir, const std::string& name) {
  std::error_code ignored;
  const fs::path xml = dir / "package.xml";
  if (!fs::is_regular_file(xml, ignored)) return false;
  const std::optional<std::string> found = packageXmlName(xml);
  return found && *found == name;
}

/// A folder that is the package, or holds it within `depth` levels.
std::optional<fs::path> searchBelow(const fs::path& dir, const std::string& name, int depth) {
  std::error_code error;
  if (!fs::is_directory(dir, error)) return std::nullopt;
  if (isPackage(dir, name)) return dir;
  if (depth == 0) return std::nullopt;
  // The usual layout first: the package's folder carries its name.
  if (isPackage(dir / name, name)) return dir / name;
  for (fs::directory_iterator it(dir, fs::directory_options::skip_permission_denied, error), end;
       !error && it != end; it.increment(error)) {
    if (!it->is_directory(error)) continue;
    const std::string leaf = it->path().filename().string();
    if (leaf.empty() || leaf[0] == '.') continue;
    if (auto found = searchBelow(it->path(), name, depth - 1)) return found;
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> packageXmlName(const fs::path& packageXml) {
  tinyxml2::XMLDocument document;
  if (document.LoadFile(packageXml.string().c_str()) != tinyxml2::XML_SUCCESS) return std::nullopt;
  const tinyxml2::XMLElement* root = document.FirstChildElement("package");
  const tinyxml2::XMLElement* name = root ? root->FirstChildElement("name") : nullptr;
  if (!name || !name->GetText()) return std::nullopt;
  std::string text = name->GetText();
  const auto first = text.find_first_not_of(" \t\r\n");
  const auto last = text.find_last_not_of(" \t\r\n");
  if (first == std::string::npos) return std::nullopt;
  return text.substr(first, last - first + 1);
}

void setPackagePaths(std::map<std::string, fs::path> paths) {
  std::lock_guard<std::mutex> lock(pathsMutex);
  given() = std::move(paths);
}

const std::map<std::string, fs::path>& packagePaths() { return given(); }

std::pair<std::string, fs::path> parsePackagePath(const std::string& text) {
  const auto equals = text.find('=');
  if (equals == std::string::npos || equals == 0 || equals + 1 == text.size())
    throw std::invalid_argument(
        "--package-path takes NAME=DIR (the folder of ROS package NAME), "
        "got '" +
        text + "'");
  return {text.substr(0, equals), fs::path(text.substr(equals + 1))};
}

std::optional<fs::path> findPackage(const std::string& name, const fs::path& urdfFile) {
  {
    std::lock_guard<std::mutex> lock(pathsMutex);
    if (auto it = given().find(name); it != given().end()) return it->second;
  }
  if (const char* env = std::getenv("ROS_PACKAGE_PATH")) {
    std::stringstream folders(env);
    std::string folder;
    while (std::getline(folders, folder, ':'))
      if (!folder.empty())
        if (auto found = searchBelow(folder, name, 3)) return found;
  }
  for (fs::path dir = fs::absolute(urdfFile).parent_path(); !dir.empty(); dir = dir.parent_path()) {
    if (isPackage(dir, name)) return dir;
    if (isPackage(dir / name, name)) return dir / name;
    if (dir == dir.parent_path()) break;
  }
  return std::nullopt;
}

}  // namespace kautham::core
