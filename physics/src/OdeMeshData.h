#pragma once

// Private to the physics library: core meshes in the layouts that ODE's convex and trimesh
// geometries read. ODE keeps pointers into these arrays, so they must outlive the geometries.

#include <vector>

#include <ode/ode.h>

#include "kautham/core/Geometry.h"

namespace kautham::physics {

struct OdeMeshData {
  /// A convex hull as dCreateConvex wants it: planes (a, b, c, d) with outward unit normals,
  /// ax + by + cz = d on the face; points x, y, z; per face its corner count followed by the
  /// corner indices, counter-clockwise seen from outside, faces in the order of the planes.
  struct Convex {
    std::vector<dReal> planes;
    std::vector<dReal> points;
    std::vector<unsigned> polygons;
  };

  explicit OdeMeshData(const core::Mesh& mesh);
  ~OdeMeshData();
  OdeMeshData(const OdeMeshData&) = delete;
  OdeMeshData& operator=(const OdeMeshData&) = delete;

  /// A new convex geometry of the hull (for bodies that move). Its frame is the hull's centre
  /// (convexCentre() in the mesh's frame), not the mesh's origin: ODE's convex collision
  /// (libccd) takes the geometry's origin as a point inside it, and ODE prints warnings on
  /// stdout for a hull that does not hold its origin (links whose mesh starts at a joint).
  dGeomID createConvex();
  const Eigen::Vector3d& convexCentre() const { return centre_; }
  /// A new trimesh geometry of the triangles (for fixed geometry).
  dGeomID createTriMesh();

  const core::Mesh mesh;  ///< keeps the source data alive

 private:
  Convex convex_;
  Eigen::Vector3d centre_ = Eigen::Vector3d::Zero();
  std::vector<dReal> triVertices_;
  std::vector<dTriIndex> triIndices_;
  dTriMeshDataID triMesh_ = nullptr;
};

}  // namespace kautham::physics
