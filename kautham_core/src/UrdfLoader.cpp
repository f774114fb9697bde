#include "kautham/core/UrdfLoader.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include "XmlReader.h"

namespace kautham::core {

namespace {

Eigen::Isometry3d toIsometry(const urdf::Pose& pose, double scale) {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  const urdf::Rotation& r = pose.rotation;
  transform.linear() = Eigen::Quaterniond(r.w, r.x, r.y, r.z).normalized().toRotationMatrix();
  transform.translation() =
      scale * Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return transform;
}

/// Line of the <link> or <joint> element with the given name, for error messages.
int lineOf(const tinyxml2::XMLElement& robot, const char* tag, const std::string& name) {
  for (auto* e = robot.FirstChildElement(tag); e; e = e->NextSiblingElement(tag))
    if (const char* n = e->Attribute("name"); n && name == n) return e->GetLineNum();
  return 0;
}

class UrdfConverter {
 public:
  UrdfConverter(const XmlReader& xml, const urdf::ModelInterface& urdf, double scale)
      : xml_(xml), urdf_(urdf), scale_(scale), robot_(xml.root("robot")) {}

  KinematicModel convert() {
    KinematicModel model;
    model.name = urdf_.getName();
    // Keep the file's order of links and joints: it is what a user reads, and it fixes the
    // order of the degrees of freedom.
    for (auto* e = robot_.FirstChildElement("link"); e; e = e->NextSiblingElement("link"))
      model.links.push_back(convertLink(*urdf_.getLink(e->Attribute("name"))));
    for (auto* e = robot_.FirstChildElement("joint"); e; e = e->NextSiblingElement("joint"))
      model.joints.push_back(convertJoint(*urdf_.getJoint(e->Attribute("name")), model));
    for (std::size_t j = 0; j < model.joints.size(); ++j) {
      model.links[model.joints[j].parentLink].childJoints.push_back(static_cast<int>(j));
      model.links[model.joints[j].childLink].parentJoint = static_cast<int>(j);
    }
    model.rootLink = *model.findLink(urdf_.getRoot()->name);
    return model;
  }

 private:
  [[noreturn]] void fail(const char* tag, const std::string& name, const std::string& msg) const {
    throw InputError({xml_.file(), lineOf(robot_, tag, name)}, msg);
  }

  Link convertLink(const urdf::Link& source) const {
    Link link;
    link.name = source.name;
    if (source.inertial) {
      const urdf::Inertial& in = *source.inertial;
      if (!(in.mass >= 0.0)) fail("link", source.name, "link '" + source.name + "': negative mass");
      link.inertial.mass = in.mass;
      link.inertial.origin = toIsometry(in.origin, scale_);
      link.inertial.inertia << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz,
          in.izz;
      link.inertial.inertia *= scale_ * scale_;
    }
    for (const auto& collision : source.collision_array)
      if (collision && collision->geometry)
        link.collisions.push_back({convertShape(*collision->geometry, source.name),
                                   toIsometry(collision->origin, scale_)});
    return link;
  }

  Shape convertShape(const urdf::Geometry& geometry, const std::string& linkName) const {
    switch (geometry.type) {
      case urdf::Geometry::BOX: {
        const auto& box = static_cast<const urdf::Box&>(geometry);
        return requirePositive(Box{scale_ * Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z)},
                               linkName);
      }
      case urdf::Geometry::CYLINDER: {
        const auto& c = static_cast<const urdf::Cylinder&>(geometry);
        return requirePositive(Cylinder{scale_ * c.radius, scale_ * c.length}, linkName);
      }
      case urdf::Geometry::SPHERE:
        return requirePositive(Sphere{scale_ * static_cast<const urdf::Sphere&>(geometry).radius},
                               linkName);
      case urdf::Geometry::MESH:
        break;
    }
    fail("link", linkName,
         "link '" + linkName +
             "': mesh collision geometry is not supported yet; use box, cylinder or sphere");
  }

