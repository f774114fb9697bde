#pragma once

#include <filesystem>
#include <string>

namespace kautham::test {

/// A file of the repository (problems, models, test data), by its path from the root.
inline std::filesystem::path repoFile(const std::string& relative) {
  return std::filesystem::path(KAUTHAM_SOURCE_DIR) / relative;
}

}  // namespace kautham::test
