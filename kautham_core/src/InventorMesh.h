#pragma once

// Private helper of MeshLoader: Open Inventor (.iv) and VRML (.wrl) files through Coin3D.

#include <filesystem>

#include <Eigen/Core>

#include "kautham/core/MeshLoader.h"

namespace kautham::core {

/// Whether `file` is an Open Inventor or VRML file (by its extension).
bool isInventorFile(const std::filesystem::path& file);

/// Reads an Open Inventor or VRML file with Coin3D: every shape of the scene graph is
/// triangulated by Coin, placed by the transforms above it, and its corners joined where they
/// coincide. Throws MeshError with Coin's first read error when the file cannot be read.
TriangleMesh loadInventorMesh(const std::filesystem::path& file, const Eigen::Vector3d& scale);

}  // namespace kautham::core