  template <typename S>
  Shape requirePositive(const S& shape, const std::string& linkName) const {
    const Eigen::AlignedBox3d box = boundingBox(shape, Eigen::Isometry3d::Identity());
    if (!((box.sizes().array() > 0.0).all()))
      fail("link", linkName, "link '" + linkName + "': collision geometry needs positive sizes");
    return shape;
  }

  Joint convertJoint(const urdf::Joint& source, const KinematicModel& model) const {
    Joint joint;
    joint.name = source.name;
    joint.parentLink = *model.findLink(source.parent_link_name);
    joint.childLink = *model.findLink(source.child_link_name);
    joint.origin = toIsometry(source.parent_to_joint_origin_transform, 1.0);
    joint.origin.translation() *= scale_;
    joint.axis = Eigen::Vector3d(source.axis.x, source.axis.y, source.axis.z);
    switch (source.type) {
      case urdf::Joint::FIXED:
        joint.type = JointType::Fixed;
        return joint;
      case urdf::Joint::REVOLUTE:
        joint.type = JointType::Revolute;
        break;
      case urdf::Joint::CONTINUOUS:
        joint.type = JointType::Continuous;
        break;
      case urdf::Joint::PRISMATIC:
        joint.type = JointType::Prismatic;
        break;
      default:
        fail("joint", source.name,
             "joint '" + source.name +
                 "': only fixed, revolute, continuous and prismatic joints are supported");
    }
    if (joint.axis.norm() < 1e-9)
      fail("joint", source.name, "joint '" + source.name + "': the axis must not be zero");
    joint.axis.normalize();
    readLimits(source, joint);
    return joint;
  }

  void readLimits(const urdf::Joint& source, Joint& joint) const {
    if (!source.limits || !(source.limits->velocity > 0.0) || !(source.limits->effort > 0.0))
      fail("joint", source.name,
           "joint '" + source.name +
               "' needs <limit velocity=\"..\" effort=\"..\"/> with positive values: the "
               "planner's controls are joint velocities driven by motors of that effort");
    const double lengthScale = joint.type == JointType::Prismatic ? scale_ : 1.0;
    joint.maxVelocity = source.limits->velocity * lengthScale;
    joint.maxEffort = source.limits->effort;
    if (joint.type == JointType::Continuous) {
      joint.lower = -M_PI;
      joint.upper = M_PI;
      return;
    }
    joint.lower = source.limits->lower * lengthScale;
    joint.upper = source.limits->upper * lengthScale;
    if (!(joint.lower < joint.upper))
      fail("joint", source.name, "joint '" + source.name + "': <limit> needs lower < upper");
  }

  const XmlReader& xml_;
  const urdf::ModelInterface& urdf_;
  double scale_;
  const tinyxml2::XMLElement& robot_;
};

std::string readWholeFile(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

KinematicModel loadUrdf(const std::filesystem::path& urdfFile, double scale,
                        const SourceLocation& requestedBy) {
  if (!(scale > 0.0) || !std::isfinite(scale))
    throw InputError(requestedBy, "scale must be a positive number");
  std::error_code ignored;
  if (!std::filesystem::is_regular_file(urdfFile, ignored))
    throw InputError(requestedBy, "model file '" + urdfFile.string() + "' not found");
  const XmlReader xml(urdfFile);  // reports XML syntax errors with their line
  xml.root("robot");

  // urdfdom reports its errors on the console; ours carry the file name instead.
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
  const urdf::ModelInterfaceSharedPtr urdf = urdf::parseURDF(readWholeFile(urdfFile));
  if (!urdf)
    throw InputError({urdfFile, 0},
                     "not a valid URDF (urdfdom rejected it: check link and joint names, that "
                     "every joint has a parent and a child, and that there is exactly one root "
                     "link; `check_urdf` from liburdfdom-tools prints the details)");
  return UrdfConverter(xml, *urdf, scale).convert();
}

}  // namespace kautham::core
