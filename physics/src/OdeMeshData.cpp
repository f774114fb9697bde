#include "OdeMeshData.h"

namespace kautham::physics {

OdeMeshData::OdeMeshData(const core::Mesh& source) : mesh(source) {
  const core::ConvexHull& hull = mesh.hull();
  for (const Eigen::Vector3d& v : hull.vertices) centre_ += v;
  if (!hull.vertices.empty()) centre_ /= static_cast<double>(hull.vertices.size());
  for (const Eigen::Vector3d& vertex : hull.vertices) {
    const Eigen::Vector3d v = vertex - centre_;
    convex_.points.insert(convex_.points.end(), {v.x(), v.y(), v.z()});
  }
  for (std::size_t f = 0; f < hull.faces.size(); ++f) {
    const Eigen::Vector4d& plane = hull.planes[f];
    const double d = plane.w() - plane.head<3>().dot(centre_);
    convex_.planes.insert(convex_.planes.end(), {plane.x(), plane.y(), plane.z(), d});
    convex_.polygons.push_back(static_cast<unsigned>(hull.faces[f].size()));
    for (int corner : hull.faces[f]) convex_.polygons.push_back(static_cast<unsigned>(corner));
  }
}

OdeMeshData::~OdeMeshData() {
  if (triMesh_) dGeomTriMeshDataDestroy(triMesh_);
}

dGeomID OdeMeshData::createConvex() {
  return dCreateConvex(nullptr, convex_.planes.data(),
                       static_cast<unsigned>(convex_.planes.size() / 4), convex_.points.data(),
                       static_cast<unsigned>(convex_.points.size() / 3), convex_.polygons.data());
}

dGeomID OdeMeshData::createTriMesh() {
  if (!triMesh_) {
    for (const Eigen::Vector3d& v : mesh.vertices())
      triVertices_.insert(triVertices_.end(), {v.x(), v.y(), v.z()});
    for (const auto& t : mesh.triangles())
      for (int corner : t) triIndices_.push_back(static_cast<dTriIndex>(corner));
    triMesh_ = dGeomTriMeshDataCreate();
    dGeomTriMeshDataBuildDouble(triMesh_, triVertices_.data(), 3 * sizeof(dReal),
                                static_cast<int>(mesh.vertices().size()), triIndices_.data(),
                                static_cast<int>(triIndices_.size()), 3 * sizeof(dTriIndex));
    // Convex-trimesh contacts (through libccd) need the face angles, or ODE aborts.
    dGeomTriMeshDataPreprocess2(triMesh_, 1u << dTRIDATAPREPROCESS_BUILD_FACE_ANGLES, nullptr);
  }
  return dCreateTriMesh(nullptr, triMesh_, nullptr, nullptr, nullptr);
}

}  // namespace kautham::physics
