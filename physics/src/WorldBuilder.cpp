// Construction of the ODE world from a loaded problem.

#include <cmath>
#include <map>
#include <optional>

#include <Eigen/Eigenvalues>

#include "GeomTag.h"
#include "OdeMeshData.h"
#include "kautham/physics/World.h"

namespace kautham::physics {

namespace {

using core::KinematicModel;

void toOdeRotation(const Eigen::Matrix3d& rotation, dMatrix3 out) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out[r * 4 + c] = rotation(r, c);
    out[r * 4 + 3] = 0.0;
  }
}

dGeomID createPrimitive(const core::Shape& shape) {
  struct Create {
    dGeomID operator()(const core::Box& b) const {
      return dCreateBox(nullptr, b.size.x(), b.size.y(), b.size.z());
    }
    dGeomID operator()(const core::Cylinder& c) const {
      return dCreateCylinder(nullptr, c.radius, c.length);
    }
    dGeomID operator()(const core::Sphere& s) const { return dCreateSphere(nullptr, s.radius); }
    dGeomID operator()(const core::Mesh&) const { return nullptr; }  // see Builder::createGeom
  };
  return std::visit(Create{}, shape);
}

/// Links rigidly attached to each other (through fixed joints) move as one ODE body.
/// A group is named by its top link: the root, or a link whose parent joint moves.
///
/// A joint that no control moves (`held`: its value, by joint index) and that hangs from the
/// static base is built into the base at that value: the YuMi's idle right arm is static
/// geometry, not nine bodies locked by their stops that the solver must hold still every step
/// (docs/physics.md, "Held joints").
struct LinkGroups {
  std::vector<int> groupOf;                ///< link -> its group's top link
  std::vector<Eigen::Isometry3d> inGroup;  ///< link pose in its group's top link frame

  explicit LinkGroups(const KinematicModel& model,
                      const std::vector<std::optional<double>>& held = {})
      : groupOf(model.links.size(), -1), inGroup(model.links.size()) {
    std::vector<int> pending{model.rootLink};
    groupOf[model.rootLink] = model.rootLink;
    inGroup[model.rootLink] = Eigen::Isometry3d::Identity();
    while (!pending.empty()) {
      const int link = pending.back();
      pending.pop_back();
      for (int j : model.links[link].childJoints) {
        const core::Joint& joint = model.joints[j];
        const int child = joint.childLink;
        const std::size_t index = static_cast<std::size_t>(j);
        const bool heldOnBase =
            index < held.size() && held[index] && groupOf[link] == model.rootLink;
        const bool rigid = !joint.isMovable() || heldOnBase;
        const Eigen::Isometry3d step =
            heldOnBase ? joint.origin * KinematicModel::jointMotion(joint, *held[index])
                       : joint.origin;
        groupOf[child] = rigid ? groupOf[link] : child;
        inGroup[child] = rigid ? inGroup[link] * step : Eigen::Isometry3d::Identity();
        pending.push_back(child);
      }
    }
  }

  /// Whether the joint is built into the static base.
  bool inBase(const KinematicModel& model, int joint) const {
    return groupOf[model.joints[joint].childLink] == model.rootLink;
  }

  std::vector<int> members(int top) const {
    std::vector<int> links;
    for (std::size_t i = 0; i < groupOf.size(); ++i)
      if (groupOf[i] == top) links.push_back(static_cast<int>(i));
    return links;
  }
};

/// Mass, centre of mass and inertia of a group, in its top link's axes.
struct GroupMass {
  double mass = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  ///< about the centre of mass

  GroupMass(const KinematicModel& model, const LinkGroups& groups, int top) {
    for (int link : groups.members(top)) {
      const core::Inertial& in = model.links[link].inertial;
      mass += in.mass;
      centre += in.mass * (groups.inGroup[link] * in.origin).translation();
    }
    if (mass <= 0.0) return;
    centre /= mass;
    for (int link : groups.members(top)) {
      const core::Inertial& in = model.links[link].inertial;
      const Eigen::Isometry3d frame = groups.inGroup[link] * in.origin;
      const Eigen::Vector3d d = frame.translation() - centre;
      // Rotate each inertia into the group's axes, then move it to the common centre.
      inertia += frame.linear() * in.inertia * frame.linear().transpose() +
                 in.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
    }
  }

