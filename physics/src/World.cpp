#include "kautham/physics/World.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "ContainedCentres.h"
#include "GeomTag.h"
#include "OdeMeshData.h"

namespace kautham::physics {

World::~World() { destroy(); }

void World::destroy() {
  // Every ODE object goes before the library may close (ode_ is released after this).
  if (contactGroup_) dJointGroupDestroy(contactGroup_);
  if (space_) dSpaceDestroy(space_);  // destroys its geoms too (cleanup mode is on)
  meshData_.clear();                  // after the geoms that point into it
  if (world_) dWorldDestroy(world_);  // destroys bodies and joints
  contactGroup_ = nullptr;
  space_ = nullptr;
  world_ = nullptr;
}

void World::readState(double* state) const {
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    double* s = state + i * WorldLayout::kBodyStateSize;
    const dReal* p = dBodyGetPosition(bodies_[i]);
    const dReal* q = dBodyGetQuaternion(bodies_[i]);
    const dReal* v = dBodyGetLinearVel(bodies_[i]);
    const dReal* w = dBodyGetAngularVel(bodies_[i]);
    std::copy(p, p + 3, s + WorldLayout::kPosition);
    std::copy(q, q + 4, s + WorldLayout::kOrientation);
    std::copy(v, v + 3, s + WorldLayout::kLinearVelocity);
    std::copy(w, w + 3, s + WorldLayout::kAngularVelocity);
  }
  readJoints(state + layout_.jointPositionIndex(), state + layout_.jointVelocityIndex());
  state[layout_.flagsIndex()] = 0.0;
}

void World::writeState(const double* state) {
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const double* s = state + i * WorldLayout::kBodyStateSize;
    dBodySetPosition(bodies_[i], s[0], s[1], s[2]);
    // dBodySetQuaternion recomputes the rotation matrix from q exactly as a step does, so a
    // written state continues bit for bit like the state the step left behind.
    dQuaternion q = {s[3], s[4], s[5], s[6]};
    dBodySetQuaternion(bodies_[i], q);
    dBodySetLinearVel(bodies_[i], s[7], s[8], s[9]);
    dBodySetAngularVel(bodies_[i], s[10], s[11], s[12]);
  }
  // After the bodies are set: setting a body moves its geometries to the front of the list
  // only if they were clean, and whether they were depends on what ran before (a collision
  // test cleans them, a step dirties them). Now every one is dirty, so its order is ours.
  restoreGeomOrder();
  for (dBodyID body : sleepers_) {
    dBodyEnable(body);  // restarts its idle count
    const dReal* v = dBodyGetLinearVel(body);
    const dReal* w = dBodyGetAngularVel(body);
    const bool resting =
        v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0 && w[0] == 0.0 && w[1] == 0.0 && w[2] == 0.0;
    if (resting && !(held_ && body == bodies_[*held_])) dBodyDisable(body);
  }
}

void World::restoreGeomOrder() {
  // ODE moves a geometry to the front of its space's list when it becomes dirty, and a step
  // dirties bodies island by island: the order of the list, hence of contacts and of the
  // solver's constraints, would carry the previous step's contacts into the next. Re-adding
  // the dynamic geometries in a fixed order makes every run from a written state the same.
  // ODE finds the geometries whose bounding boxes are out of date at the front of that list
  // (it moves one there when it first moves), so those robotTouchesShifted() moved are brought
  // up to date before the order is restored: behind a geometry that has not moved, a later
  // collision test would use their old boxes and miss touches.
  if (shiftedAside_) dSpaceClean(space_);
  shiftedAside_ = false;
  for (dGeomID geom : dynamicGeoms_) dSpaceRemove(space_, geom);
  for (dGeomID geom : dynamicGeoms_) dSpaceAdd(space_, geom);
}

void World::setJointVelocities(const double* velocities) {
  for (std::size_t i = 0; i < actuators_.size(); ++i) {
    const Actuator& a = actuators_[i];
    if (!a.joint) continue;  // built into the static base
    const double v = std::clamp(velocities[i], -a.maxVelocity, a.maxVelocity);
    if (a.type == core::JointType::Prismatic)
      dJointSetSliderParam(a.joint, dParamVel, v);
    else
      dJointSetHingeParam(a.joint, dParamVel, v);
  }
}

void World::readJoints(double* positions, double* rates) const {
  for (std::size_t i = 0; i < actuators_.size(); ++i) {
    const Actuator& a = actuators_[i];
    if (!a.joint) {  // built into the static base
      positions[i] = a.heldAt;
      rates[i] = 0.0;
      continue;
    }
    const bool prismatic = a.type == core::JointType::Prismatic;
    positions[i] = prismatic ? dJointGetSliderPosition(a.joint) : dJointGetHingeAngle(a.joint);
    rates[i] = prismatic ? dJointGetSliderPositionRate(a.joint) : dJointGetHingeAngleRate(a.joint);
  }
}

std::vector<double> World::jointPositions() const {
  std::vector<double> positions(actuators_.size());
  std::vector<double> rates(actuators_.size());
  readJoints(positions.data(), rates.data());
  return positions;
}

