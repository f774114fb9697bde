#include "LinkInertia.h"

#include <sstream>

#include "kautham/core/Geometry.h"
#include "kautham/core/Log.h"

namespace kautham::core {

namespace {

/// A principal moment under this fraction of the solid box's is too small to simulate steadily.
constexpr double kSmallestFraction = 0.01;

std::string triple(const Eigen::Vector3d& v) {
  std::ostringstream text;
  text << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return text.str();
}

/// Why the link's declared principal moments cannot be used, given the solid box's of its mass
/// and size; empty when they can.
std::string defect(const Eigen::Vector3d& given, const Eigen::Vector3d& solid,
                   const std::string& body) {
  for (int i = 0; i < 3; ++i)
    if (given[i] < kSmallestFraction * solid[i]) return "is far below that of " + body;
  // A solid box's moment is m (s_j^2 + s_k^2) / 12; no mass inside the box exceeds 12 times it.
  for (int i = 0; i < 3; ++i)
    if (given[i] > 12.0 * solid[i]) return "is more than " + body + " can have";
  return {};
}

}  // namespace

void repairLinkInertias(ModelInstance& instance) {
  for (Link& link : instance.model.links) {
    const double mass = link.inertial.mass;
    if (!(mass > 0.0) || link.collisions.empty()) continue;
    Eigen::AlignedBox3d box;
    for (const CollisionShape& c : link.collisions) box.extend(boundingBox(c.shape, c.origin));
    const Eigen::Vector3d s = box.sizes();
    const Eigen::Vector3d solid(mass / 12.0 * (s.y() * s.y() + s.z() * s.z()),
                                mass / 12.0 * (s.x() * s.x() + s.z() * s.z()),
                                mass / 12.0 * (s.x() * s.x() + s.y() * s.y()));
    const Eigen::Vector3d given = link.inertial.inertia.diagonal();
    std::ostringstream body;
    body << "a " << mass << " kg body of its size";
    const std::string why = defect(given, solid, body.str());
    if (why.empty()) continue;
    warnOnce(instance.urdf.string() + "\n" + link.name,
             instance.urdf.string() + ": link '" + link.name + "': its inertia " + triple(given) +
                 " " + why + ", which ODE cannot simulate steadily; using the solid box's " +
                 triple(solid));
    link.inertial.inertia = solid.asDiagonal();
    link.inertial.origin.linear().setIdentity();
  }
}

}  // namespace kautham::core
