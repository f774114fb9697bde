#include "kautham/core/MeshSimplify.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <unordered_map>

#include <Eigen/Geometry>

namespace kautham::core {

namespace {

/// Vertex clustering on a grid of `cell` metres: one vertex per occupied cell, at the mean of
/// the vertices in it.
TriangleMesh clusterVertices(const TriangleMesh& mesh, const Eigen::Vector3d& origin, double cell) {
  std::unordered_map<std::uint64_t, int> clusterOfCell;
  std::vector<int> clusterOf(mesh.vertices.size());
  std::vector<Eigen::Vector3d> sums;
  std::vector<int> counts;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const Eigen::Vector3d index = ((mesh.vertices[v] - origin) / cell).array().floor();
    // 21 bits per axis: the coarsest search cell spans the mesh, the finest 2^-20 of it.
    const std::uint64_t key = (static_cast<std::uint64_t>(index.x()) << 42) |
                              (static_cast<std::uint64_t>(index.y()) << 21) |
                              static_cast<std::uint64_t>(index.z());
    auto [it, added] = clusterOfCell.emplace(key, static_cast<int>(sums.size()));
    if (added) {
      sums.push_back(Eigen::Vector3d::Zero());
      counts.push_back(0);
    }
    clusterOf[v] = it->second;
    sums[it->second] += mesh.vertices[v];
    ++counts[it->second];
  }
  TriangleMesh result;
  for (std::size_t c = 0; c < sums.size(); ++c) result.vertices.push_back(sums[c] / counts[c]);
  std::set<std::array<int, 3>> seen;  // a triangle and its repeats, whatever their order
  for (const auto& t : mesh.triangles) {
    const std::array<int, 3> corners{clusterOf[t[0]], clusterOf[t[1]], clusterOf[t[2]]};
    if (corners[0] == corners[1] || corners[1] == corners[2] || corners[0] == corners[2]) continue;
    std::array<int, 3> sorted = corners;
    std::sort(sorted.begin(), sorted.end());
    if (seen.insert(sorted).second) result.triangles.push_back(corners);
  }
  return result;
}

/// Drops the vertices no triangle uses, renumbering the triangles.
TriangleMesh dropUnusedVertices(TriangleMesh mesh) {
  std::vector<int> newIndex(mesh.vertices.size(), -1);
  std::vector<Eigen::Vector3d> kept;
  for (auto& t : mesh.triangles)
    for (int& corner : t) {
      if (newIndex[corner] < 0) {
        newIndex[corner] = static_cast<int>(kept.size());
        kept.push_back(mesh.vertices[corner]);
      }
      corner = newIndex[corner];
    }
  mesh.vertices = std::move(kept);
  return mesh;
}

}  // namespace

TriangleMesh simplifyMesh(const TriangleMesh& mesh, std::size_t maxTriangles) {
  if (mesh.triangles.size() <= maxTriangles || mesh.vertices.empty()) return mesh;
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& v : mesh.vertices) box.extend(v);
  const double span = std::max(box.sizes().maxCoeff(), 1e-9);
  // Bisect the cell size between 2^-20 of the mesh (every vertex its own cell) and the whole
  // mesh (at most eight cells), in log scale: the triangle count falls as the cell grows.
  double fine = span / (1 << 20), coarse = span;
  TriangleMesh best = clusterVertices(mesh, box.min(), coarse);
  for (int i = 0; i < 24 && coarse / fine > 1.02; ++i) {
    const double cell = std::sqrt(fine * coarse);
    TriangleMesh candidate = clusterVertices(mesh, box.min(), cell);
    if (candidate.triangles.size() <= maxTriangles) {
      coarse = cell;
      best = std::move(candidate);
    } else {
      fine = cell;
    }
  }
  return dropUnusedVertices(std::move(best));
}

}  // namespace kautham::core
