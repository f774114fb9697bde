#include "kautham/core/UrdfLoader.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <sstream>

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include "XmlReader.h"
#include "kautham/core/Log.h"
#include "kautham/core/MeshLoader.h"
#include "kautham/core/PackagePaths.h"

namespace kautham::core {

namespace {

/// Largest |lower| or |upper| of a revolute or prismatic joint (rad or m, as the URDF writes
/// it): far beyond any real joint, still small enough for the physics to step.
constexpr double kMaxJointLimit = 1000.0;

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
      model.links.push_back(convertLink(*urdf_.getLink(e->Attribute("name")), *e));
    reportMissingMeshes();
    for (auto* e = robot_.FirstChildElement("joint"); e; e = e->NextSiblingElement("joint"))
      model.joints.push_back(convertJoint(*urdf_.getJoint(e->Attribute("name")), model));
    for (std::size_t j = 0; j < model.joints.size(); ++j) {
      model.links[model.joints[j].parentLink].childJoints.push_back(static_cast<int>(j));
      model.links[model.joints[j].childLink].parentJoint = static_cast<int>(j);
    }
    model.rootLink = *model.findLink(urdf_.getRoot()->name);
    requireConnected(model);
    return model;
  }

 private:
  [[noreturn]] void fail(const char* tag, const std::string& name, const std::string& msg) const {
    throw InputError({xml_.file(), lineOf(robot_, tag, name)}, msg);
  }

