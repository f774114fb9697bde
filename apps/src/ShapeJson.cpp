#include "ShapeJson.h"

#include <cmath>

namespace kautham::apps {

using nlohmann::json;

json meshJson(const core::TriangleMesh& mesh, const std::string& file) {
  std::vector<double> vertices;
  vertices.reserve(3 * mesh.vertices.size());
  for (const Eigen::Vector3d& v : mesh.vertices)
    for (int k = 0; k < 3; ++k) vertices.push_back(std::round(v[k] * 1e4) / 1e4);
  std::vector<int> triangles;
  triangles.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) triangles.insert(triangles.end(), t.begin(), t.end());
  return {{"type", "mesh"}, {"file", file}, {"vertices", vertices}, {"triangles", triangles}};
}

json shapeJson(const core::Shape& shape) {
  struct Describe {
    json operator()(const core::Box& b) const {
      return {{"type", "box"}, {"size", {b.size.x(), b.size.y(), b.size.z()}}};
    }
    json operator()(const core::Cylinder& c) const {
      return {{"type", "cylinder"}, {"radius", c.radius}, {"length", c.length}};
    }
    json operator()(const core::Sphere& s) const {
      return {{"type", "sphere"}, {"radius", s.radius}};
    }
    json operator()(const core::Mesh& m) const {
      return meshJson({m.vertices(), m.triangles()}, m.data->source.filename().string());
    }
  };
  return std::visit(Describe{}, shape);
}

json poseJson(const Eigen::Isometry3d& pose) {
  const Eigen::Quaterniond q(pose.linear());
  const Eigen::Vector3d p = pose.translation();
  return {p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z()};
}

}  // namespace kautham::apps
