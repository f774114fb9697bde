#include "ContainedCentres.h"

#include <algorithm>
#include <cmath>

namespace kautham::physics {

namespace {

/// The geometries of `space` and of the spaces inside it (a fixed object of many shapes has a
/// space of its own: WorldBuilder).
void collectGeoms(dSpaceID space, std::vector<dGeomID>& geoms) {
  for (int i = 0; i < dSpaceGetNumGeoms(space); ++i) {
    const dGeomID g = dSpaceGetGeom(space, i);
    if (dGeomIsSpace(g))
      collectGeoms(reinterpret_cast<dSpaceID>(g), geoms);
    else
      geoms.push_back(g);
  }
}

bool isBoxOrCylinder(dGeomID g) {
  const int c = dGeomGetClass(g);
  return c == dBoxClass || c == dCylinderClass;
}

/// How deep `point` (world) lies inside the box or cylinder `g`: the distance to its nearest
/// face, negative outside.
double depthInside(dGeomID g, const dReal* point) {
  if (dGeomGetClass(g) == dBoxClass) return dGeomBoxPointDepth(g, point[0], point[1], point[2]);
  dReal radius = 0.0;
  dReal length = 0.0;
  dGeomCylinderGetParams(g, &radius, &length);
  const dReal* centre = dGeomGetPosition(g);
  const dReal* r = dGeomGetRotation(g);  // 3x4, row major: the axis (local z) is column 2
  const double d[3] = {point[0] - centre[0], point[1] - centre[1], point[2] - centre[2]};
  const double axial = d[0] * r[2] + d[1] * r[6] + d[2] * r[10];
  const double radial =
      std::sqrt(std::max(0.0, d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - axial * axial));
  return std::min(0.5 * length - std::abs(axial), radius - radial);
}

bool mayCollide(dGeomID a, dGeomID b) {
  if (!dGeomGetBody(a) && !dGeomGetBody(b)) return false;  // static against static
  return (dGeomGetCategoryBits(a) & dGeomGetCollideBits(b)) ||
         (dGeomGetCategoryBits(b) & dGeomGetCollideBits(a));
}

}  // namespace

std::vector<ContainedPair> containedCentres(dSpaceID space, double minDepth) {
  std::vector<dGeomID> geoms;
  collectGeoms(space, geoms);
  geoms.erase(
      std::remove_if(geoms.begin(), geoms.end(), [](dGeomID g) { return !isBoxOrCylinder(g); }),
      geoms.end());
  std::vector<ContainedPair> pairs;
  for (std::size_t i = 0; i < geoms.size(); ++i)
    for (std::size_t j = i + 1; j < geoms.size(); ++j) {
      const dGeomID a = geoms[i];
      const dGeomID b = geoms[j];
      if (dGeomGetClass(a) == dGeomGetClass(b) || !mayCollide(a, b)) continue;
      const double aInB = depthInside(b, dGeomGetPosition(a));
      const double bInA = depthInside(a, dGeomGetPosition(b));
      if (aInB > minDepth)
        pairs.push_back({a, b, aInB});
      else if (bInA > minDepth)
        pairs.push_back({b, a, bInA});
    }
  return pairs;
}

}  // namespace kautham::physics