  /// Every link hangs from the root through its parent joints. urdfdom accepts joints that
  /// close a loop away from the root (its root is merely the one link without a parent), and
  /// the physics cannot build such a chain: name the loop instead.
  void requireConnected(const KinematicModel& model) const {
    std::vector<bool> reached(model.links.size(), false);
    std::vector<int> pending{model.rootLink};
    while (!pending.empty()) {
      const int link = pending.back();
      pending.pop_back();
      if (reached[link]) continue;
      reached[link] = true;
      for (int j : model.links[link].childJoints) pending.push_back(model.joints[j].childLink);
    }
    for (std::size_t l = 0; l < model.links.size(); ++l) {
      if (reached[l]) continue;
      // Follow the parents from the link not reached: they come round to a link seen before.
      std::vector<int> chain{static_cast<int>(l)};
      std::vector<bool> seen(model.links.size(), false);
      seen[l] = true;
      int joint = model.links[l].parentJoint;
      while (joint >= 0 && !seen[model.joints[joint].parentLink]) {
        chain.push_back(model.joints[joint].parentLink);
        seen[chain.back()] = true;
        joint = model.links[chain.back()].parentJoint;
      }
      if (joint < 0)  // urdfdom refuses a second link without a parent; kept as a guard
        fail("link", model.links[chain.back()].name,
             "link '" + model.links[chain.back()].name +
                 "' has no parent joint and is not the root link '" +
                 model.links[model.rootLink].name + "'");
      // The loop, parent to child, from the link the parents came round to.
      const int repeated = model.joints[joint].parentLink;
      std::string loop = model.links[repeated].name;
      for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
        loop += " -> " + model.links[*it].name;
        if (*it == repeated) break;
      }
      fail("joint", model.joints[joint].name,
           "joint '" + model.joints[joint].name + "': the links " + loop +
               " form a loop, not connected to the root link '" + model.links[model.rootLink].name +
               "'; every link but the root needs one parent joint, and its parents must lead "
               "to the root");
    }
  }

  /// Every mesh that could not be found, in one message: a user fixes the paths at once.
  void reportMissingMeshes() const {
    if (missing_.empty()) return;
    std::string list;
    for (const std::string& m : missing_) list += "\n  " + m;
    throw InputError({xml_.file(), missingLine_}, std::to_string(missing_.size()) + " mesh file" +
                                                      (missing_.size() == 1 ? "" : "s") +
                                                      " not found:" + list);
  }

  /// urdfdom leaves out what it cannot read (a <collision> whose <geometry> it does not know,
  /// say) without failing: compare with the file, so no collision shape is lost silently.
  void checkNothingDropped(const urdf::Link& source, const tinyxml2::XMLElement& element) const {
    static constexpr const char* kCollisionNeeds =
        " <collision> elements; each needs a <geometry> with one <box>, <cylinder>, <sphere> or "
        "<mesh filename=..>";
    int written = 0;
    const tinyxml2::XMLElement* firstMissing = nullptr;
    for (auto* c = element.FirstChildElement("collision"); c;
         c = c->NextSiblingElement("collision")) {
      ++written;
      if (!c->FirstChildElement("geometry") && !firstMissing) firstMissing = c;
    }
    int read = 0;
    for (const auto& collision : source.collision_array) read += collision && collision->geometry;
    if (read == written) return;
    // urdfdom's own complaint comes first when it has one (a mass that is not a number drops
    // the link's collisions too): that is what to fix.
    if (!urdfMessages_.empty())
      throw InputError({xml_.file(), element.GetLineNum()},
                       "link '" + source.name + "': urdfdom could not read it: " + urdfMessages_ +
                           " (so it read " + std::to_string(read) + " of its " +
                           std::to_string(written) + kCollisionNeeds + ")");
    const int line = firstMissing ? firstMissing->GetLineNum() : element.GetLineNum();
    throw InputError({xml_.file(), line}, "link '" + source.name + "': urdfdom read " +
                                              std::to_string(read) + " of its " +
                                              std::to_string(written) + kCollisionNeeds);
  }

  /// The link's <mass value> and <inertia> attributes, as written, are finite numbers: depending
  /// on how it is called, urdfdom keeps an infinite inertia (which ODE integrates into nonsense)
  /// or drops the whole <inertial> and reports the link's collisions as what it could not read.
  void requireFiniteInertial(const std::string& link, const tinyxml2::XMLElement& element) const {
    const tinyxml2::XMLElement* inertial = element.FirstChildElement("inertial");
    if (!inertial) return;
    const auto check = [&](const tinyxml2::XMLElement* e, const char* attribute) {
      double value = 0.0;
      if (e && e->QueryDoubleAttribute(attribute, &value) == tinyxml2::XML_SUCCESS &&
          !std::isfinite(value))
        throw InputError({xml_.file(), e->GetLineNum()},
                         "link '" + link + "': <" + e->Name() + "> " + attribute + "=\"" +
                             e->Attribute(attribute) + "\" must be a finite number");
    };
    check(inertial->FirstChildElement("mass"), "value");
    for (const char* attribute : {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"})
      check(inertial->FirstChildElement("inertia"), attribute);
  }

  Link convertLink(const urdf::Link& source, const tinyxml2::XMLElement& element) {
    // Before urdfdom's own account: it drops an inertial it cannot read, and what it then says
    // it dropped is the link's collisions.
    requireFiniteInertial(source.name, element);
    checkNothingDropped(source, element);
    Link link;
    link.name = source.name;
    if (source.inertial) {
      const urdf::Inertial& in = *source.inertial;
      if (!(in.mass >= 0.0)) fail("link", source.name, "link '" + source.name + "': negative mass");
      link.inertial.mass = in.mass;
      const auto* inertial = element.FirstChildElement("inertial");
      const auto* mass = inertial ? inertial->FirstChildElement("mass") : nullptr;
      link.inertial.massLine = (mass ? mass : &element)->GetLineNum();
      link.inertial.origin = toIsometry(in.origin, scale_);
      link.inertial.inertia << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz,
          in.izz;
      link.inertial.inertia *= scale_ * scale_;
    }
    for (std::size_t c = 0; c < source.collision_array.size(); ++c)
      if (const auto& collision = source.collision_array[c]; collision && collision->geometry)
        link.collisions.push_back({convertShape(*collision->geometry, source.name, c),
                                   toIsometry(collision->origin, scale_)});
    link.visuals = convertVisuals(source);
    return link;
  }

  /// The link's <visual>s, for pictures. A visual mesh that cannot be found costs a warning, not
  /// the problem: the viewer then draws the link's collision shapes instead (all of them, so a
  /// link is never half drawn).
  std::vector<VisualShape> convertVisuals(const urdf::Link& source) const {
    std::vector<VisualShape> visuals;
    for (std::size_t v = 0; v < source.visual_array.size(); ++v) {
      const auto& visual = source.visual_array[v];
      if (!visual || !visual->geometry) continue;
      std::optional<VisualShape> shape = convertVisual(*visual, source.name, v);
      if (!shape) return {};
      visuals.push_back(std::move(*shape));
    }
    return visuals;
  }

  std::optional<VisualShape> convertVisual(const urdf::Visual& visual, const std::string& linkName,
                                           std::size_t index) const {
    VisualShape shape;
    shape.origin = toIsometry(visual.origin, scale_);
    // urdfdom cannot tell a material without <color> from black: that default is no colour.
    if (const auto& m = visual.material; m && (m->color.r || m->color.g || m->color.b))
      shape.colour = Eigen::Vector4d(m->color.r, m->color.g, m->color.b, m->color.a);
    const urdf::Geometry& g = *visual.geometry;
    switch (g.type) {
      case urdf::Geometry::BOX: {
        const urdf::Vector3& d = static_cast<const urdf::Box&>(g).dim;
        shape.geometry = Box{scale_ * Eigen::Vector3d(d.x, d.y, d.z)};
        return shape;
      }
      case urdf::Geometry::CYLINDER: {
        const auto& c = static_cast<const urdf::Cylinder&>(g);
        shape.geometry = Cylinder{scale_ * c.radius, scale_ * c.length};
        return shape;
      }
      case urdf::Geometry::SPHERE:
        shape.geometry = Sphere{scale_ * static_cast<const urdf::Sphere&>(g).radius};
        return shape;
      case urdf::Geometry::MESH:
        if (std::optional<MeshFile> file =
                visualMesh(static_cast<const urdf::Mesh&>(g), linkName, index)) {
          shape.geometry = std::move(*file);
          return shape;
        }
        return std::nullopt;
    }
    return std::nullopt;
  }

  std::optional<MeshFile> visualMesh(const urdf::Mesh& mesh, const std::string& linkName,
                                     std::size_t index) const {
    const SourceLocation where{xml_.file(), meshLine(linkName, "visual", index)};
    const std::string prefix = "link '" + linkName + "': visual mesh '" + mesh.filename + "'";
    std::string looked;
    std::filesystem::path path;
    try {
      path = resolveMesh(mesh.filename, where, prefix, looked);
    } catch (const InputError& e) {
      looked = e.what();
    }
    if (path.empty()) {
      warning(where.file.string() + ":" + std::to_string(where.line) + ": " + prefix + ": " +
              looked + "; pictures show the link's collision shapes");
      return std::nullopt;
    }
    return MeshFile{path, scale_ * Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z)};
  }

  Shape convertShape(const urdf::Geometry& geometry, const std::string& linkName,
                     std::size_t collisionIndex) {
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

  /// Line of the <mesh> element of the link's index-th <collision> or <visual> (`tag`), else the
  /// link's line.
  int meshLine(const std::string& linkName, const char* tag, std::size_t index) const {
    for (auto* link = robot_.FirstChildElement("link"); link;
         link = link->NextSiblingElement("link")) {
      if (const char* n = link->Attribute("name"); !n || linkName != n) continue;
      auto* element = link->FirstChildElement(tag);
      for (std::size_t i = 0; element && i < index; ++i) element = element->NextSiblingElement(tag);
      const auto* geometry = element ? element->FirstChildElement("geometry") : nullptr;
      const auto* mesh = geometry ? geometry->FirstChildElement("mesh") : nullptr;
      return mesh ? mesh->GetLineNum() : link->GetLineNum();
    }
    return 0;
  }

  /// The file a mesh's filename names: relative to the URDF's folder, `file://` or
  /// `package://NAME/..` (PackagePaths.h). Empty when it cannot be found; `looked` says where.
  std::filesystem::path resolveMesh(const std::string& name, const SourceLocation& where,
                                    const std::string& prefix, std::string& looked) const {
    std::filesystem::path path;
    if (name.rfind("package://", 0) == 0) {
      const std::string rest = name.substr(10);
      const auto slash = rest.find('/');
      const std::string package = rest.substr(0, slash);
      if (package.empty() || slash == std::string::npos)
        throw InputError(where, prefix + ": a package:// path is package://NAME/path/in/package");
      const auto root = findPackage(package, xml_.file());
      if (!root) {
        looked = "package '" + package + "' not found (give --package-path " + package +
                 "=DIR, add its parent folder to ROS_PACKAGE_PATH, or keep the URDF inside the "
                 "package, whose package.xml names it)";
        return {};
      }
      path = *root / rest.substr(slash + 1);
    } else if (name.rfind("file://", 0) == 0) {
      path = name.substr(7);
    } else if (name.find("://") != std::string::npos) {
      throw InputError(where,
                       prefix + ": only plain file paths, file:// and package:// are supported");
    } else {
      path = name;
    }
    if (path.empty()) throw InputError(where, prefix + ": mesh without a filename");
    if (path.is_relative()) path = folder_ / path;
    std::error_code ignored;
    if (!std::filesystem::is_regular_file(path, ignored)) {
      looked = "file not found (looked for '" + path.string() + "')";
      return {};
    }
    return path;
  }

  /// A mesh file, found relative to the URDF's folder (or through package://), scaled, with its
  /// convex hull. A mesh that is not found is recorded, and all are reported together.
  Shape convertMesh(const urdf::Mesh& source, const std::string& linkName,
                    std::size_t collisionIndex) {
    const SourceLocation where{xml_.file(), meshLine(linkName, "collision", collisionIndex)};
    const std::string& name = source.filename;
    const std::string prefix = "link '" + linkName + "': mesh '" + name + "'";
    std::string looked;
    const std::filesystem::path path = resolveMesh(name, where, prefix, looked);
    if (path.empty()) {
      if (missing_.empty()) missingLine_ = where.line;
      missing_.push_back("line " + std::to_string(where.line) + ": " + prefix + ": " + looked);
      return Sphere{0.0};  // never used: reportMissingMeshes() throws before the model is
    }
    const Eigen::Vector3d scale =
        scale_ * Eigen::Vector3d(source.scale.x, source.scale.y, source.scale.z);
    if (!(scale.array() != 0.0).all() || !scale.allFinite())
      throw InputError(where, prefix +
                                  ": scale must be three non-zero numbers (a negative one "
                                  "mirrors the mesh along that axis)");

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
    if (source.mimic) {
      const double lengthScale = joint.type == JointType::Prismatic ? scale_ : 1.0;
      joint.mimic = Joint::Mimic{source.mimic->joint_name, source.mimic->multiplier,
                                 source.mimic->offset * lengthScale};
      if (!urdf_.getJoint(joint.mimic->joint))
        fail("joint", source.name,
             "joint '" + source.name + "' mimics '" + joint.mimic->joint +
                 "', which is no joint of this robot");
    }
    return joint;
  }

  void readLimits(const urdf::Joint& source, Joint& joint) const {
    // URDF lets a continuous joint (a wheel) go without <limit>; its motor needs some.
    if (joint.type == JointType::Continuous &&
        (!source.limits || (source.limits->velocity == 0.0 && source.limits->effort == 0.0))) {
      constexpr double kVelocity = 1.0;  // rad/s
      constexpr double kEffort = 10.0;   // N m
      warning(xml_.file().string() + ":" + std::to_string(lineOf(robot_, "joint", source.name)) +
              ": continuous joint '" + source.name +
              "' has no <limit velocity effort>; its motor uses 1 rad/s and 10 N m");
      joint.maxVelocity = kVelocity;
      joint.maxEffort = kEffort;
      joint.lower = -M_PI;
      joint.upper = M_PI;
      return;
    }
    if (!source.limits || !(source.limits->velocity > 0.0) || !(source.limits->effort > 0.0) ||
        !std::isfinite(source.limits->velocity) || !std::isfinite(source.limits->effort))
      fail("joint", source.name,
           "joint '" + source.name +
               "' needs <limit velocity=\"..\" effort=\"..\"/> with positive finite values: "
               "the planner's controls are joint velocities driven by motors of that effort");
    const double lengthScale = joint.type == JointType::Prismatic ? scale_ : 1.0;
    joint.maxVelocity = source.limits->velocity * lengthScale;
    joint.maxEffort = source.limits->effort;
    if (joint.type == JointType::Continuous) {
      joint.lower = -M_PI;
      joint.upper = M_PI;
      return;
    }
    requireSaneRange(source);
    joint.lower = source.limits->lower * lengthScale;
    joint.upper = source.limits->upper * lengthScale;
    if (!(joint.lower < joint.upper))
      fail("joint", source.name, "joint '" + source.name + "': <limit> needs lower < upper");
  }

  /// A range such as [-1e300, 1e300] maps the planner's [0, 1] joint values onto numbers no
  /// motor can reach: every propagated state diverges. No real joint comes near the bound.
  void requireSaneRange(const urdf::Joint& source) const {
    const double lower = source.limits->lower;
    const double upper = source.limits->upper;
    if (std::abs(lower) <= kMaxJointLimit && std::abs(upper) <= kMaxJointLimit) return;
    std::ostringstream message;
    message << "joint '" << source.name << "': <limit lower=\"" << lower << "\" upper=\"" << upper
            << "\"> is beyond +-" << kMaxJointLimit << " (rad or m); give the joint's real range"
            << (source.type == urdf::Joint::REVOLUTE
                    ? ", or make it type=\"continuous\" if it turns without end"
                    : "");
    fail("joint", source.name, message.str());
  }

  const XmlReader& xml_;
  const urdf::ModelInterface& urdf_;
  double scale_;
  const tinyxml2::XMLElement& robot_;
  std::filesystem::path folder_;      ///< mesh paths are relative to it
  std::vector<std::string> missing_;  ///< meshes not found, one line each
  int missingLine_ = 0;

 public:
  std::string urdfMessages_;  ///< what urdfdom said while parsing, for error messages
};

/// urdfdom's messages, kept instead of printed: errors for our message, warnings to the log.
class UrdfMessages : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) {
      if (!errors.empty()) errors += "; ";
      errors += text;
    } else if (level == console_bridge::CONSOLE_BRIDGE_LOG_WARN) {
      warnings.push_back(text);
    }
  }
  std::string errors;
  std::vector<std::string> warnings;
};

