#pragma once

// Private to the physics library: what each ODE geometry belongs to, for contact handling.

#include <string>

#include "kautham/physics/World.h"

namespace kautham::physics {

/// Collision categories: which kinds of geometry ODE even tests against each other.
enum CollisionCategory : unsigned long {
  kCategoryFixed = 1u << 0,      ///< fixed obstacles: static
  kCategoryObject = 1u << 1,     ///< movable objects and the target: dynamic
  kCategoryRobot = 1u << 2,      ///< robot links that move
  kCategoryRobotBase = 1u << 3,  ///< robot links fixed to the world: static
};

struct GeomTag {
  enum class Kind { RobotLink, RobotBase, Fixed, Movable, Target } kind;
  std::string name;  ///< the object's name, or robot/link
  int body = -1;     ///< index into WorldLayout::bodies; -1 for static geometry

  bool isRobot() const { return kind == Kind::RobotLink || kind == Kind::RobotBase; }
  unsigned long category() const;
  unsigned long collidesWith() const;
};

/// The ContactEvent that a contact between two geometries means for validity.
unsigned contactEvent(const GeomTag& a, const GeomTag& b);

}  // namespace kautham::physics
