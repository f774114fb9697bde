#pragma once

#include <filesystem>
#include <vector>

#include "kautham/core/Problem.h"

namespace kautham::core {

/// Loads a problem file (the Kautham XML format plus this project's additions, see
/// docs/problem-format.md) and checks it. Models are searched relative to the problem file's
/// folder, then in `../models/` and `../../models/` from it, then in `modelDirs`.
/// Throws InputError naming the file, the line and what was expected.
Problem loadProblem(const std::filesystem::path& problemFile,
                    const std::vector<std::filesystem::path>& modelDirs = {});

}  // namespace kautham::core
