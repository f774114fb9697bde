#include "kautham/core/UrdfLoader.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include "XmlReader.h"
#include "kautham/core/MeshLoader.h"

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
      : xml_(xml),
        urdf_(urdf),
        scale_(scale),
        robot_(xml.root("robot")),
        folder_(xml.file().parent_path()) {}

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
    for (std::size_t c = 0; c < source.collision_array.size(); ++c)
      if (const auto& collision = source.collision_array[c]; collision && collision->geometry)
        link.collisions.push_back({convertShape(*collision->geometry, source.name, c),
                                   toIsometry(collision->origin, scale_)});
    return link;
  }

  Shape convertShape(const urdf::Geometry& geometry, const std::string& linkName,
                     std::size_t collisionIndex) const {
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
        return convertMesh(static_cast<const urdf::Mesh&>(geometry), linkName, collisionIndex);
    }
    fail("link", linkName, "link '" + linkName + "': unknown collision geometry");
  }

  /// Line of the <mesh> element of the link's collisionIndex-th <collision> (else the link's).
  int meshLine(const std::string& linkName, std::size_t collisionIndex) const {
    for (auto* link = robot_.FirstChildElement("link"); link;
         link = link->NextSiblingElement("link")) {
      if (const char* n = link->Attribute("name"); !n || linkName != n) continue;
      auto* collision = link->FirstChildElement("collision");
      for (std::size_t i = 0; collision && i < collisionIndex; ++i)
        collision = collision->NextSiblingElement("collision");
      const auto* geometry = collision ? collision->FirstChildElement("geometry") : nullptr;
      const auto* mesh = geometry ? geometry->FirstChildElement("mesh") : nullptr;
      return mesh ? mesh->GetLineNum() : link->GetLineNum();
    }
    return 0;
  }

  /// A mesh file, found relative to the URDF's folder, scaled, with its convex hull.
  Shape convertMesh(const urdf::Mesh& source, const std::string& linkName,
                    std::size_t collisionIndex) const {
    const SourceLocation where{xml_.file(), meshLine(linkName, collisionIndex)};
    const std::string& name = source.filename;
    const std::string prefix = "link '" + linkName + "': mesh '" + name + "'";
    if (name.rfind("package://", 0) == 0)
      throw InputError(where, prefix +
                                  ": package:// paths need ROS to resolve; write the path "
                                  "relative to the URDF's folder instead (e.g. meshes/x.stl)");
    std::filesystem::path path = name.rfind("file://", 0) == 0 ? name.substr(7) : name;
    if (name.find("://") != std::string::npos && name.rfind("file://", 0) != 0)
      throw InputError(where, prefix +
                                  ": only plain file paths are supported, relative to the "
                                  "URDF's folder");
    if (path.empty()) throw InputError(where, "link '" + linkName + "': mesh without a filename");
    if (path.is_relative()) path = folder_ / path;
    std::error_code ignored;
    if (!std::filesystem::is_regular_file(path, ignored))
      throw InputError(where, prefix + ": file not found (looked for '" + path.string() + "')");
    const Eigen::Vector3d scale =
        scale_ * Eigen::Vector3d(source.scale.x, source.scale.y, source.scale.z);
    if (!(scale.array() > 0.0).all() || !scale.allFinite())
      throw InputError(where, prefix + ": scale must be three positive numbers");

    auto data = std::make_shared<Mesh::Data>();
    data->source = path;
    try {
      TriangleMesh mesh = loadMesh(path, scale);
      data->vertices = std::move(mesh.vertices);
      data->triangles = std::move(mesh.triangles);
      data->hull = convexHull(data->vertices);
    } catch (const MeshError& e) {
      throw InputError(where, prefix + ": " + e.what());
    } catch (const DegenerateHullError& e) {
      throw InputError(where,
                       prefix + " has no volume, so it cannot be a collision body: " + e.what());
    }
    return Mesh{std::move(data)};
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
  std::filesystem::path folder_;  ///< mesh paths are relative to it
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
