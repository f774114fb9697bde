#include "kautham/physics/WorldLayout.h"

#include <algorithm>

namespace kautham::physics {

const char* toString(BodyRole role) {
  switch (role) {
    case BodyRole::Robot:
      return "robot";
    case BodyRole::Movable:
      return "movable";
    case BodyRole::Target:
      return "target";
  }
  return "?";
}

Eigen::Vector3d WorldLayout::position(const double* state, std::size_t body) {
  const double* p = state + body * kBodyStateSize + kPosition;
  return {p[0], p[1], p[2]};
}

Eigen::Quaterniond WorldLayout::orientation(const double* state, std::size_t body) {
  const double* q = state + body * kBodyStateSize + kOrientation;
  return {q[0], q[1], q[2], q[3]};
}

Eigen::Vector3d WorldLayout::linearVelocity(const double* state, std::size_t body) {
  const double* v = state + body * kBodyStateSize + kLinearVelocity;
  return {v[0], v[1], v[2]};
}

Eigen::Vector3d WorldLayout::angularVelocity(const double* state, std::size_t body) {
  const double* w = state + body * kBodyStateSize + kAngularVelocity;
  return {w[0], w[1], w[2]};
}

unsigned WorldLayout::flags(const double* state) const {
  return static_cast<unsigned>(state[flagsIndex()]);
}

Eigen::Isometry3d WorldLayout::linkPose(const double* state, std::size_t body) const {
  Eigen::Isometry3d bodyPose = Eigen::Isometry3d::Identity();
  bodyPose.linear() = orientation(state, body).normalized().toRotationMatrix();
  bodyPose.translation() = position(state, body);
  return bodyPose * bodies[body].linkInBody;
}

Eigen::AlignedBox3d WorldLayout::bounds(std::size_t body, const double* state) const {
  const Eigen::Isometry3d pose = state ? linkPose(state, body) * bodies[body].linkInBody.inverse()
                                       : Eigen::Isometry3d::Identity();
  Eigen::AlignedBox3d box;
  for (const ShapeInfo& shape : shapes)
    if (shape.body == static_cast<int>(body))
      box.extend(core::boundingBox(shape.shape, pose * shape.pose));
  return box;
}

void WorldLayout::placeBody(double* state, std::size_t body, const Eigen::Isometry3d& link) const {
  const Eigen::Isometry3d pose = link * bodies[body].linkInBody.inverse();
  double* s = state + body * kBodyStateSize;
  const Eigen::Quaterniond turn(pose.linear());
  const Eigen::Vector3d& p = pose.translation();
  const double values[7] = {p.x(), p.y(), p.z(), turn.w(), turn.x(), turn.y(), turn.z()};
  std::copy(values, values + 7, s + kPosition);
  std::fill(s + kLinearVelocity, s + kBodyStateSize, 0.0);
}

Eigen::Vector3d WorldLayout::goalLinkPosition(const double* state) const {
  const std::size_t body = static_cast<std::size_t>(goalBody);
  const Eigen::Vector3d offset = goalLinkInBody.translation();
  return position(state, body) + orientation(state, body).normalized() * offset;
}

Eigen::Matrix3d WorldLayout::goalLinkOrientation(const double* state) const {
  const std::size_t body = static_cast<std::size_t>(goalBody);
  return orientation(state, body).normalized().toRotationMatrix() * goalLinkInBody.linear();
}

}  // namespace kautham::physics
