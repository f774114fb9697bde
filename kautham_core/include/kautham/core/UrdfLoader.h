#pragma once

#include <filesystem>

#include "kautham/core/InputError.h"
#include "kautham/core/KinematicModel.h"

namespace kautham::core {

/// Reads a URDF file (box, cylinder and sphere collision geometry) into a KinematicModel,
/// scaling every length by `scale`. Errors name the URDF file and, for XML errors, the line;
/// `requestedBy` is the problem-file element that asked for it.
KinematicModel loadUrdf(const std::filesystem::path& urdfFile, double scale,
                        const SourceLocation& requestedBy);

}  // namespace kautham::core
