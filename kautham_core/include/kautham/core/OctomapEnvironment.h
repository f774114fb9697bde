#pragma once

// Sensed environments: the occupied voxels of an OctoMap octree (.bt or .ot) as fixed boxes.
// The octomap library stays behind this header: users see boxes and an ObjectInstance only.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "kautham/core/InputError.h"
#include "kautham/core/Problem.h"

namespace kautham::core {

/// The occupied space of an octree as disjoint axis-aligned boxes, in the octree's frame.
struct OctomapBoxes {
  double resolution = 0.0;                 ///< side of the finest voxel, metres
  std::size_t leaves = 0;                  ///< occupied leaves of the octree (of any size)
  double occupiedVolume = 0.0;             ///< total volume of the occupied leaves, m^3
  std::vector<Eigen::AlignedBox3d> boxes;  ///< merged leaves; their union is the occupied space
};

/// Default probability at or above which a leaf counts as occupied (OctoMap's own default).
constexpr double kDefaultOccupancyThreshold = 0.5;
/// Most boxes an environment may have after merging: a larger scene is too slow to simulate
/// and to draw; coarsen the octree instead.
constexpr std::size_t kMaxEnvironmentBoxes = 20000;

/// Reads a binary (.bt, OcTree::readBinary) or full (.ot, AbstractOcTree::read, must be an
/// OcTree) octree and merges its occupied leaves into boxes: neighbouring boxes with the same
/// cross-section are joined along x, then y, then z. The file is checked byte by byte before
/// octomap parses it, so a truncated or corrupt file is an error, not a crash. Every error
/// (missing, unreadable, corrupt or empty octree, a .ot that holds another tree type) is an
/// InputError at `where`, the element that named the file.
OctomapBoxes readOctomapBoxes(const std::filesystem::path& file, double occupancyThreshold,
                              const SourceLocation& where);

/// A fixed object made of the boxes: one link, "occupied", carrying every box as a collision
/// shape (no mass: fixed objects are static geometry). Its `environment` records the source.
ObjectInstance makeEnvironmentObject(const std::string& name, const std::filesystem::path& file,
                                     const OctomapBoxes& boxes, const Pose& home,
                                     const SourceLocation& where);

}  // namespace kautham::core
