#pragma once

#include <filesystem>

#include "kautham/core/InputError.h"
#include "kautham/core/KinematicModel.h"

namespace kautham::core {

/// Reads a URDF file (box, cylinder, sphere and mesh collision geometry) into a KinematicModel,
/// scaling every length by `scale`. Mesh files are found relative to the URDF's folder and get
/// their convex hull. Errors name the URDF file and, for XML and mesh errors, the line;
/// `requestedBy` is the problem-file element that asked for it.
KinematicModel loadUrdf(const std::filesystem::path& urdfFile, double scale,
                        const SourceLocation& requestedBy);

}  // namespace kautham::core
