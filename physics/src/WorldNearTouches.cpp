// World::robotTouchesNear and robotTouchesShifted: a geometric planner's clearance test (the
// robot shifted along each axis, see SceneChecker::setClearance) without ODE's space-wide
// bounding-box update per shift.

#include <algorithm>

#include "GeomTag.h"
#include "kautham/physics/World.h"

namespace kautham::physics {

namespace {

/// Every geometry of `space` that is not itself a space, depth first.
void leafGeoms(dSpaceID space, std::vector<dGeomID>& out) {
  const int count = dSpaceGetNumGeoms(space);
  for (int i = 0; i < count; ++i) {
    dGeomID geom = dSpaceGetGeom(space, i);
    if (dGeomIsSpace(geom))
      leafGeoms(reinterpret_cast<dSpaceID>(geom), out);
    else
      out.push_back(geom);
  }
}

/// Whether the bounding boxes of `a` and `b` are at most `margin` apart along every axis.
bool boxesWithin(dGeomID a, dGeomID b, double margin) {
  dReal boxA[6];
  dReal boxB[6];
  dGeomGetAABB(a, boxA);
  dGeomGetAABB(b, boxB);
  for (int axis = 0; axis < 3; ++axis)
    if (boxA[2 * axis] - boxB[2 * axis + 1] > margin ||
        boxB[2 * axis] - boxA[2 * axis + 1] > margin)
      return false;
  return true;
}

}  // namespace

RobotTouches World::robotTouchesNear(int heldBody, double margin) {
  // The space-wide test brings every bounding box up to date for the current poses.
  RobotTouches touches = robotTouches(heldBody);
  nearPairs_.clear();
  nearBodies_.clear();
  nearHeldBody_ = heldBody;
  nearTriangles_ = false;
  std::vector<dGeomID> geoms;
  leafGeoms(space_, geoms);
  const auto moving = [heldBody](const GeomTag& tag) {
    return tag.kind == GeomTag::Kind::RobotLink || (heldBody >= 0 && tag.body == heldBody);
  };
  for (dGeomID a : geoms) {
    const GeomTag& tagA = *static_cast<const GeomTag*>(dGeomGetData(a));
    if (!moving(tagA) || !dGeomIsEnabled(a)) continue;
    dBodyID body = dGeomGetBody(a);
    if (body && std::none_of(nearBodies_.begin(), nearBodies_.end(),
                             [body](const auto& known) { return known.first == body; })) {
      const dReal* p = dBodyGetPosition(body);
      nearBodies_.emplace_back(body, Eigen::Vector3d(p[0], p[1], p[2]));
    }
    for (dGeomID b : geoms) {
      const GeomTag& tagB = *static_cast<const GeomTag*>(dGeomGetData(b));
      // The pairs recordTouch() would test: ODE's own filters (categories, one body), then
      // the robot against what moves with neither it nor what it holds.
      if (moving(tagB) || (tagA.isRobot() && tagB.isRobot()) || !dGeomIsEnabled(b)) continue;
      if (body && dGeomGetBody(b) == body) continue;
      if (!(dGeomGetCategoryBits(a) & dGeomGetCollideBits(b)) &&
          !(dGeomGetCategoryBits(b) & dGeomGetCollideBits(a)))
        continue;
      if (!boxesWithin(a, b, margin)) continue;
      nearPairs_.emplace_back(a, b);
      const int kind = dGeomGetClass(b);
      nearTriangles_ |= kind == dTriMeshClass || kind == dHeightfieldClass;
    }
  }
  return touches;
}

RobotTouches World::robotTouchesShifted(const Eigen::Vector3d& offset) {
  for (const auto& [body, from] : nearBodies_) {
    const Eigen::Vector3d to = from + offset;
    dBodySetPosition(body, to.x(), to.y(), to.z());
  }
  // ODE's colliders against triangle meshes pick the triangles by the other geometry's bounding
  // box: those must be where the bodies now are (a cube shifted into the S-passage's mesh walls
  // was found touching nothing).
  if (nearTriangles_) dSpaceClean(space_);
  RobotTouches touches;
  touches_ = &touches;
  heldBody_ = nearHeldBody_;
  for (const auto& [a, b] : nearPairs_) recordTouch(a, b);
  touches_ = nullptr;
  shiftedAside_ = true;
  std::sort(touches.bodies.begin(), touches.bodies.end());
  touches.bodies.erase(std::unique(touches.bodies.begin(), touches.bodies.end()),
                       touches.bodies.end());
  return touches;
}

}  // namespace kautham::physics
