#pragma once

#include <cstddef>

#include "kautham/core/MeshLoader.h"

namespace kautham::core {

/// The mesh with at most `maxTriangles` triangles, for pictures: vertices that fall in one cell
/// of a regular grid are merged into their mean, and triangles left with fewer than three
/// corners (or repeated) are dropped. The cell is the smallest, to within a few percent, that
/// meets the cap. A mesh already within the cap is returned as it is. Good enough to show a
/// link's shape (its outline keeps within one cell); not meant for collision geometry.
TriangleMesh simplifyMesh(const TriangleMesh& mesh, std::size_t maxTriangles);

}  // namespace kautham::core
