#include "kautham/physics/GoalFreeSpace.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <type_traits>

namespace kautham::physics {

namespace {

/// Whether a point given in a shape's own frame lies inside it.
bool inside(const core::Shape& shape, const Eigen::Vector3d& p) {
  return std::visit(
      [&p](const auto& s) {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, core::Box>) {
          return (p.cwiseAbs() - 0.5 * s.size).maxCoeff() <= 0.0;
        } else if constexpr (std::is_same_v<S, core::Cylinder>) {
          return p.head<2>().squaredNorm() <= s.radius * s.radius &&
                 std::abs(p.z()) <= 0.5 * s.length;
        } else if constexpr (std::is_same_v<S, core::Sphere>) {
          return p.squaredNorm() <= s.radius * s.radius;
        } else {
          return s.hull().contains(p);  // moving meshes collide as their hull
        }
      },
      shape);
}

/// Radius of a ball about a shape's origin that holds the whole shape: the distance to the
/// farthest corner of its bounding box.
double boundingRadius(const core::Shape& shape) {
  const Eigen::AlignedBox3d box = core::boundingBox(shape, Eigen::Isometry3d::Identity());
  return box.min().cwiseAbs().cwiseMax(box.max().cwiseAbs()).norm();
}

}  // namespace

GoalFreeSpace::GoalFreeSpace(std::shared_ptr<const WorldLayout> layout, const Eigen::Vector3d& size,
                             const Eigen::Vector3d& center)
    : layout_(std::move(layout)), center_(center), boundingRadius_(0.5 * size.norm()) {
  if (!(size.minCoeff() > 0.0) || !size.allFinite())
    throw std::invalid_argument("a goal's free space needs three positive box sides");
  Eigen::Vector3i count;
  // At least two points per axis (both faces), at most kSpacing apart.
  for (int a = 0; a < 3; ++a)
    count[a] = std::max(2, 1 + static_cast<int>(std::ceil(size[a] / kSpacing)));
  for (int i = 0; i < count.x(); ++i)
    for (int j = 0; j < count.y(); ++j)
      for (int k = 0; k < count.z(); ++k) {
        const Eigen::Vector3d fraction(i / double(count.x() - 1), j / double(count.y() - 1),
                                       k / double(count.z() - 1));
        grid_.push_back(center + (fraction.array() - 0.5).matrix().cwiseProduct(size));
      }
  for (std::size_t b = 0; b < layout_->bodies.size(); ++b)
    if (layout_->bodies[b].role == BodyRole::Movable) movable_.push_back(b);
  for (const ShapeInfo& shape : layout_->shapes)
    shapeRadius_.push_back(boundingRadius(shape.shape));
}

std::vector<std::string> GoalFreeSpace::occupants(const double* state,
                                                  const Eigen::Isometry3d& goalLink) const {
  std::vector<Eigen::Vector3d> worldPoints;
  worldPoints.reserve(grid_.size());
  for (const Eigen::Vector3d& p : grid_) worldPoints.push_back(goalLink * p);
  std::vector<std::string> names;
  for (std::size_t body : movable_)
    if (occupies(body, state, worldPoints, goalLink * center_))
      names.push_back(layout_->bodies[body].name);
  return names;
}

bool GoalFreeSpace::isFree(const double* state, const Eigen::Isometry3d& goalLink) const {
  return occupants(state, goalLink).empty();
}

GoalFreeSpace::Occupancy GoalFreeSpace::occupancy(const double* state,
                                                  const Eigen::Isometry3d& goalLink) const {
  const Eigen::Vector3d boxCentre = goalLink * center_;
  // The shapes near the box, each with its body and the map from world to its own frame.
  struct NearShape {
    const core::Shape* shape;
    std::size_t body;
    Eigen::Isometry3d toShape;
  };
  std::vector<NearShape> near;
  for (std::size_t body : movable_) {
    const std::optional<Eigen::Isometry3d> pose = poseIfNear(body, state, boxCentre);
    if (!pose) continue;
    for (std::size_t s = 0; s < layout_->shapes.size(); ++s)
      if (layout_->shapes[s].body == static_cast<int>(body))
        near.push_back(
            {&layout_->shapes[s].shape, body, (*pose * layout_->shapes[s].pose).inverse()});
  }
  Occupancy result;
  if (near.empty()) return result;
  std::vector<std::size_t> pointsOf(layout_->bodies.size(), 0);
  std::size_t occupied = 0;
  for (const Eigen::Vector3d& p : grid_) {
    const Eigen::Vector3d world = goalLink * p;
    for (const NearShape& n : near)
      if (inside(*n.shape, n.toShape * world)) {
        ++occupied;
        ++pointsOf[n.body];
        break;
      }
  }
  result.fraction = static_cast<double>(occupied) / static_cast<double>(grid_.size());
  const auto most = std::max_element(pointsOf.begin(), pointsOf.end());
  if (*most > 0) result.largest = static_cast<std::size_t>(most - pointsOf.begin());
  return result;
}

std::optional<Eigen::Isometry3d> GoalFreeSpace::poseIfNear(std::size_t body, const double* state,
                                                           const Eigen::Vector3d& boxCentre) const {
  const Eigen::Vector3d position = WorldLayout::position(state, body);
  double reach = 0.0;
  for (std::size_t s = 0; s < layout_->shapes.size(); ++s)
    if (layout_->shapes[s].body == static_cast<int>(body))
      reach = std::max(reach, layout_->shapes[s].pose.translation().norm() + shapeRadius_[s]);
  if ((position - boxCentre).norm() > reach + boundingRadius_) return std::nullopt;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = WorldLayout::orientation(state, body).normalized().toRotationMatrix();
  pose.translation() = position;
  return pose;
}

bool GoalFreeSpace::occupies(std::size_t body, const double* state,
                             const std::vector<Eigen::Vector3d>& worldPoints,
                             const Eigen::Vector3d& boxCentre) const {
  Eigen::Isometry3d bodyPose = Eigen::Isometry3d::Identity();
  bodyPose.linear() = WorldLayout::orientation(state, body).normalized().toRotationMatrix();
  bodyPose.translation() = WorldLayout::position(state, body);
  for (std::size_t s = 0; s < layout_->shapes.size(); ++s) {
    const ShapeInfo& shape = layout_->shapes[s];
    if (shape.body != static_cast<int>(body)) continue;
    const Eigen::Isometry3d toShape = (bodyPose * shape.pose).inverse();
    // Far shapes are skipped whole: most objects are nowhere near the gripper.
    const double reach = shapeRadius_[s] + boundingRadius_;
    if ((toShape * boxCentre).norm() > reach) continue;
    for (const Eigen::Vector3d& p : worldPoints)
      if (inside(shape.shape, toShape * p)) return true;
  }
  return false;
}

}  // namespace kautham::physics