std::vector<double> World::jointVelocities() const {
  std::vector<double> positions(actuators_.size());
  std::vector<double> rates(actuators_.size());
  readJoints(positions.data(), rates.data());
  return rates;
}

void World::setContactParameters(const ContactParameters& parameters) {
  if (!(parameters.friction >= 0.0) || !(parameters.erp >= 0.0 && parameters.erp <= 1.0) ||
      !(parameters.cfm >= 0.0))
    throw std::invalid_argument("contact parameters need friction >= 0, erp in [0, 1], cfm >= 0");
  contact_ = parameters;
}

void World::resetSolverSeed() const { dRandSetSeed(0); }

void World::step() {
  dSpaceCollide(space_, this, &World::nearCallback);
  dWorldQuickStep(world_, settings_.stepSize);
  dJointGroupEmpty(contactGroup_);
  if (diverged()) events_ |= kSimulationDiverged;
}

std::vector<int> World::takeTouchedBodies() {
  std::vector<int> touched;
  for (std::size_t b = 0; b < touched_.size(); ++b)
    if (touched_[b]) touched.push_back(static_cast<int>(b));
  std::fill(touched_.begin(), touched_.end(), 0);
  return touched;
}

namespace {

/// The box-cylinder overlaps ODE's collider misses (ContainedCentres.h), added to `overlaps`.
void addContainedCentres(dSpaceID space, double depth, std::vector<Overlap>& overlaps) {
  for (const ContainedPair& pair : containedCentres(space, depth)) {
    const auto* inner = static_cast<const GeomTag*>(dGeomGetData(pair.inner));
    const auto* outer = static_cast<const GeomTag*>(dGeomGetData(pair.outer));
    if (!inner || !outer || (inner->isRobot() && outer->isRobot())) continue;
    const bool known = std::any_of(overlaps.begin(), overlaps.end(), [&](const Overlap& o) {
      return (o.first == inner->name && o.second == outer->name) ||
             (o.first == outer->name && o.second == inner->name);
    });
    if (!known) overlaps.push_back({inner->name, outer->name, pair.depth});
  }
}

}  // namespace

std::vector<Overlap> World::probeContacts(double depth) {
  std::vector<Overlap> overlaps;
  overlaps_ = &overlaps;
  overlapDepth_ = depth;
  dSpaceCollide(space_, this, &World::nearCallback);
  dJointGroupEmpty(contactGroup_);
  overlaps_ = nullptr;
  addContainedCentres(space_, depth, overlaps);
  return overlaps;
}

RobotTouches World::robotTouches(int heldBody) {
  RobotTouches touches;
  touches_ = &touches;
  heldBody_ = heldBody;
  dSpaceCollide(space_, this, &World::touchCallback);
  touches_ = nullptr;
  std::sort(touches.bodies.begin(), touches.bodies.end());
  touches.bodies.erase(std::unique(touches.bodies.begin(), touches.bodies.end()),
                       touches.bodies.end());
  return touches;
}

void World::touchCallback(void* data, dGeomID a, dGeomID b) {
  if (dGeomIsSpace(a) || dGeomIsSpace(b)) return dSpaceCollide2(a, b, data, &World::touchCallback);
  static_cast<World*>(data)->recordTouch(a, b);
}

void World::recordTouch(dGeomID a, dGeomID b) {
  const GeomTag& tagA = *static_cast<const GeomTag*>(dGeomGetData(a));
  const GeomTag& tagB = *static_cast<const GeomTag*>(dGeomGetData(b));
  const auto moving = [this](const GeomTag& tag) {
    return tag.kind == GeomTag::Kind::RobotLink || (heldBody_ >= 0 && tag.body == heldBody_);
  };
  if (tagA.isRobot() && tagB.isRobot()) return;  // no self-collision (docs/problem-format.md)
  if (moving(tagA) == moving(tagB)) return;      // the arm with what it holds, or bystanders
  if (usableContacts(dCollide(a, b, 1, &contactBuffer_[0].geom, sizeof(dContact))) == 0) return;
  const GeomTag& other = moving(tagA) ? tagB : tagA;
  if (other.kind == GeomTag::Kind::Fixed || other.kind == GeomTag::Kind::RobotBase)
    touches_->fixed = true;
  if (other.kind == GeomTag::Kind::Target) touches_->target = true;
  if (other.body >= 0) touches_->bodies.push_back(other.body);
}

bool World::attach(std::size_t body, double reach) {
  release();
  std::vector<double> state(layout_.stateSize());
  readState(state.data());
  const Eigen::Vector3d tcp = layout_.goalLinkPosition(state.data());
  // Distance from the gripper to the object's shapes' bounding box, in the world.
  const Eigen::AlignedBox3d box = layout_.bounds(body, state.data());
  if (box.isEmpty() || box.exteriorDistance(tcp) > reach) return false;

  dBodyID gripper = bodies_[static_cast<std::size_t>(layout_.goalBody)];
  grip_ = dJointCreateFixed(world_, nullptr);
  dJointAttach(grip_, gripper, bodies_[body]);
  dJointSetFixed(grip_);
  dBodyEnable(bodies_[body]);
  dBodySetAutoDisableFlag(bodies_[body], 0);  // a held object never sleeps
  // The arm holds itself (its links have no gravity); what it holds is its payload, carried
  // the same way, or its weight would drag the velocity-driven joints off their path.
  dBodySetGravityMode(bodies_[body], 0);
  held_ = body;
  return true;
}

