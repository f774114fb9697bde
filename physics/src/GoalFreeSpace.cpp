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
    : layout_(std::move(layout)),
      center_(center),
      halfSize_(0.5 * size),
      boundingRadius_(0.5 * size.norm()) {
  if (!(size.minCoeff() > 0.0) || !size.allFinite())
    throw std::invalid_argument("a goal's free space needs three positive box sides");
  // At least two points per axis (both faces), at most kSpacing apart.
  for (int a = 0; a < 3; ++a) {
    count_[a] = std::max(2, 1 + static_cast<int>(std::ceil(size[a] / kSpacing)));
    spacing_[a] = size[a] / (count_[a] - 1);
  }
  for (int i = 0; i < count_.x(); ++i)
    for (int j = 0; j < count_.y(); ++j)
      for (int k = 0; k < count_.z(); ++k) {
        const Eigen::Vector3d fraction(i / double(count_.x() - 1), j / double(count_.y() - 1),
                                       k / double(count_.z() - 1));
        grid_.push_back(center + (fraction.array() - 0.5).matrix().cwiseProduct(size));
      }
  for (std::size_t b = 0; b < layout_->bodies.size(); ++b) {
    if (layout_->bodies[b].role != BodyRole::Movable) continue;
    MovableBody movable{b, {}, {}, 0.0};
    for (std::size_t s = 0; s < layout_->shapes.size(); ++s) {
      const ShapeInfo& shape = layout_->shapes[s];
      if (shape.body != static_cast<int>(b)) continue;
      movable.shapes.push_back(s);
      movable.shapeRadii.push_back(boundingRadius(shape.shape));
      movable.reach =
          std::max(movable.reach, shape.pose.translation().norm() + movable.shapeRadii.back());
    }
    movable_.push_back(std::move(movable));
  }
}

std::vector<GoalFreeSpace::NearShape> GoalFreeSpace::nearShapes(
    const double* state, const Eigen::Isometry3d& goalLink) const {
  // Padded so that rounding never culls a point the shape's own test would find inside.
  constexpr double kBallPadding = 1e-6;  // m
  const Eigen::Vector3d boxCentre = goalLink * center_;
  const Eigen::Isometry3d toGoalLink = goalLink.inverse();
  std::vector<NearShape> near;
  for (std::size_t e = 0; e < movable_.size(); ++e) {
    const MovableBody& m = movable_[e];
    const Eigen::Vector3d position = WorldLayout::position(state, m.body);
    if ((position - boxCentre).norm() > m.reach + boundingRadius_) continue;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = WorldLayout::orientation(state, m.body).normalized().toRotationMatrix();
    pose.translation() = position;
    for (std::size_t i = 0; i < m.shapes.size(); ++i) {
      const Eigen::Isometry3d shapePose = pose * layout_->shapes[m.shapes[i]].pose;
      const Eigen::Vector3d ballCentre = toGoalLink * shapePose.translation();
      const double radius = m.shapeRadii[i] + kBallPadding;
      // How far the ball's centre lies outside the box (zero inside it). A shape at a pose
      // that is not a number holds no point (as the exact test says).
      const Eigen::Vector3d outside = ((ballCentre - center_).cwiseAbs() - halfSize_).cwiseMax(0.0);
      if (!ballCentre.allFinite() || outside.squaredNorm() > radius * radius) continue;
      near.push_back({&layout_->shapes[m.shapes[i]].shape, e, shapePose.inverse(), ballCentre,
                      radius * radius});
    }
  }
  return near;
}

template <typename Visit>
bool GoalFreeSpace::forPointsAround(const NearShape& shape, Visit&& visit) const {
  const double radius = std::sqrt(shape.ballRadiusSquared);
  Eigen::Vector3i first, last;
  for (int a = 0; a < 3; ++a) {
    const double low = shape.ballCentre[a] - radius - (center_[a] - halfSize_[a]);
    const double top = count_[a] - 1;
    first[a] = static_cast<int>(std::clamp(std::floor(low / spacing_[a]) - 1.0, 0.0, top));
    last[a] =
        static_cast<int>(std::clamp(std::ceil((low + 2.0 * radius) / spacing_[a]) + 1.0, 0.0, top));
  }
  for (int i = first.x(); i <= last.x(); ++i)
    for (int j = first.y(); j <= last.y(); ++j)
      for (int k = first.z(); k <= last.z(); ++k)
        if (!visit((static_cast<std::size_t>(i) * count_.y() + j) * count_.z() + k)) return false;
  return true;
}

std::vector<std::size_t> GoalFreeSpace::pointsInside(const double* state,
                                                     const Eigen::Isometry3d& goalLink,
                                                     std::size_t& anyInside) const {
  // Shape by shape, over the grid points near each: most of the box is near no object.
  const std::vector<NearShape> near = nearShapes(state, goalLink);
  std::vector<std::size_t> counts(movable_.size(), 0);
  anyInside = 0;
  if (near.empty()) return counts;
  std::vector<std::size_t> countedFor(grid_.size(), movable_.size());  // the entry, or none
  std::vector<char> inSome(grid_.size(), 0);
  for (const NearShape& n : near)
    forPointsAround(n, [&](std::size_t index) {
      const Eigen::Vector3d& p = grid_[index];
      // A point counts once per body, however many of its shapes hold it.
      if (countedFor[index] == n.entry || !n.mayHold(p) ||
          !inside(*n.shape, n.toShape * (goalLink * p)))
        return true;
      countedFor[index] = n.entry;
      ++counts[n.entry];
      if (!inSome[index]) {
        inSome[index] = 1;
        ++anyInside;
      }
      return true;
    });
  return counts;
}

std::vector<std::string> GoalFreeSpace::occupants(const double* state,
                                                  const Eigen::Isometry3d& goalLink) const {
  std::size_t anyInside = 0;
  const std::vector<std::size_t> counts = pointsInside(state, goalLink, anyInside);
  std::vector<std::string> names;
  for (std::size_t e = 0; e < movable_.size(); ++e)
    if (counts[e] > 0) names.push_back(layout_->bodies[movable_[e].body].name);
  return names;
}

bool GoalFreeSpace::isFree(const double* state, const Eigen::Isometry3d& goalLink) const {
  // Stops at the first point inside an object: the planners ask this of many poses.
  for (const NearShape& n : nearShapes(state, goalLink)) {
    const bool clear = forPointsAround(n, [&](std::size_t index) {
      const Eigen::Vector3d& p = grid_[index];
      return !n.mayHold(p) || !inside(*n.shape, n.toShape * (goalLink * p));
    });
    if (!clear) return false;
  }
  return true;
}

GoalFreeSpace::Occupancy GoalFreeSpace::occupancy(const double* state,
                                                  const Eigen::Isometry3d& goalLink) const {
  std::size_t anyInside = 0;
  const std::vector<std::size_t> counts = pointsInside(state, goalLink, anyInside);
  Occupancy result;
  result.fraction = static_cast<double>(anyInside) / static_cast<double>(grid_.size());
  const auto most = std::max_element(counts.begin(), counts.end());
  if (most != counts.end() && *most > 0)
    result.largest = movable_[static_cast<std::size_t>(most - counts.begin())].body;
  return result;
}

}  // namespace kautham::physics
