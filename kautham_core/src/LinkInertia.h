#pragma once

#include "kautham/core/Problem.h"

namespace kautham::core {

/// Replaces a URDF inertia that ODE cannot simulate as given by that of the solid box around
/// the link's collision shapes, with a warning naming the file and link. Kautham itself never
/// reads the URDF's inertia: its ODE environment computes every body's from its mesh and mass.
///  - Far below the solid box's (under 1 %): Kautham's walls (2 kg, 9 m long, the inertia of a
///    5 cm cube) spin or jitter.
///  - Above what any mass inside that box can have, whatever its distribution and centre of
///    mass: about x, m (s_y^2 + s_z^2) for sides s. Kautham's planar chain declares 1 kg m^2 for
///    0.1 kg links 0.2 m long (240 times that bound); a stopped link then hands its momentum to
///    its neighbours faster than their motors can absorb.
void repairLinkInertias(ModelInstance& instance);

}  // namespace kautham::core