// console_bridge's handler and level are global: one URDF at a time.
std::mutex urdfdomMutex;

/// The URDF as urdfdom should read it. urdfdom gives up on a <visual> whose <material> has no
/// name (Kautham's URDFs, exported from its GUI, have many) and, with it, on the link's
/// <collision>: such materials get a name of their own. Returns how many were named.
int nameAnonymousMaterials(tinyxml2::XMLDocument& document) {
  int named = 0;
  std::vector<tinyxml2::XMLElement*> pending;
  if (auto* root = document.RootElement()) pending.push_back(root);
  while (!pending.empty()) {
    tinyxml2::XMLElement* e = pending.back();
    pending.pop_back();
    if (std::strcmp(e->Name(), "material") == 0 && !e->Attribute("name"))
      e->SetAttribute("name", ("kautham_unnamed_material_" + std::to_string(++named)).c_str());
    for (auto* child = e->FirstChildElement(); child; child = child->NextSiblingElement())
      pending.push_back(child);
  }
  return named;
}

/// Kautham reads numbers with strtod, so `ixx="0.46\n 5"` (a line break inside a number, as in
/// Kautham's own Tiago) is 0.46 there, and urdfdom drops the whole link. Read the leading number
/// as Kautham does, and say so.
void repairInertialNumbers(tinyxml2::XMLDocument& document, const std::filesystem::path& file) {
  auto* robot = document.RootElement();
  if (!robot) return;
  for (auto* link = robot->FirstChildElement("link"); link;
       link = link->NextSiblingElement("link")) {
    auto* inertial = link->FirstChildElement("inertial");
    if (!inertial) continue;
    for (auto* e = inertial->FirstChildElement(); e; e = e->NextSiblingElement()) {
      for (const char* name : {"value", "ixx", "ixy", "ixz", "iyy", "iyz", "izz"}) {
        const char* text = e->Attribute(name);
        if (!text) continue;
        char* end = nullptr;
        const double value = std::strtod(text, &end);
        if (end == text) continue;  // not a number at all: urdfdom's error names it
        std::string rest(end);
        if (rest.find_first_not_of(" \t\r\n") == std::string::npos) continue;
        std::ostringstream repaired;
        repaired.precision(15);
        repaired << value;
        warning(file.string() + ":" + std::to_string(e->GetLineNum()) + ": <" + e->Name() + " " +
                name + "=\"" + text + "\"> is not one number; read as " + repaired.str() +
                ", as Kautham does (fix the file to silence this)");
        e->SetAttribute(name, repaired.str().c_str());
      }
    }
  }
}

