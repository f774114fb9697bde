#pragma once
// ODE's box-cylinder collider finds no contact at all when the centre of one shape lies inside
// the other (a thin palm inside a can, a can inside a wall: physics.md, "Known limit of ODE").
// A probe of the start looks for that containment itself.

#include <vector>

#include <ode/ode.h>

namespace kautham::physics {

/// A box and a cylinder, the centre of `inner` inside `outer` by `depth` metres (the distance
/// from the centre to the nearest face of `outer`).
struct ContainedPair {
  dGeomID inner = nullptr;
  dGeomID outer = nullptr;
  double depth = 0.0;
};

/// Every box-cylinder pair of `space` and of the spaces inside it that ODE would collide (their
/// category and collide bits), at least one of them on a body, where the centre of one lies
/// deeper than `minDepth` inside the other.
std::vector<ContainedPair> containedCentres(dSpaceID space, double minDepth);

}  // namespace kautham::physics