  /// ODE rejects a body without positive mass and positive definite inertia; massless links
  /// (URDF frames without <inertial>) get a small sphere's, so they do not break the chain.
  void ensurePhysical() {
    constexpr double kDefaultMass = 0.1;
    constexpr double kDefaultRadius = 0.02;
    if (mass <= 0.0) mass = kDefaultMass;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(inertia);
    if (solver.eigenvalues().minCoeff() <= 0.0)
      inertia = Eigen::Matrix3d::Identity() * 0.4 * mass * kDefaultRadius * kDefaultRadius;
  }
};

const char* roleName(GeomTag::Kind kind) {
  switch (kind) {
    case GeomTag::Kind::RobotLink:
    case GeomTag::Kind::RobotBase:
      return "robot";
    case GeomTag::Kind::Fixed:
      return "fixed";
    case GeomTag::Kind::Movable:
      return "movable";
    case GeomTag::Kind::Target:
      return "target";
  }
  return "?";
}

}  // namespace

class World::Builder {
 public:
  explicit Builder(World& world, const core::Problem& problem) : world_(world), problem_(problem) {}

  void build(const core::Query& query) {
    createWorld();
    buildRobot(query);
    for (std::size_t i = 0; i < problem_.objects.size(); ++i) buildObject(static_cast<int>(i));
    if (problem_.groundHeight) buildGround(*problem_.groundHeight);
    world_.contactBuffer_.resize(static_cast<std::size_t>(problem_.physics.maxContacts));
    world_.touched_.assign(world_.bodies_.size(), 0);
  }

 private:
  void createWorld() {
    const core::PhysicsSettings& s = problem_.physics;
    world_.world_ = dWorldCreate();
    dWorldSetGravity(world_.world_, s.gravity.x(), s.gravity.y(), s.gravity.z());
    dWorldSetQuickStepNumIterations(world_.world_, s.solverIterations);
    dWorldSetQuickStepW(world_.world_, s.overRelaxation);
    // Only objects sleep (makeSleeper), and only in a way the state records (World::writeState).
    dWorldSetAutoDisableFlag(world_.world_, 0);
    // A thin allowed penetration keeps resting contacts from flickering on and off.
    dWorldSetContactSurfaceLayer(world_.world_, 0.0005);
    world_.space_ = dSimpleSpaceCreate(nullptr);
    dSpaceSetCleanup(world_.space_, 1);
    world_.contactGroup_ = dJointGroupCreate(0);
  }

  /// Kautham's implicit ground (core::Problem::groundHeight): a plane that objects rest on and
  /// that the robot passes through, as it does the static base of the robot.
  void buildGround(double height) {
    world_.tags_.push_back(
        std::make_unique<GeomTag>(GeomTag{GeomTag::Kind::RobotBase, "ground", -1}));
    GeomTag* tag = world_.tags_.back().get();
    dGeomID plane = dCreatePlane(world_.space_, 0.0, 0.0, 1.0, height);
    dGeomSetData(plane, tag);
    dGeomSetCategoryBits(plane, tag->category());
    dGeomSetCollideBits(plane, tag->collidesWith());
  }

