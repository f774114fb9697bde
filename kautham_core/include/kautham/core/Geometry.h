#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <variant>
#include <vector>

#include <Eigen/Geometry>

#include "kautham/core/ConvexHull.h"

namespace kautham::core {

/// Collision primitives, in the conventions of URDF (cylinders along their local z axis).
struct Box {
  Eigen::Vector3d size;  ///< full side lengths
};
struct Cylinder {
  double radius;
  double length;
};
struct Sphere {
  double radius;
};

/// A triangle mesh in its link's frame (already scaled), with its convex hull: dynamic bodies
/// collide as the hull, fixed ones as the triangles. The data is shared and never changes, so
/// copying a Mesh is cheap.
struct Mesh {
  struct Data {
    std::filesystem::path source;  ///< the mesh file it was loaded from
    std::vector<Eigen::Vector3d> vertices;
    std::vector<std::array<int, 3>> triangles;  ///< vertex indices, counter-clockwise outside
    ConvexHull hull;                            ///< of the vertices
  };
  std::shared_ptr<const Data> data;

  const std::vector<Eigen::Vector3d>& vertices() const { return data->vertices; }
  const std::vector<std::array<int, 3>>& triangles() const { return data->triangles; }
  const ConvexHull& hull() const { return data->hull; }
};

using Shape = std::variant<Box, Cylinder, Sphere, Mesh>;

/// A primitive placed in the frame of the link it belongs to.
struct CollisionShape {
  Shape shape;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
};

/// A mesh file that a URDF <visual> names: found, but read only by what draws it (the viewer),
/// since planning never needs visual meshes and they can be large (the UR5's DAE files: 6.5 MB).
struct MeshFile {
  std::filesystem::path file;
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();  ///< per axis, the model's scale included
};

/// What a link looks like (URDF <visual>), placed in the link's frame; drawn instead of the
/// collision shapes when a model has it.
struct VisualShape {
  std::variant<Box, Cylinder, Sphere, MeshFile> geometry;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  std::optional<Eigen::Vector4d> colour;  ///< the <material>'s rgba, when it gives one
};

/// Axis-aligned bounding box of a shape placed at `pose` in the world.
Eigen::AlignedBox3d boundingBox(const Shape& shape, const Eigen::Isometry3d& pose);

}  // namespace kautham::core
