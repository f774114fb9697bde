#include "kautham/core/ConvexHull.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numeric>

#include <Eigen/Eigenvalues>

#include <libqhull_r/qhull_ra.h>

namespace kautham::core {

namespace {

/// Qhull's state for one run; frees Qhull's memory on every way out.
class QhullRun {
 public:
  QhullRun() : errors_(open_memstream(&errorText_, &errorSize_)) { qh_zero(&qh_, errors_); }
  ~QhullRun() {
    int longs = 0, totalLong = 0;
    qh_freeqhull(&qh_, !qh_ALL);
    qh_memfreeshort(&qh_, &longs, &totalLong);
    if (errors_) std::fclose(errors_);
    std::free(errorText_);
  }
  QhullRun(const QhullRun&) = delete;
  QhullRun& operator=(const QhullRun&) = delete;

  /// Runs Qhull on the points; returns false with the first line of its message on failure.
  bool run(std::vector<double>& coordinates, std::string& message) {
    char command[] = "qhull";  // default options: coplanar facets merged (C-0 Qx)
    const int points = static_cast<int>(coordinates.size() / 3);
    const int code =
        qh_new_qhull(&qh_, 3, points, coordinates.data(), False, command, nullptr, errors_);
    if (code == 0) return true;
    if (errors_) std::fflush(errors_);
    message = errorText_ ? std::string(errorText_, errorSize_) : std::string();
    message = message.substr(0, message.find('\n'));
    return false;
  }

  qhT* qh() { return &qh_; }

 private:
  char* errorText_ = nullptr;
  std::size_t errorSize_ = 0;
  std::FILE* errors_;
  qhT qh_;
};

/// Sorts a face's corners counter-clockwise around its outward normal.
void orderAroundNormal(std::vector<int>& face, const std::vector<Eigen::Vector3d>& vertices,
                       const Eigen::Vector3d& normal) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int v : face) centre += vertices[v];
  centre /= static_cast<double>(face.size());
  const Eigen::Vector3d u = (vertices[face.front()] - centre).normalized();
  const Eigen::Vector3d w = normal.cross(u);  // (u, w, normal) is right-handed
  std::vector<double> angle(vertices.size());
  for (int v : face) {
    const Eigen::Vector3d d = vertices[v] - centre;
    angle[v] = std::atan2(d.dot(w), d.dot(u));
  }
  std::sort(face.begin(), face.end(), [&](int a, int b) { return angle[a] < angle[b]; });
}

}  // namespace

bool ConvexHull::contains(const Eigen::Vector3d& point, double tolerance) const {
  for (const Eigen::Vector4d& plane : planes)
    if (plane.head<3>().dot(point) > plane.w() + tolerance) return false;
  return true;
}

ConvexHull convexHull(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 4)
    throw DegenerateHullError("a convex hull needs at least 4 points, got " +
                              std::to_string(points.size()));
  // Flat or collinear points span no volume: say so plainly rather than with Qhull's words.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  double extent = 0.0;
  for (const Eigen::Vector3d& p : points) {
    scatter += (p - mean) * (p - mean).transpose();
    extent = std::max(extent, (p - mean).norm());
  }
  const Eigen::Vector3d spread =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter / points.size()).eigenvalues();
  if (!(extent > 0.0) || std::sqrt(std::max(spread.minCoeff(), 0.0)) < 1e-6 * extent)
    throw DegenerateHullError("the points are flat (they lie in one plane or on one line)");

  std::vector<double> coordinates;
  coordinates.reserve(3 * points.size());
  for (const Eigen::Vector3d& p : points)
    coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
  QhullRun run;
  std::string message;
  if (!run.run(coordinates, message))
    throw DegenerateHullError("Qhull could not build the hull: " + message);

  qhT* qh = run.qh();
  ConvexHull hull;
  std::map<int, int> hullIndex;  // Qhull's point id -> index into hull.vertices
  vertexT* vertex;
  FORALLvertices {
    const int id = qh_pointid(qh, vertex->point);
    hullIndex[id] = static_cast<int>(hull.vertices.size());
    hull.vertices.push_back(points[static_cast<std::size_t>(id)]);
  }
  facetT* facet;
  FORALLfacets {
    const Eigen::Vector3d normal(facet->normal[0], facet->normal[1], facet->normal[2]);
    std::vector<int> face;
    vertexT** vertexp;
    FOREACHvertex_(facet->vertices) face.push_back(hullIndex.at(qh_pointid(qh, vertex->point)));
    orderAroundNormal(face, hull.vertices, normal);
    hull.faces.push_back(std::move(face));
    // Qhull's hyperplane is normal.x + offset = 0 with the normal pointing outwards.
    hull.planes.emplace_back(normal.x(), normal.y(), normal.z(), -facet->offset);
  }
  return hull;
}

}  // namespace kautham::core
