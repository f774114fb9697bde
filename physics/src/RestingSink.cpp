#include "kautham/physics/RestingSink.h"

#include "kautham/core/Pose.h"
#include "kautham/core/SoftContact.h"

namespace kautham::physics {

namespace {

constexpr double kSettleTime = 1.0;     // s: soft contacts settle within a few tenths
constexpr double kMaxSideways = 0.01;   // m
constexpr double kMaxTiltChange = 0.1;  // rad
constexpr double kTinySpeed = -1e-9;    // m/s: wakes an object (World::writeState) unnoticed
// An object that moves or tilts more than this when the start is left to rest does not rest.
constexpr double kRestlessMove = 0.02;  // m
constexpr double kRestlessTilt = 0.2;   // rad

double tiltChange(const std::vector<double>& start, const std::vector<double>& settled,
                  std::size_t body) {
  return std::abs(core::tiltAngle(WorldLayout::orientation(settled.data(), body)) -
                  core::tiltAngle(WorldLayout::orientation(start.data(), body)));
}

}  // namespace

std::vector<double> settledStart(World& world, const std::vector<double>& start) {
  const WorldLayout& layout = world.layout();
  std::vector<double> awake = start;
  for (std::size_t b = 0; b < layout.bodies.size(); ++b)
    if (layout.bodies[b].role != BodyRole::Robot)
      awake[b * WorldLayout::kBodyStateSize + WorldLayout::kLinearVelocity + 2] = kTinySpeed;
  world.writeState(awake.data());
  const std::vector<double> still(world.actuators().size(), 0.0);
  world.setJointVelocities(still.data());
  world.resetSolverSeed();
  const int steps = static_cast<int>(kSettleTime / world.settings().stepSize + 0.5);
  for (int i = 0; i < steps; ++i) world.step();
  std::vector<double> settled(start.size());
  world.readState(settled.data());
  world.writeState(start.data());  // as it was: nothing of the settling may leak into planning
  world.takeEvents();
  world.takeTouchedBodies();
  return settled;
}

bool hasSoftContacts(const World& world) {
  const ContactParameters& c = world.contactParameters();
  if (!(c.cfm > 0.0)) return false;
  const double spring = core::contactSpring({c.erp, c.cfm}, world.settings().stepSize);
  constexpr double kGravity = 9.81;  // N on one kilogram
  constexpr double kMeasurable = 0.001;
  return kGravity / spring > kMeasurable;
}

std::vector<double> restingSink(const WorldLayout& layout, const std::vector<double>& start,
                                const std::vector<double>& settled) {
  std::vector<double> sink(layout.bodies.size(), 0.0);
  for (std::size_t b = 0; b < layout.bodies.size(); ++b) {
    if (layout.bodies[b].role == BodyRole::Robot) continue;
    const Eigen::Vector3d from = WorldLayout::position(start.data(), b);
    const Eigen::Vector3d to = WorldLayout::position(settled.data(), b);
    if ((to - from).head<2>().norm() < kMaxSideways &&
        tiltChange(start, settled, b) < kMaxTiltChange)
      sink[b] = std::max(0.0, from.z() - to.z());
  }
  return sink;
}

std::vector<RestlessObject> restlessObjects(const WorldLayout& layout,
                                            const std::vector<double>& start,
                                            const std::vector<double>& settled, bool soft) {
  // On soft contacts a resting object sinks, heavy ones by more than 10 cm (Kautham's walls):
  // only a move sideways tells there that it does not rest.
  std::vector<RestlessObject> restless;
  for (std::size_t b = 0; b < layout.bodies.size(); ++b) {
    if (layout.bodies[b].role == BodyRole::Robot) continue;
    Eigen::Vector3d move =
        WorldLayout::position(settled.data(), b) - WorldLayout::position(start.data(), b);
    if (soft) move.z() = 0.0;
    const double tilt = tiltChange(start, settled, b);
    if (move.norm() > kRestlessMove || tilt > kRestlessTilt)
      restless.push_back({layout.bodies[b].name, move.norm(), tilt});
  }
  return restless;
}

}  // namespace kautham::physics
