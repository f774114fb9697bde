#include "kautham/planners/pkpiece/RobotSpread.h"

#include <algorithm>

namespace kautham::planners {

RobotSpread::Part::Part(const physics::WorldLayout& layout) {
  for (std::size_t b = 0; b < layout.bodies.size(); ++b) {
    if (layout.bodies[b].role != physics::BodyRole::Robot) continue;
    for (std::size_t k = 0; k < physics::WorldLayout::kBodyStateSize; ++k)
      indices_.push_back(b * physics::WorldLayout::kBodyStateSize + k);
  }
  for (std::size_t j = 0; j < layout.joints.size(); ++j) {
    indices_.push_back(layout.jointPositionIndex() + j);
    indices_.push_back(layout.jointVelocityIndex() + j);
  }
}

RobotSpread::RobotSpread(std::shared_ptr<const Part> part, std::size_t samples,
                         std::vector<std::size_t> objects)
    : part_(std::move(part)), samples_(samples), objects_(std::move(objects)) {
  values_.resize(samples_ * rowSize());
}

std::size_t RobotSpread::rowSize() const {
  return part_->indices().size() + objects_.size() * physics::WorldLayout::kBodyStateSize;
}

std::shared_ptr<const RobotSpread> RobotSpread::fromStates(
    std::shared_ptr<const Part> part, const std::vector<const std::vector<double>*>& states,
    std::vector<std::size_t> objects) {
  if (states.empty()) return nullptr;
  std::sort(objects.begin(), objects.end());
  objects.erase(std::unique(objects.begin(), objects.end()), objects.end());
  std::shared_ptr<RobotSpread> spread(
      new RobotSpread(std::move(part), states.size(), std::move(objects)));
  const std::vector<std::size_t>& indices = spread->part_->indices();
  double* out = spread->values_.data();
  for (const std::vector<double>* state : states) {
    for (std::size_t index : indices) *out++ = (*state)[index];
    for (std::size_t b : spread->objects_) {
      const double* body = state->data() + b * physics::WorldLayout::kBodyStateSize;
      out = std::copy(body, body + physics::WorldLayout::kBodyStateSize, out);
    }
  }
  return spread;
}

const double* RobotSpread::sample(std::size_t i) const {
  return values_.data() + (i % samples_) * rowSize();
}

void RobotSpread::apply(std::size_t i, double* state) const {
  const double* in = sample(i);
  for (std::size_t index : part_->indices()) state[index] = *in++;
  for (std::size_t b : objects_) {
    std::copy(in, in + physics::WorldLayout::kBodyStateSize,
              state + b * physics::WorldLayout::kBodyStateSize);
    in += physics::WorldLayout::kBodyStateSize;
  }
}

}  // namespace kautham::planners