bool endsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

KinematicModel loadUrdf(const std::filesystem::path& urdfFile, double scale,
                        const SourceLocation& requestedBy) {
  if (!(scale > 0.0) || !std::isfinite(scale))
    throw InputError(requestedBy, "scale must be a positive number");
  std::error_code ignored;
  if (!std::filesystem::is_regular_file(urdfFile, ignored))
    throw InputError(requestedBy, "model file '" + urdfFile.string() + "' not found");
  if (endsWith(urdfFile.string(), ".xacro"))
    throw InputError(requestedBy,
                     "'" + urdfFile.filename().string() +
                         "' is a xacro macro file, not a URDF: expand it first, e.g. `xacro " +
                         urdfFile.filename().string() +
                         " > robot.urdf` (ROS's xacro tool; "
                         "pass the macro's arguments as name:=value), and load robot.urdf");
  const XmlReader xml(urdfFile);  // reports XML syntax errors with their line
  xml.root("robot");

  tinyxml2::XMLDocument document;
  document.LoadFile(urdfFile.string().c_str());
  nameAnonymousMaterials(document);
  repairInertialNumbers(document, urdfFile);
  tinyxml2::XMLPrinter printer;
  document.Print(&printer);

  UrdfMessages messages;
  urdf::ModelInterfaceSharedPtr urdf;
  {
    std::lock_guard<std::mutex> lock(urdfdomMutex);
    console_bridge::useOutputHandler(&messages);
    console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_WARN);
    urdf = urdf::parseURDF(printer.CStr());
    console_bridge::restorePreviousOutputHandler();
    console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
  }
  for (const std::string& w : messages.warnings)
    if (w.find("material") == std::string::npos)  // visual colours only: not our concern
      warnOnce(urdfFile.string() + "\n" + w, urdfFile.string() + ": urdfdom: " + w);
  if (!urdf)
    throw InputError(
        {urdfFile, 0},
        "not a valid URDF (urdfdom: " +
            (messages.errors.empty() ? std::string("no reason given") : messages.errors) +
            "; check link and joint names, that every joint has a parent and a "
            "child, and that there is exactly one root link)");
  UrdfConverter converter(xml, *urdf, scale);
  converter.urdfMessages_ = messages.errors;
  return converter.convert();
}

}  // namespace kautham::core
