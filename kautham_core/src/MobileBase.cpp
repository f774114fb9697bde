#include "MobileBase.h"

#include <algorithm>
#include <cmath>

#include "XmlReader.h"
#include "kautham/core/Log.h"

namespace kautham::core {

namespace {

// Carriages between the base joints carry no geometry; ODE still needs a mass for each moving
// body (robot bodies have no gravity: it loads only the motors). Each gets the robot's mass:
// ODE's iterative solver converges badly along a chain of bodies of very different masses, and
// 0.5 kg carriages under Kautham's 25 kg sphere or 28 kg Tiago made the base joints' rates
// jitter past 1.2 times their limit ("joint too fast" was 97 % of Tiago's rejected states).
constexpr double kMinCarriageMass = 0.1;    // kg, for robots whose URDF gives no mass
constexpr double kCarriageGyration = 0.01;  // m^2: inertia per kg (a 10 cm radius of gyration),
                                            // at least; see addMobileBase
constexpr double kTurnVelocity = 1.0;       ///< rad/s of base_X3 (Kautham gives none)
constexpr double kTurnEffort = 100.0;       ///< N m

const char* const kAxisNames[3] = {"X", "Y", "Z"};

/// Renumbers every index of `model` as if `count` links and joints were inserted in front.
void shiftIndices(KinematicModel& model, int count) {
  for (Link& link : model.links) {
    if (link.parentJoint >= 0) link.parentJoint += count;
    for (int& j : link.childJoints) j += count;
  }
  for (Joint& joint : model.joints) {
    joint.parentLink += count;
    joint.childLink += count;
  }
  model.rootLink += count;
}

/// The DOF's name without Kautham's "robot/" prefix, and with this project's "base_" prefix
/// (base_X for X) taken off.
std::string dofName(const std::string& full) {
  std::string name = full.substr(full.find_last_of('/') + 1);
  if (name.rfind("base_", 0) == 0) name = name.substr(5);
  return name;
}

bool isBaseDof(const std::string& name) {
  return name == "X" || name == "Y" || name == "Z" || name == "X1" || name == "X2" || name == "X3";
}

/// Where the robot's root sits, in the frame of the carriage before joint `first`, when the
/// translations from `first` on are at the middle of their ranges.
Eigen::Vector3d middleOfTravel(const std::vector<Joint>& joints, int first) {
  Eigen::Vector3d middle = Eigen::Vector3d::Zero();
  for (std::size_t j = static_cast<std::size_t>(first); j < joints.size(); ++j) {
    if (joints[j].type != JointType::Prismatic) break;  // rotated frames follow
    middle += joints[j].axis * 0.5 * (joints[j].lower + joints[j].upper);
  }
  return middle;
}

}  // namespace

Eigen::Quaterniond kauthamRotation(double x1, double x2, double x3) {
  const double theta1 = 2.0 * M_PI * x2;
  const double theta2 = M_PI * x3;
  const double r1 = std::sqrt(std::clamp(x1, 0.0, 1.0));
  const double r2 = std::sqrt(1.0 - std::clamp(x1, 0.0, 1.0));
  return Eigen::Quaterniond(std::cos(theta2) * r2, std::sin(theta1) * r1, std::cos(theta1) * r1,
                            std::sin(theta2) * r2)
      .normalized();
}

BaseDofUse scanBaseDofs(const std::filesystem::path& cntrFile) {
  BaseDofUse use;
  use.where = {cntrFile, 0};
  const XmlReader xml(cntrFile);
  const tinyxml2::XMLElement& root = xml.root("ControlSet");
  if (const auto* offset = root.FirstChildElement("Offset"))
    for (const auto* d = offset->FirstChildElement("DOF"); d; d = d->NextSiblingElement("DOF")) {
      const char* name = d->Attribute("name");
      if (!name || !isBaseDof(dofName(name))) continue;
      use.named = true;
      use.kauthamNames |=
          isBaseDof(std::string(name).substr(std::string(name).find_last_of('/') + 1));
      use.offset[dofName(name)] = xml.requiredNumber(*d, "value");
    }
  for (const auto* c = root.FirstChildElement("Control"); c; c = c->NextSiblingElement("Control"))
    for (const auto* d = c->FirstChildElement("DOF"); d; d = d->NextSiblingElement("DOF")) {
      const char* name = d->Attribute("name");
      if (!name || !isBaseDof(dofName(name))) continue;
      use.named = true;
      use.kauthamNames |=
          isBaseDof(std::string(name).substr(std::string(name).find_last_of('/') + 1));
      if (d->DoubleAttribute("value", 0.0) != 0.0) use.moved.insert(dofName(name));
    }
  return use;
}

std::set<std::string> addMobileBase(KinematicModel& model, const std::vector<BaseAxisLimits>& axes,
                                    const Pose& home, const BaseDofUse* controls) {
  std::set<std::string> absorbed{"X", "Y", "Z", "X1", "X2", "X3"};
  if (controls && !controls->named) {
    if (!axes.empty())
      warning(axes.front().where.str() + ": the <Limits> are unused: the control set (" +
              controls->where.file.filename().string() +
              ") names none of the base's X, Y, Z, X1, X2, X3, so the base stays at <Home> "
              "(as in Kautham)");
    return {};
  }
  if (!controls && axes.empty()) return {};

  // Kautham's corners of the limits, from the world into the Home frame.
  Eigen::Vector3d minWorld = Eigen::Vector3d::Zero();
  Eigen::Vector3d maxWorld = Eigen::Vector3d::Zero();
  const BaseAxisLimits* byAxis[3] = {nullptr, nullptr, nullptr};
  for (const BaseAxisLimits& limits : axes) {
    const int i = limits.axis == "X" ? 0 : limits.axis == "Y" ? 1 : 2;
    byAxis[i] = &limits;
    minWorld[i] = limits.min;
    maxWorld[i] = limits.max;
  }
  const Eigen::Isometry3d toHome = home.isometry().inverse();
  const Eigen::Vector3d minHome = toHome * minWorld;
  const Eigen::Vector3d maxHome = toHome * maxWorld;

  // The chain in front of the URDF's root: translations, then the turn, then a fixed rotation.
  std::vector<Joint> joints;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(maxHome[i] - minHome[i]) < 1e-12) continue;  // pinned at Home
    Joint joint;
    joint.name = std::string("base_") + kAxisNames[i];
    joint.type = JointType::Prismatic;
    const bool increasing = minHome[i] < maxHome[i];
    joint.axis = (increasing ? 1.0 : -1.0) * Eigen::Vector3d::Unit(i);
    joint.lower = increasing ? minHome[i] : -minHome[i];
    joint.upper = increasing ? maxHome[i] : -maxHome[i];
    const BaseAxisLimits* limits = byAxis[i] ? byAxis[i] : &axes.front();
    joint.maxVelocity = limits->velocity;
    joint.maxEffort = limits->effort;
    joints.push_back(joint);
    absorbed.erase(kAxisNames[i]);
  }
  Eigen::Quaterniond fixedTurn = Eigen::Quaterniond::Identity();
  if (controls) {
    auto offset = [&](const char* name) {
      const auto it = controls->offset.find(name);
      return it == controls->offset.end() ? 0.5 : it->second;
    };
    for (const char* tilt : {"X1", "X2"})
      if (controls->moved.count(tilt))
        throw InputError(controls->where,
                         std::string("a control moves ") + tilt +
                             ", which tilts the base: only X3 (a turn about the base's z axis, "
                             "with X1's offset 0) is supported");
    if (controls->moved.count("X3")) {
      if (std::abs(offset("X1")) > 1e-12)
        throw InputError(controls->where,
                         "a control moves X3, the base's turn, but X1's offset is not 0, which "
                         "tilts it: give <DOF name=\"robot/X1\" value=\"0\"/> in <Offset>");
      Joint joint;
      joint.name = "base_X3";
      // Kautham's X3 in [0, 1] is a turn of 2 pi X3. ODE measures hinge angles in [-pi, pi]:
      // the joint turns from a frame already turned by pi, so its [-pi, pi] is Kautham's
      // [0, 2 pi] and it turns freely (continuous) through its ends.
      joint.type = JointType::Continuous;
      joint.axis = Eigen::Vector3d::UnitZ();
      joint.origin.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      joint.lower = -M_PI;
      joint.upper = M_PI;
      joint.maxVelocity = kTurnVelocity;
      joint.maxEffort = kTurnEffort;
      joints.push_back(joint);
      absorbed.erase("X3");
    } else if (controls->kauthamNames) {
      fixedTurn = kauthamRotation(offset("X1"), offset("X2"), offset("X3"));
    }
  }
  const bool turned = !fixedTurn.isApprox(Eigen::Quaterniond::Identity(), 1e-12);
  if (turned) {
    Joint joint;
    joint.name = "base_rotation";
    joint.type = JointType::Fixed;
    joint.origin.linear() = fixedTurn.toRotationMatrix();
    joints.push_back(joint);
  }
  if (joints.empty()) return absorbed;

  double carriageMass = 0.0;
  for (const Link& link : model.links) carriageMass += link.inertial.mass;
  carriageMass = std::max(carriageMass, kMinCarriageMass);
  const int count = static_cast<int>(joints.size());
  shiftIndices(model, count);
  // Links 0..count-1: the static mount, then one carriage per joint but the last, whose child is
  // the URDF's root. Joints 0..count-1 link them in that order.
  std::vector<Link> links(static_cast<std::size_t>(count));
  links[0].name = "mobile_base_mount";
  for (int i = 0; i < count; ++i) {
    Joint& joint = joints[static_cast<std::size_t>(i)];
    joint.parentLink = i;
    joint.childLink = i + 1 < count ? i + 1 : model.rootLink;
    links[static_cast<std::size_t>(i)].childJoints.push_back(i);
    if (i > 0) {
      Link& carriage = links[static_cast<std::size_t>(i)];
      carriage.name = "mobile_" + joints[static_cast<std::size_t>(i) - 1].name;
      carriage.parentJoint = i - 1;
      carriage.inertial.mass = carriageMass;
      // A carriage sits at the base's <Home>, which Kautham's demos may put far outside the
      // limits (the Sphere demos: Home at (10, 10), limits [-5, 5]), so it holds the robot 8
      // to 15 m away. With the inertia of a 10 cm radius of gyration, the solver's small
      // errors in the carriage's rotation (0.05 rad/s) swung the robot at that distance past
      // 1.2 times its speed limit across the joints' axes (3 % of the states of a tree of
      // random pushes).
      // A carriage turns as hard as its mass would at the middle of the robot's travel (the
      // parallel-axis inertia of that point; none is added about the line to it: an isotropic
      // m L^2 made the TX90's base, 0.5 m from its travel's middle, break the link speed rule
      // while tracking PRM's paths).
      const Eigen::Vector3d lever = middleOfTravel(joints, i);
      carriage.inertial.inertia =
          carriageMass * (Eigen::Matrix3d::Identity() * (kCarriageGyration + lever.squaredNorm()) -
                          lever * lever.transpose());
    }
  }
  model.links[static_cast<std::size_t>(model.rootLink - count)].parentJoint = count - 1;
  model.links.insert(model.links.begin(), links.begin(), links.end());
  model.joints.insert(model.joints.begin(), joints.begin(), joints.end());
  model.rootLink = 0;
  return absorbed;
}

}  // namespace kautham::core