void World::release() {
  if (grip_) dJointDestroy(grip_);
  grip_ = nullptr;
  if (held_) dBodySetGravityMode(bodies_[*held_], 1);
  if (held_ && std::find(sleepers_.begin(), sleepers_.end(), bodies_[*held_]) != sleepers_.end())
    dBodySetAutoDisableFlag(bodies_[*held_], 1);
  held_.reset();
}

unsigned World::takeEvents() {
  const unsigned events = events_;
  events_ = kNoEvent;
  return events;
}

void World::nearCallback(void* data, dGeomID a, dGeomID b) {
  // A fixed object of many shapes has a space of its own (WorldBuilder): test inside it.
  if (dGeomIsSpace(a) || dGeomIsSpace(b)) return dSpaceCollide2(a, b, data, &World::nearCallback);
  static_cast<World*>(data)->collide(a, b);
}

void World::collide(dGeomID a, dGeomID b) {
  dBodyID bodyA = dGeomGetBody(a);
  dBodyID bodyB = dGeomGetBody(b);
  if (!bodyA && !bodyB) return;
  // Two sleeping objects, or one on the table, exert nothing: skip them, which is most of
  // the cost of a dense scene. A probe of the start state looks at every pair.
  if (!overlaps_ && !isAwake(bodyA) && !isAwake(bodyB)) return;
  const GeomTag& tagA = *static_cast<const GeomTag*>(dGeomGetData(a));
  const GeomTag& tagB = *static_cast<const GeomTag*>(dGeomGetData(b));
  if (tagA.isRobot() && tagB.isRobot()) return;  // no self-collision (docs/problem-format.md)

  const int count = usableContacts(
      dCollide(a, b, settings_.maxContacts, &contactBuffer_[0].geom, sizeof(dContact)));
  if (count == 0) return;
  events_ |= contactEvent(tagA, tagB);
  if (tagA.isRobot() != tagB.isRobot()) {
    const GeomTag& other = tagA.isRobot() ? tagB : tagA;
    if (other.body >= 0) touched_[static_cast<std::size_t>(other.body)] = 1;
  }
  if (overlaps_) recordOverlap(tagA, tagB, count);
  for (int i = 0; i < count; ++i) {
    dContact& contact = contactBuffer_[i];
    contact.surface.mode = dContactApprox1 | dContactSoftERP | dContactSoftCFM;
    contact.surface.mu = contact_.friction;
    contact.surface.soft_erp = contact_.erp;
    contact.surface.soft_cfm = contact_.cfm;
    dJointAttach(dJointCreateContact(world_, contactGroup_, &contact), bodyA, bodyB);
  }
}

bool World::isAwake(dBodyID body) { return body && dBodyIsEnabled(body); }

int World::usableContacts(int count) {
  // libccd's colliders (convex hulls against anything) report shapes that just touch as a
  // contact of depth 0 with a zero normal; a contact joint along it makes the solver's result
  // NaN. Such contacts carry no information: drop them.
  int kept = 0;
  for (int i = 0; i < count; ++i) {
    const dContactGeom& g = contactBuffer_[i].geom;
    const double length = std::sqrt(g.normal[0] * g.normal[0] + g.normal[1] * g.normal[1] +
                                    g.normal[2] * g.normal[2]);
    if (!(std::abs(length - 1.0) < 1e-3) || !std::isfinite(g.depth)) continue;
    if (kept != i) contactBuffer_[kept].geom = g;
    ++kept;
  }
  return kept;
}

void World::recordOverlap(const GeomTag& a, const GeomTag& b, int contacts) {
  double deepest = 0.0;
  for (int i = 0; i < contacts; ++i) deepest = std::max(deepest, contactBuffer_[i].geom.depth);
  if (deepest > overlapDepth_) overlaps_->push_back({a.name, b.name, deepest});
}

bool World::diverged() const {
  constexpr double kMaxSpeed = 100.0;   // m/s or rad/s: far beyond anything on a table
  constexpr double kMaxDistance = 1e3;  // m from the origin
  for (dBodyID body : bodies_) {
    const dReal* p = dBodyGetPosition(body);
    const dReal* v = dBodyGetLinearVel(body);
    const dReal* w = dBodyGetAngularVel(body);
    for (int k = 0; k < 3; ++k)
      if (!(std::abs(p[k]) < kMaxDistance) || !(std::abs(v[k]) < kMaxSpeed) ||
          !(std::abs(w[k]) < kMaxSpeed))
        return true;  // also catches NaN: every comparison with NaN is false
  }
  return false;
}

}  // namespace kautham::physics