  /// The shapes of the links in `top`'s group, on `body` or static (null). Each shape's owner is
  /// `name`, or with `linkPrefix` the prefix and its own link's name (the robot's static base,
  /// where links that no control moves join it, is several links).
  void addGeoms(const KinematicModel& model, const LinkGroups& groups, int top, GeomTag::Kind kind,
                dBodyID body, const Eigen::Isometry3d& topInWorldOrBody, const std::string& name,
                dSpaceID space = nullptr, const std::string& linkPrefix = "") {
    const int bodyIndex = body ? static_cast<int>(world_.bodies_.size()) : -1;
    world_.tags_.push_back(std::make_unique<GeomTag>(GeomTag{kind, name, bodyIndex}));
    GeomTag* tag = world_.tags_.back().get();
    for (int link : groups.members(top)) {
      for (const core::CollisionShape& collision : model.links[link].collisions) {
        Eigen::Vector3d shift = Eigen::Vector3d::Zero();  // a convex hull's centre
        dGeomID geom = createGeom(collision.shape, body != nullptr, shift);
        dSpaceAdd(space ? space : world_.space_, geom);
        dGeomSetData(geom, tag);
        dGeomSetCategoryBits(geom, tag->category());
        dGeomSetCollideBits(geom, tag->collidesWith());
        const Eigen::Isometry3d pose = topInWorldOrBody * groups.inGroup[link] * collision.origin;
        const std::string owner = linkPrefix.empty() ? name : linkPrefix + model.links[link].name;
        world_.layout_.shapes.push_back({collision.shape, bodyIndex, pose, owner, roleName(kind)});
        const Eigen::Isometry3d geomPose = pose * Eigen::Translation3d(shift);
        dMatrix3 rotation;
        toOdeRotation(geomPose.linear(), rotation);
        if (body) {
          world_.dynamicGeoms_.push_back(geom);
          dGeomSetBody(geom, body);
          dGeomSetOffsetPosition(geom, geomPose.translation().x(), geomPose.translation().y(),
                                 geomPose.translation().z());
          dGeomSetOffsetRotation(geom, rotation);
        } else {
          dGeomSetPosition(geom, geomPose.translation().x(), geomPose.translation().y(),
                           geomPose.translation().z());
          dGeomSetRotation(geom, rotation);
        }
      }
    }
  }

  /// Meshes collide as their convex hull on bodies, as their triangles when fixed: ODE's
  /// trimesh-trimesh contacts are slow and unstable, and a fixed trimesh never meets another.
  dGeomID createGeom(const core::Shape& shape, bool onBody, Eigen::Vector3d& shift) {
    const auto* mesh = std::get_if<core::Mesh>(&shape);
    if (!mesh) return createPrimitive(shape);
    std::shared_ptr<OdeMeshData>& data = meshData_[mesh->data.get()];
    if (!data) {
      data = std::make_shared<OdeMeshData>(*mesh);
      world_.meshData_.push_back(data);
    }
    if (!onBody) return data->createTriMesh();
    shift = data->convexCentre();
    return data->createConvex();
  }

  /// Creates the body of a group whose top link is at `topPose`; returns it and records it.
  dBodyID createBody(const KinematicModel& model, const LinkGroups& groups, int top,
                     const Eigen::Isometry3d& topPose, BodyInfo info, GeomTag::Kind kind) {
    GroupMass groupMass(model, groups, top);
    groupMass.ensurePhysical();
    dBodyID body = dBodyCreate(world_.world_);
    dMass mass;
    dMassSetZero(&mass);
    const Eigen::Matrix3d& I = groupMass.inertia;
    dMassSetParameters(&mass, groupMass.mass, 0, 0, 0, I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2),
                       I(1, 2));
    dBodySetMass(body, &mass);

    // ODE bodies sit at their centre of mass; the link frame is offset from it.
    Eigen::Isometry3d centreInTop = Eigen::Isometry3d::Identity();
    centreInTop.translation() = groupMass.centre;
    info.linkInBody = centreInTop.inverse();
    setBodyPose(body, topPose * centreInTop);
    addGeoms(model, groups, top, kind, body, info.linkInBody, info.name);

