#pragma once

#include <array>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>

namespace kautham::core {

/// Vertices and triangles of a mesh file, every mesh of the file merged into one.
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
};

/// A mesh file that cannot be read, or that holds no triangles.
class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Reads a mesh file with Assimp (STL, OBJ, DAE and the other formats it knows), or with Coin3D
/// for Open Inventor `.iv` and VRML `.wrl` files: faces are triangulated, identical vertices
/// joined, node transforms applied, and every coordinate multiplied by `scale` per axis. A scale
/// with an odd number of negative factors mirrors the mesh (its triangles are turned so they
/// stay counter-clockwise from outside). Throws MeshError naming what is wrong.
TriangleMesh loadMesh(const std::filesystem::path& file,
                      const Eigen::Vector3d& scale = Eigen::Vector3d::Ones());

}  // namespace kautham::core
