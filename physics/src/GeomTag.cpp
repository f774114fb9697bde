#include "GeomTag.h"

namespace kautham::physics {

unsigned long GeomTag::category() const {
  switch (kind) {
    case Kind::RobotLink:
      return kCategoryRobot;
    case Kind::RobotBase:
      return kCategoryRobotBase;
    case Kind::Fixed:
      return kCategoryFixed;
    default:
      return kCategoryObject;
  }
}

unsigned long GeomTag::collidesWith() const {
  switch (kind) {
    // Static geometry never needs testing against static geometry, and the robot's base
    // stands on the table by design.
    case Kind::RobotBase:
      return kCategoryObject;
    case Kind::Fixed:
      return kCategoryObject | kCategoryRobot;
    case Kind::RobotLink:
      return kCategoryFixed | kCategoryObject;
    default:
      return kCategoryFixed | kCategoryObject | kCategoryRobot | kCategoryRobotBase;
  }
}

unsigned contactEvent(const GeomTag& a, const GeomTag& b) {
  using Kind = GeomTag::Kind;
  const GeomTag& other = a.isRobot() ? b : a;
  if (!a.isRobot() && !b.isRobot()) return kNoEvent;
  if (other.kind == Kind::Fixed) return kRobotTouchedFixed;
  if (other.kind == Kind::Target) return kRobotTouchedTarget;
  return kNoEvent;
}

}  // namespace kautham::physics
