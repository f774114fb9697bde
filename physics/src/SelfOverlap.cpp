#include "kautham/physics/SelfOverlap.h"

#include <map>
#include <memory>
#include <set>

#include <ode/ode.h>

#include "OdeMeshData.h"
#include "kautham/physics/OdeLibrary.h"

namespace kautham::physics {

namespace {

/// The robot's collision shapes as free ODE geometries (in no space) at their world poses.
class LinkGeoms {
 public:
  struct Geom {
    dGeomID id;
    int link;
  };

  LinkGeoms(const core::KinematicModel& model, const std::vector<Eigen::Isometry3d>& poses) {
    for (std::size_t l = 0; l < model.links.size(); ++l)
      for (const core::CollisionShape& c : model.links[l].collisions)
        add(c.shape, poses[l] * c.origin, static_cast<int>(l));
  }
  ~LinkGeoms() {
    for (const Geom& g : geoms_) dGeomDestroy(g.id);
  }
  LinkGeoms(const LinkGeoms&) = delete;
  LinkGeoms& operator=(const LinkGeoms&) = delete;

  const std::vector<Geom>& geoms() const { return geoms_; }

 private:
  void add(const core::Shape& shape, const Eigen::Isometry3d& pose, int link) {
    dGeomID id = create(shape);
    const Eigen::Vector3d p = pose.translation();
    const Eigen::Quaterniond q(pose.linear());
    const dQuaternion quaternion = {q.w(), q.x(), q.y(), q.z()};
    dGeomSetPosition(id, p.x(), p.y(), p.z());
    dGeomSetQuaternion(id, quaternion);
    geoms_.push_back({id, link});
  }

  /// Meshes as their triangles: the warning is about the real robot, and a hull (what the
  /// physics gives a moving link) fills a concave link and would overlap its neighbours falsely.
  dGeomID create(const core::Shape& shape) {
    if (const auto* b = std::get_if<core::Box>(&shape))
      return dCreateBox(nullptr, b->size.x(), b->size.y(), b->size.z());
    if (const auto* c = std::get_if<core::Cylinder>(&shape))
      return dCreateCylinder(nullptr, c->radius, c->length);
    if (const auto* s = std::get_if<core::Sphere>(&shape)) return dCreateSphere(nullptr, s->radius);
    meshes_.push_back(std::make_unique<OdeMeshData>(std::get<core::Mesh>(shape)));
    return meshes_.back()->createTriMesh();
  }

  std::vector<std::unique_ptr<OdeMeshData>> meshes_;  // declared first: outlives the geoms
  std::vector<Geom> geoms_;
};

/// Pairs of rigid groups (by top link) joined by a movable joint, smaller index first.
std::set<std::pair<int, int>> jointedGroups(const core::KinematicModel& model) {
  std::set<std::pair<int, int>> pairs;
  for (const core::Joint& joint : model.joints) {
    if (!joint.isMovable()) continue;
    const int a = model.rigidGroupTop(joint.parentLink), b = model.rigidGroupTop(joint.childLink);
    pairs.insert({std::min(a, b), std::max(a, b)});
  }
  return pairs;
}

double deepestContact(dGeomID a, dGeomID b) {
  constexpr int kMaxContacts = 8;
  dContactGeom contacts[kMaxContacts];
  const int n = dCollide(a, b, kMaxContacts, contacts, sizeof(dContactGeom));
  double depth = 0.0;
  for (int i = 0; i < n; ++i) depth = std::max(depth, static_cast<double>(contacts[i].depth));
  return depth;
}

}  // namespace

std::vector<LinkOverlap> robotSelfOverlaps(const core::RobotInstance& robot,
                                           const std::vector<double>& jointValues,
                                           double minDepth) {
  const std::shared_ptr<OdeLibrary> ode = OdeLibrary::acquire();
  const core::KinematicModel& model = robot.model;
  const std::set<std::pair<int, int>> jointed = jointedGroups(model);
  std::map<std::pair<int, int>, double> deepest;  // by link pair, in link order
  {
    const LinkGeoms geoms(model, model.linkPoses(robot.home.isometry(), jointValues));
    const auto& all = geoms.geoms();
    for (std::size_t i = 0; i < all.size(); ++i)
      for (std::size_t j = i + 1; j < all.size(); ++j) {
        const int a = std::min(all[i].link, all[j].link), b = std::max(all[i].link, all[j].link);
        const int ga = model.rigidGroupTop(a), gb = model.rigidGroupTop(b);
        if (ga == gb || jointed.count({std::min(ga, gb), std::max(ga, gb)})) continue;
        const double depth = deepestContact(all[i].id, all[j].id);
        if (depth > minDepth) deepest[{a, b}] = std::max(deepest[{a, b}], depth);
      }
  }
  std::vector<LinkOverlap> overlaps;
  for (const auto& [pair, depth] : deepest)
    overlaps.push_back({model.links[pair.first].name, model.links[pair.second].name, depth});
  return overlaps;
}

}  // namespace kautham::physics