    world_.bodies_.push_back(body);
    world_.layout_.bodies.push_back(std::move(info));
    return body;
  }

  static void setBodyPose(dBodyID body, const Eigen::Isometry3d& pose) {
    dBodySetPosition(body, pose.translation().x(), pose.translation().y(), pose.translation().z());
    const Eigen::Quaterniond q(pose.linear());
    dQuaternion quaternion = {q.w(), q.x(), q.y(), q.z()};
    dBodySetQuaternion(body, quaternion);
  }

  void buildRobot(const core::Query& query) {
    const core::RobotInstance& robot = problem_.robot;
    const KinematicModel& model = robot.model;
    const std::vector<int> movable = model.movableJoints();
    const std::vector<double> initialValues = problem_.initialJointValues(query);
    std::vector<std::optional<double>> held(model.joints.size());
    for (std::size_t i = 0; i < movable.size(); ++i)
      if (!robot.controls.moves(i)) held[static_cast<std::size_t>(movable[i])] = initialValues[i];
    const LinkGroups groups(model, held);
    const Eigen::Isometry3d base = robot.home.isometry();
    // Joints are created at the zero configuration, so ODE's zero matches the URDF's zero; the
    // joints built into the base are where they stay.
    std::vector<double> zero(movable.size(), 0.0);
    for (std::size_t i = 0; i < movable.size(); ++i)
      if (groups.inBase(model, movable[i])) zero[i] = initialValues[i];
    const std::vector<Eigen::Isometry3d> zeroPoses = model.linkPoses(base, zero);

    addGeoms(model, groups, model.rootLink, GeomTag::Kind::RobotBase, nullptr, base,
             robot.name + "/" + model.links[model.rootLink].name, nullptr, robot.name + "/");
    std::vector<dBodyID> bodyOfGroup(model.links.size(), nullptr);
    std::vector<int> bodyIndexOfGroup(model.links.size(), -1);
    for (int j : movable) {
      if (groups.inBase(model, j)) continue;
      const int child = model.joints[j].childLink;
      bodyIndexOfGroup[child] = static_cast<int>(world_.bodies_.size());
      BodyInfo info{robot.name + "/" + model.links[child].name, BodyRole::Robot, -1, {}};
      dBodyID body =
          createBody(model, groups, child, zeroPoses[child], info, GeomTag::Kind::RobotLink);
      dBodySetGravityMode(body, 0);  // the arm holds itself: its motors need not fight gravity
      bodyOfGroup[child] = body;
    }
    for (std::size_t i = 0; i < movable.size(); ++i) {
      if (groups.inBase(model, movable[i]))
        addActuator(model.joints[movable[i]], nullptr, initialValues[i]);
      else
        createActuator(model, movable[i], zeroPoses, groups, bodyOfGroup);
    }

    const std::vector<Eigen::Isometry3d> initial = model.linkPoses(base, initialValues);
    for (int j : movable) {
      if (groups.inBase(model, j)) continue;
      const int child = model.joints[j].childLink;
      const BodyInfo& info = world_.layout_.bodies[bodyIndexOfGroup[child]];
      setBodyPose(bodyOfGroup[child], initial[child] * info.linkInBody.inverse());
    }
    lockHeldJoints(initialValues);
    placeLinks(model, groups, base, bodyIndexOfGroup);
    locateGoalLink(query, groups, bodyIndexOfGroup);
  }

  void placeLinks(const KinematicModel& model, const LinkGroups& groups,
                  const Eigen::Isometry3d& base, const std::vector<int>& bodyIndexOfGroup) {
    WorldLayout& layout = world_.layout_;
    for (std::size_t link = 0; link < model.links.size(); ++link) {
      const int body = bodyIndexOfGroup[static_cast<std::size_t>(groups.groupOf[link])];
      const Eigen::Isometry3d& top =
          body < 0 ? base : layout.bodies[static_cast<std::size_t>(body)].linkInBody;
      layout.robotLinks.push_back({body, top * groups.inGroup[link]});
    }
  }

  void createActuator(const KinematicModel& model, int j,
                      const std::vector<Eigen::Isometry3d>& zeroPoses, const LinkGroups& groups,
                      const std::vector<dBodyID>& bodyOfGroup) {
    const core::Joint& joint = model.joints[j];
    const Eigen::Isometry3d frame = zeroPoses[joint.parentLink] * joint.origin;
    const Eigen::Vector3d axis = frame.linear() * joint.axis;
    const Eigen::Vector3d anchor = frame.translation();
    dBodyID child = bodyOfGroup[joint.childLink];
    dBodyID parent = bodyOfGroup[groups.groupOf[joint.parentLink]];  // null: the static base
    const bool prismatic = joint.type == core::JointType::Prismatic;

    // The child is ODE's body 1, so positive joint rates move the child along +axis,
    // as the URDF convention does.
    dJointID id = prismatic ? dJointCreateSlider(world_.world_, nullptr)
                            : dJointCreateHinge(world_.world_, nullptr);
    dJointAttach(id, child, parent);
    if (prismatic) {
      dJointSetSliderAxis(id, axis.x(), axis.y(), axis.z());
      setLimitsAndMotor(id, joint, &dJointSetSliderParam);
    } else {
      dJointSetHingeAnchor(id, anchor.x(), anchor.y(), anchor.z());
      dJointSetHingeAxis(id, axis.x(), axis.y(), axis.z());
      setLimitsAndMotor(id, joint, &dJointSetHingeParam);
      addArmature(child);
    }
    addActuator(joint, id);
  }

  /// Records a movable joint: its actuator (`id`, or none for a held joint built into the
  /// static base, which reads as `heldAt`) and what states and the validity check know of it.
  void addActuator(const core::Joint& joint, dJointID id, double heldAt = 0.0) {
    world_.actuators_.push_back({joint.name, id, joint.type, joint.maxVelocity, heldAt});
    const bool limited = joint.type != core::JointType::Continuous;
    world_.layout_.joints.push_back({joint.name, limited ? joint.lower : 0.0,
                                     limited ? joint.upper : 0.0, joint.maxVelocity, limited});
  }

  // Joint stops and motors with QuickStep's default 20 iterations (docs/physics.md, "Joint
  // stops"; measured with the KUKA and YuMi arms).
  //
  // ODE's stop error correction: the fraction of a joint's penetration into its stop removed
  // in one step. With the default (the world's ERP, 0.2), the KUKA's A2 pressed into its stop
  // by its motor settled 0.08 rad past it; with 0.8 (and kArmature) 0.003 rad.
  static constexpr double kStopErp = 0.8;
  // While a joint is at a stop, ODE replaces its motor by the full effort applied as a
  // torque (or force): into the stop, or times the fudge factor out of it when the command
  // points away. The default factor 1 gives a light link a kick of effort x step / inertia
  // when it leaves the stop (with 38 N*m on the KUKA's wrist: over 100 rad/s, a divergence);
  // 0.1, ODE's documented remedy, is still enough to free the joint, and the motor takes over
  // at the next step.
  static constexpr double kFudgeFactor = 0.1;
  // Extra rotational inertia (kg m^2, about every axis through the centre of mass) of each body
  // behind a revolute joint, like the armature of a geared motor. QuickStep passes impulses
  // along a chain of light links poorly: with 20 iterations an arm stopping at a joint stop
  // passed it by 0.08 rad (100 iterations: 0.02). With 0.1 kg m^2 it passes by 0.01 rad, also
  // with the KUKA's published torques. The arms are velocity controlled: the inertia slows
  // their accelerations a little, not their speeds.
  static constexpr double kArmature = 0.1;

  static void setLimitsAndMotor(dJointID id, const core::Joint& joint,
                                void (*setParam)(dJointID, int, dReal)) {
    if (joint.type != core::JointType::Continuous) {
      // Set high first: ODE ignores a low stop above the current high stop.
      setParam(id, dParamHiStop, joint.upper);
      setParam(id, dParamLoStop, joint.lower);
      setParam(id, dParamStopERP, kStopErp);
    }
    setParam(id, dParamFudgeFactor, kFudgeFactor);
    setParam(id, dParamFMax, joint.maxEffort);
    setParam(id, dParamVel, 0.0);
  }

  /// Adds kArmature to the body's inertia (the body sits at its centre of mass).
  static void addArmature(dBodyID body) {
    dMass mass;
    dBodyGetMass(body, &mass);
    for (int axis = 0; axis < 3; ++axis) mass.I[axis * 4 + axis] += kArmature;
    dBodySetMass(body, &mass);
  }

  /// A joint that no control moves (a gripper's fingers while the arm pushes) is locked where
  /// it starts: both stops at its initial value. Held by its motor alone, a light finger slips
  /// under the arm's accelerations (0.12 m/s with a 20 N finger motor on the KUKA).
  void lockHeldJoints(const std::vector<double>& initialValues) {
    const core::ControlSet& controls = problem_.robot.controls;
    for (std::size_t i = 0; i < world_.actuators_.size(); ++i) {
      if (controls.moves(i)) continue;
      world_.layout_.joints[i].held = true;
      const Actuator& a = world_.actuators_[i];
      if (!a.joint) continue;  // built into the base
      const auto setParam =
          a.type == core::JointType::Prismatic ? &dJointSetSliderParam : &dJointSetHingeParam;
      // High first: ODE ignores a low stop above the current high stop.
      setParam(a.joint, dParamHiStop, initialValues[i]);
      setParam(a.joint, dParamLoStop, initialValues[i]);
    }
  }

  void locateGoalLink(const core::Query& query, const LinkGroups& groups,
                      const std::vector<int>& bodyIndexOfGroup) {
    const KinematicModel& model = problem_.robot.model;
    const int link = *model.findLink(query.goal.link);
    const int top = groups.groupOf[link];
    if (bodyIndexOfGroup[top] < 0)
      throw core::InputError(query.goal.where, "goal link '" + query.goal.link +
                                                   "' is fixed to the robot's base (or joined "
                                                   "to it only by joints no control moves): it "
                                                   "can never move to the goal; move its arm's "
                                                   "joints in the control set");
    WorldLayout& layout = world_.layout_;
    layout.goalBody = bodyIndexOfGroup[top];
    layout.goalLinkInBody = layout.bodies[layout.goalBody].linkInBody * groups.inGroup[link];
  }

  void buildObject(int index) {
    const core::ObjectInstance& object = problem_.objects[index];
    const LinkGroups groups(object.model);
    const int root = object.model.rootLink;
    const Eigen::Isometry3d home = object.home.isometry();
    if (object.role == core::ObjectRole::Fixed) {
      addGeoms(object.model, groups, root, GeomTag::Kind::Fixed, nullptr, home, object.name,
               spaceOfFixed(object.model));
      return;
    }
    const bool target = object.role == core::ObjectRole::Target;
    BodyInfo info{object.name, target ? BodyRole::Target : BodyRole::Movable, index, {}};
    dBodyID body = createBody(object.model, groups, root, home, info,
                              target ? GeomTag::Kind::Target : GeomTag::Kind::Movable);
    if (problem_.physics.sleep) makeSleeper(body);
  }

  /// ODE disables the object once it has been idle for sleepSteps steps (and zeroes its
  /// velocity then), and wakes it when a contact joins it to an awake body.
  void makeSleeper(dBodyID body) {
    const core::PhysicsSettings& s = problem_.physics;
    dBodySetAutoDisableFlag(body, 1);
    dBodySetAutoDisableLinearThreshold(body, s.sleepSpeed);
    dBodySetAutoDisableAngularThreshold(body, s.sleepSpeed);
    // One sample: idleness is judged on the current step alone, so no history outlives a
    // written state.
    dBodySetAutoDisableAverageSamplesCount(body, 1);
    dBodySetAutoDisableSteps(body, s.sleepSteps);
    dBodySetAutoDisableTime(body, 0.0);
    world_.sleepers_.push_back(body);
  }

  /// A fixed object of many shapes (a sensed environment, docs/physics.md) gets a collision
  /// space of its own inside the world's: the world's space sees it as one geometry, and a
  /// moving geometry is tested against its shapes only when it is inside their bounding box.
  dSpaceID spaceOfFixed(const KinematicModel& model) {
    constexpr std::size_t kShapesForOwnSpace = 8;
    std::size_t shapes = 0;
    for (const core::Link& link : model.links) shapes += link.collisions.size();
    if (shapes < kShapesForOwnSpace) return world_.space_;
    dSpaceID space = dSimpleSpaceCreate(world_.space_);
    dSpaceSetCleanup(space, 1);  // the world's space destroys it, and it its geometries
    const GeomTag fixed{GeomTag::Kind::Fixed, "", -1};
    dGeomSetCategoryBits(reinterpret_cast<dGeomID>(space), fixed.category());
    dGeomSetCollideBits(reinterpret_cast<dGeomID>(space), fixed.collidesWith());
    return space;
  }

  World& world_;
  const core::Problem& problem_;
  std::map<const core::Mesh::Data*, std::shared_ptr<OdeMeshData>> meshData_;  ///< one per mesh
};

World::World(const core::Problem& problem, const core::Query& query)
    : ode_(OdeLibrary::acquire()),
      settings_(problem.physics),
      contact_{problem.physics.friction, problem.physics.erp, problem.physics.cfm} {
  try {
    Builder(*this, problem).build(query);
  } catch (...) {
    destroy();  // the destructor does not run when a constructor throws
    throw;
  }
}

}  // namespace kautham::physics
