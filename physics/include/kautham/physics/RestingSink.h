#pragma once

#include <string>
#include <vector>

#include "kautham/physics/World.h"

namespace kautham::physics {

/// Whether the world's contacts are soft enough for objects to sink measurably into what carries
/// them: a kilogram on one contact point sinks more than a millimetre (Kautham's CFM 0.3 does,
/// by centimetres; this project's default CFM 1e-5 by micrometres).
bool hasSoftContacts(const World& world);

/// The start left to rest: the world stepped for one simulated second with the robot held still
/// and every object awake, then put back in `start` exactly (nothing of the settling leaks into
/// planning); the settled state. restingSink() and restlessObjects() read it.
std::vector<double> settledStart(World& world, const std::vector<double>& start);

/// How deep each body sinks into what carries it between `start` and `settled` (settledStart()).
/// Per body, in metres: the sink of an object that stays in place (moves less than 1 cm sideways,
/// tilts less than 0.1 rad), 0 for the robot and for objects that slide or tip (they are not
/// resting). The validity checker does not count this sink as a drop.
std::vector<double> restingSink(const WorldLayout& layout, const std::vector<double>& start,
                                const std::vector<double>& settled);

/// An object that does not rest where the start puts it.
struct RestlessObject {
  std::string name;
  double moved = 0.0;   ///< metres, in the settling second
  double tilted = 0.0;  ///< radians
};

/// The objects that do not rest at the start: between `start` and `settled` (settledStart())
/// they move more than 2 cm (sideways only, with `softContacts`, where resting objects sink) or
/// tilt more than 0.2 rad: they float, fall, slide or tip. Objects start asleep (physics.md,
/// "Sleeping objects"), so such an object would stay where it is, in the air, until something
/// touched it.
std::vector<RestlessObject> restlessObjects(const WorldLayout& layout,
                                            const std::vector<double>& start,
                                            const std::vector<double>& settled, bool softContacts);

}  // namespace kautham::physics
