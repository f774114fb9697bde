#include "kautham/core/ProblemLoader.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include "FinalLinkGoal.h"
#include "LinkInertia.h"
#include "MobileBase.h"
#include "XmlReader.h"
#include "kautham/core/Log.h"
#include "kautham/core/OctomapEnvironment.h"
#include "kautham/core/PhysicsOverrides.h"
#include "kautham/core/SoftContact.h"
#include "kautham/core/UrdfLoader.h"

namespace kautham::core {

namespace {

using tinyxml2::XMLElement;
namespace fs = std::filesystem;

/// Names for a message about a name that is not among them: all of a few, the first ten of
/// many (a robot with hands has dozens of links), so the message stays readable.
std::string someNames(const std::vector<std::string>& names) {
  constexpr std::size_t kShown = 10;
  std::string list;
  for (std::size_t i = 0; i < names.size() && i < kShown; ++i)
    list += (i == 0 ? "" : ", ") + names[i];
  if (names.size() > kShown) list += " and " + std::to_string(names.size() - kShown) + " more";
  return names.empty() ? "none" : list;
}

/// Kautham's physics parameter names, accepted inside <Parameters> for compatibility:
/// they set the <Physics> block rather than the planner, with the same checks.
bool applyKauthamPhysicsParameter(const PlannerParameter& p, PhysicsSettings& physics,
                                  const XmlReader& xml, const XMLElement& element) {
  auto number = [&](double min, double max, const char* range) {
    const std::vector<double> values = xml.numbersInText(element);
    if (values.size() != 1 || values[0] < min || values[0] > max)
      xml.fail(element, "parameter '" + p.name + "' must be one number in " + range + ", got '" +
                            p.value + "'");
    return values[0];
  };
  if (p.name == "Max Contacts") {
    const double value = number(1, 64, "[1, 64]");
    if (value != std::floor(value))
      xml.fail(element, "parameter 'Max Contacts' must be a whole number, got '" + p.value + "'");
    physics.maxContacts = static_cast<int>(value);
  } else if (p.name == "Error Reduction Parameter") {
    physics.erp = number(0, 1, "[0, 1]");
  } else if (p.name == "Constraint Force Mixing") {
    physics.cfm = number(0, std::numeric_limits<double>::infinity(), "[0, inf)");
  } else {
    return false;
  }
  return true;
}

/// Kautham planners that do not simulate physics: its geometric OMPL planners (omplRRT,
/// omplPRM, ...) and its kinematic control planners (omplcRRT...). Its ODE planners (omplODE...,
/// ...KPIECE2DPlanner, ...ChainPlanner) and ours simulate.
bool isKauthamKinematicPlanner(const std::string& name) {
  return name.rfind("ompl", 0) == 0 && name.rfind("omplODE", 0) != 0;
}

class ProblemReader {
 public:
  ProblemReader(const fs::path& file, std::vector<fs::path> modelDirs)
      : xml_(file), modelDirs_(std::move(modelDirs)) {
    const fs::path folder = fs::absolute(file).parent_path();
    // The problem's folder, this repository's layout (problems/ beside models/), Kautham's
    // layout (demos/<set>/ two levels under models/), then the user's folders.
    modelDirs_.insert(modelDirs_.begin(), {folder, folder.parent_path() / "models",
                                           folder.parent_path().parent_path() / "models"});
    // Near the root the layouts name the same folder (/tmp/p.xml: /models twice): each folder
    // once, in its first place and spelling, so the list of folders searched names each once.
    // Two spellings are one folder when the file system resolves them alike ("a/b/", "a/x/../b").
    std::vector<fs::path> unique;
    std::set<fs::path> seen;
    for (const fs::path& given : modelDirs_)
      if (seen.insert(sameFolderKey(given)).second) unique.push_back(given);
    modelDirs_ = std::move(unique);
  }

  Problem read() {
    const XMLElement* first = xml_.anyRoot();
    if (first && std::string(first->Name()) == "Benchmark")
      xml_.fail(*first,
                "a Kautham benchmark file, not a problem: run it with `kautham bench "
                "--file " +
                    xml_.file().string() + "`");
    const XMLElement& root = xml_.root("Problem");
    if (root.Attribute("topology"))
      warning(xml_.at(root).str() + ": <Problem topology> is used by Kautham's GUI only; ignored");
    xml_.allowAttributes(root, {"name", "topology"});
    problem_.file = xml_.file();
    problem_.name = xml_.optionalText(root, "name").value_or(xml_.file().stem().string());
    xml_.atMostOnce(root, {"Physics", "Interaction", "Kinodynamics", "Workspace", "Uncertainty"});
    for (const XMLElement* e = root.FirstChildElement(); e; e = e->NextSiblingElement())
      readTopLevel(*e);
    resolvePoseUncertainty();
    if (!robotElement_) xml_.fail(root, "the problem has no <Robot>");
    if (!plannerElement_) xml_.fail(root, "the problem has no <Planner> block");
    finishRobot();
    readControls();
    // Read last, wherever it stands: <Init> needs the robot and its controls, and Kautham's
    // physics parameters override the <Physics> block.
    readPlanner(*plannerElement_);
    check(root);
    return std::move(problem_);
  }

 private:
  void readTopLevel(const XMLElement& e) {
    const std::string tag = e.Name();
    if (tag == "Robot")
      readRobot(e);
    else if (tag == "Obstacle")
      readObstacle(e);
    else if (tag == "Physics")
      readPhysics(e);
    else if (tag == "Uncertainty")
      readUncertainty(e);
    else if (tag == "Interaction")
      readInteraction(e);
    else if (tag == "Kinodynamics")
      readKinodynamics(e);
    else if (tag == "Workspace")
      readWorkspace(e);
    else if (tag == "Planner")
      setPlannerElement(e);
    else if (tag == "Environment")
      readEnvironment(e);
    else if (tag == "Controls")
      setControlsElement(e);
    else
      xml_.fail(e, "unexpected element <" + tag +
                       ">; expected Robot, Obstacle, Environment, Controls, Physics, Uncertainty, "
                       "Interaction, Kinodynamics, Workspace or Planner");
  }

  static fs::path sameFolderKey(const fs::path& dir) {
    std::error_code unresolved;
    fs::path key = fs::weakly_canonical(dir, unresolved);
    if (unresolved) key = dir.lexically_normal();
    return key.has_filename() ? key : key.parent_path();  // "a/b/" is "a/b"
  }

  fs::path findModel(const XMLElement& e, const std::string& relative) const {
    const bool absolute = fs::path(relative).is_absolute();
    std::vector<fs::path> candidates;
    if (absolute)
      candidates.push_back(relative);
    else
      for (const fs::path& dir : modelDirs_) candidates.push_back(dir / relative);
    std::error_code ignored;
    for (const fs::path& candidate : candidates)
      if (fs::is_regular_file(candidate, ignored))
        return absolute ? candidate : fs::weakly_canonical(candidate);
    std::string searched;
    for (const fs::path& candidate : candidates) {
      if (fs::is_directory(candidate, ignored))
        xml_.fail(e, "model file '" + relative + "' is a folder ('" + candidate.string() +
                         "'), not a file: name the model file inside it (a .urdf, or an "
                         "<Environment>'s .bt)");
      searched += "\n  " + candidate.string();
    }
    xml_.fail(e, "model file '" + relative + "' not found; searched:" + searched +
                     "\n(add a folder with --model-dir)");
  }

  Pose readHome(const XMLElement& parent) const {
    const XMLElement* home = parent.FirstChildElement("Home");
    if (!home) return {};
    xml_.allowAttributes(*home, {"X", "Y", "Z", "WX", "WY", "WZ", "TH"});
    const Eigen::Vector3d position(homeCoordinate(*home, "X"), homeCoordinate(*home, "Y"),
                                   homeCoordinate(*home, "Z"));
    const Eigen::Vector3d axis(xml_.number(*home, "WX", 0), xml_.number(*home, "WY", 0),
                               xml_.number(*home, "WZ", 1));
    return Pose::fromAxisAngle(position, axis, xml_.number(*home, "TH", 0));
  }

  /// A <Home> coordinate in metres. Far beyond any scene (1e308), later sums overflow or put
  /// the robot's hand outside the workspace, and the error would point elsewhere: refuse here.
  double homeCoordinate(const XMLElement& home, const char* attribute) const {
    constexpr double kMaxHomeCoordinate = 1000.0;  // m
    const double value = xml_.number(home, attribute, 0);
    if (std::abs(value) > kMaxHomeCoordinate) {
      std::ostringstream message;
      message << "<Home " << attribute << "=\"" << xml_.optionalText(home, attribute).value_or("")
              << "\"> is beyond +-" << kMaxHomeCoordinate
              << " m: positions are in metres, in the world frame; place the " << parentName(home)
              << " in the scene";
      xml_.fail(home, message.str());
    }
    return value;
  }

  static std::string parentName(const XMLElement& home) {
    const XMLElement* parent = home.Parent() ? home.Parent()->ToElement() : nullptr;
    return parent ? "<" + std::string(parent->Name()) + ">" : "model";
  }

  void readModel(const XMLElement& e, const char* fileAttribute, ModelInstance& instance) {
    const std::string relative = xml_.requiredText(e, fileAttribute);
    xml_.atMostOnce(e, {"Home", "KauthamName", "Uncertainty"});
    instance.where = xml_.at(e);
    instance.urdf = findModel(e, relative);
    instance.model = loadModel(instance.urdf, xml_.number(e, "scale", 1.0), instance.where);
    instance.home = readHome(e);
    const XMLElement* home = e.FirstChildElement("Home");
    instance.homeWhere = xml_.at(home ? *home : e);
    instance.name = xml_.optionalText(e, "name").value_or(instance.model.name);
    if (const XMLElement* rename = e.FirstChildElement("KauthamName"))
      instance.name = xml_.requiredText(*rename, "name");
    const bool robot = std::strcmp(e.Name(), "Robot") == 0;
    for (const XMLElement* c = e.FirstChildElement(); c; c = c->NextSiblingElement()) {
      const std::string tag = c->Name();
      if (robot && (tag == "ViewLink" || tag == "WeightSE3" || tag == "InvKinematic" ||
                    tag == "ConstrainedKinematic")) {
        warnOnce(xml_.file().string() + "\n" + tag, xml_.at(*c).str() + ": <" + tag +
                                                        "> is used by Kautham's GUI or its " +
                                                        "inverse kinematics only; ignored");
        continue;
      }
      if (tag == "Limits" && !robot)
        xml_.fail(*c, "<Limits> moves a robot's base; an <Obstacle> has none");
      if (tag != "Home" && tag != "KauthamName" && tag != "Uncertainty" && tag != "Limits")
        xml_.fail(*c, "unexpected <" + tag + "> inside <" + e.Name() +
                          ">; expected Home, KauthamName, Limits or Uncertainty");
    }
  }

  /// Kautham's <Limits>: X, Y and Z become base joints; the rotations (WX, WY, WZ, TH/THETA)
  /// are accepted so Kautham files load, and the base does not turn.
  std::vector<BaseAxisLimits> readBaseLimits(const XMLElement& robot) const {
    std::vector<BaseAxisLimits> axes;
    for (const XMLElement* l = robot.FirstChildElement("Limits"); l;
         l = l->NextSiblingElement("Limits")) {
      xml_.allowAttributes(*l, {"name", "min", "max", "velocity", "effort"});
      BaseAxisLimits limits;
      limits.where = xml_.at(*l);
      limits.axis = xml_.requiredText(*l, "name");
      limits.min = xml_.requiredNumber(*l, "min");
      limits.max = xml_.requiredNumber(*l, "max");
      limits.velocity = positive(*l, "velocity", limits.velocity);
      limits.effort = positive(*l, "effort", limits.effort);
      const std::set<std::string> rotations{"WX", "WY", "WZ", "TH", "THETA"};
      if (rotations.count(limits.axis)) continue;
      if (limits.axis != "X" && limits.axis != "Y" && limits.axis != "Z")
        xml_.fail(*l, "unknown <Limits name=\"" + limits.axis +
                          "\">; expected X, Y, Z (or WX, WY, WZ, TH, which are ignored)");
      if (!(limits.min <= limits.max))
        xml_.fail(*l, "<Limits> needs min <= max (min = max pins the base on that axis)");
      for (const BaseAxisLimits& other : axes)
        if (other.axis == limits.axis)
          xml_.fail(*l, "a second <Limits name=\"" + limits.axis + "\">");
      axes.push_back(limits);
    }
    return axes;
  }

  /// A URDF error names the URDF's line; say which line of the problem asked for it, too.
  static KinematicModel loadModel(const fs::path& urdf, double scale, const SourceLocation& where) {
    try {
      return loadUrdf(urdf, scale, where);
    } catch (const InputError& e) {
      if (e.where().file == where.file) throw;
      throw InputError(e.where(), std::string(e.what()).substr(e.where().str().size() + 2) +
                                      "\n  (model loaded at " + where.str() + ")");
    }
  }

  void readRobot(const XMLElement& e) {
    if (robotElement_) {
      readExtraRobot(e);
      return;
    }
    robotElement_ = &e;
    xml_.allowAttributes(e, {"robot", "scale", "name"});
    if (const XMLElement* u = e.FirstChildElement("Uncertainty"))
      xml_.fail(*u, "<Uncertainty> is for objects' poses; a <Robot> has none");
    readModel(e, "robot", problem_.robot);
    repairLinkInertias(problem_.robot);
    problem_.robot.baseAxes = readBaseLimits(e);
  }

  /// Kautham plans for every <Robot> together; this project plans for one. The first is the
  /// robot; every further one stands still at its <Home> (joints at zero) as a fixed obstacle.
  void readExtraRobot(const XMLElement& e) {
    xml_.allowAttributes(e, {"robot", "scale", "name"});
    ObjectInstance object;
    readModel(e, "robot", object);
    if (e.FirstChildElement("Limits"))
      warning(xml_.at(e).str() + ": this second <Robot>'s <Limits> are unused");
    freezeJoints(object.model);
    object.role = ObjectRole::Fixed;
    warning(xml_.at(e).str() + ": only the first <Robot> ('" + problem_.robot.name +
            "') is planned for; robot '" + object.name +
            "' stands still at its <Home> as a fixed obstacle");
    problem_.objects.push_back(std::move(object));
  }

  /// Turns every movable joint into a fixed one at its value 0 (clamped into its limits).
  static void freezeJoints(KinematicModel& model) {
    for (Joint& joint : model.joints) {
      if (!joint.isMovable()) continue;
      joint.origin = joint.origin *
                     KinematicModel::jointMotion(joint, std::clamp(0.0, joint.lower, joint.upper));
      joint.type = JointType::Fixed;
    }
  }

  /// The robot's base and its default controls, once the whole file is read: how Kautham places
  /// the base depends on which base DOFs the control set names (MobileBase.h).
  void finishRobot() {
    RobotInstance& robot = problem_.robot;
    std::optional<BaseDofUse> use;
    if (controlsElement_)
      if (const auto cntr = xml_.optionalText(*controlsElement_, "robot"))
        use = scanBaseDofs(findModel(*controlsElement_, *cntr));
    absorbedDofs_ = addMobileBase(robot.model, robot.baseAxes, robot.home, use ? &*use : nullptr);
    robot.controls = ControlSet::onePerJoint(robot.model);
    coupleMimicJoints(/*ownControls=*/true);
    const KinematicModel& model = robot.model;
    for (int j : model.movableJoints())
      robot.initialJoints.push_back(std::clamp(0.0, model.joints[j].lower, model.joints[j].upper));
  }

  /// URDF <mimic> joints follow their leader: each one's row of K (and its offset) is its
  /// leader's, scaled from the leader's normalized range onto its own, so every configuration
  /// and every motion keeps value = multiplier * leader + offset; its speed limit is set so the
  /// same control turns both at that ratio. Without a .cntr (`ownControls`) the mimic joint's own
  /// control is removed.
  void coupleMimicJoints(bool ownControls) {
    RobotInstance& robot = problem_.robot;
    KinematicModel& model = robot.model;
    const std::vector<int> movable = model.movableJoints();
    auto dofOf = [&](const std::string& joint) -> std::optional<Eigen::Index> {
      for (std::size_t i = 0; i < movable.size(); ++i)
        if (model.joints[movable[i]].name == joint) return static_cast<Eigen::Index>(i);
      return std::nullopt;
    };
    ControlSet& set = robot.controls;
    std::vector<Eigen::Index> ownColumns;
    for (std::size_t i = 0; i < movable.size(); ++i) {
      Joint& follower = model.joints[movable[i]];
      if (!follower.mimic) continue;
      const auto lead = dofOf(follower.mimic->joint);
      if (!lead || model.joints[movable[*lead]].mimic)
        throw InputError(robot.where, "joint '" + follower.name + "' mimics '" +
                                          follower.mimic->joint +
                                          "', which is not a movable joint that moves by itself");
      const Joint& leader = model.joints[movable[*lead]];
      const auto row = static_cast<Eigen::Index>(i);
      if (!ownControls && set.moves(i))
        throw InputError(set.where, "the control set moves joint '" + follower.name +
                                        "', which mimics '" + leader.name +
                                        "' (URDF <mimic>): move its leader only");
      const double leaderRange = leader.upper - leader.lower;
      const double range = follower.upper - follower.lower;
      const double slope = follower.mimic->multiplier * leaderRange / range;
      const double intercept =
          (follower.mimic->multiplier * leader.lower + follower.mimic->offset - follower.lower) /
          range;
      if (ownControls) ownColumns.push_back(row);  // K = I: column i moves joint i only
      set.matrix.row(row) = slope * set.matrix.row(*lead);
      set.offset[row] = slope * set.offset[*lead] + intercept;
      follower.maxVelocity = leader.maxVelocity * range / leaderRange;
    }
    if (ownColumns.empty()) return;
    Eigen::MatrixXd matrix(set.matrix.rows(),
                           set.matrix.cols() - static_cast<Eigen::Index>(ownColumns.size()));
    std::vector<std::string> names;
    Eigen::Index kept = 0;
    for (Eigen::Index c = 0; c < set.matrix.cols(); ++c) {
      if (std::find(ownColumns.begin(), ownColumns.end(), c) != ownColumns.end()) continue;
      matrix.col(kept++) = set.matrix.col(c);
      names.push_back(set.names[static_cast<std::size_t>(c)]);
    }
    set.matrix = matrix;
    set.names = names;
  }

  /// Without a role attribute (Kautham's own files), an object with mass in its URDF can be
  /// pushed and one without is fixed.
  ObjectRole readRole(const XMLElement& e, const KinematicModel& model) {
    const std::optional<std::string> given = xml_.optionalText(e, "role");
    if (!given) {
      double mass = 0.0;
      for (const Link& link : model.links) mass += link.inertial.mass;
      return mass > 0.0 ? ObjectRole::Movable : ObjectRole::Fixed;
    }
    rolesGiven_ = true;
    const std::string& role = *given;
    if (role == "fixed") return ObjectRole::Fixed;
    if (role == "movable") return ObjectRole::Movable;
    if (role == "target") return ObjectRole::Target;
    xml_.fail(e, "unknown role '" + role + "'; expected fixed, movable or target");
  }

  void readObstacle(const XMLElement& e) {
    xml_.allowAttributes(e, {"obstacle", "scale", "name", "role"});
    ObjectInstance object;
    readModel(e, "obstacle", object);
    repairLinkInertias(object);
    object.role = readRole(e, object.model);
    if (const XMLElement* u = e.FirstChildElement("Uncertainty")) {
      xml_.allowAttributes(*u, {"x", "y", "yaw"});
      for (const char* attribute : {"x", "y", "yaw"}) nonNegative(*u, attribute);
      if (object.role == ObjectRole::Fixed)
        xml_.fail(*u, "object '" + object.name +
                          "' is fixed: it cannot be displaced, so it has no pose <Uncertainty>");
      ownUncertainty_.emplace_back(problem_.objects.size(), u);
    }
    problem_.objects.push_back(std::move(object));
  }

  /// The top-level <Uncertainty x y yaw friction erp cfm control>: standard deviations.
  void readUncertainty(const XMLElement& e) {
    xml_.allowAttributes(e, {"x", "y", "yaw", "friction", "erp", "cfm", "control"});
    problem_.defaultPoseUncertainty = {nonNegative(e, "x"), nonNegative(e, "y"),
                                       nonNegative(e, "yaw")};
    ContactUncertainty& u = problem_.uncertainty;
    u.where = xml_.at(e);
    u.friction = nonNegative(e, "friction");
    u.erp = nonNegative(e, "erp");
    u.cfm = nonNegative(e, "cfm");
    u.control = nonNegative(e, "control");
  }

  /// Every movable object and the target gets the default pose uncertainty; the attributes of
  /// its own <Uncertainty> replace the default's, one by one. Fixed objects have none.
  void resolvePoseUncertainty() {
    for (ObjectInstance& object : problem_.objects)
      if (object.role != ObjectRole::Fixed) object.uncertainty = problem_.defaultPoseUncertainty;
    for (const auto& [index, element] : ownUncertainty_) {
      PoseUncertainty& u = problem_.objects[index].uncertainty;
      u.x = nonNegative(*element, "x", u.x);
      u.y = nonNegative(*element, "y", u.y);
      u.yaw = nonNegative(*element, "yaw", u.yaw);
    }
  }

  /// <Environment octomap name occupancy> with an optional <Home>: a sensed scene whose
  /// occupied voxels become one fixed object (OctomapEnvironment.h).
  void readEnvironment(const XMLElement& e) {
    xml_.allowAttributes(e, {"octomap", "name", "occupancy"});
    xml_.allowChildren(e, {"Home"});
    xml_.atMostOnce(e, {"Home"});
    const double threshold = xml_.number(e, "occupancy", kDefaultOccupancyThreshold);
    if (!(threshold > 0.0 && threshold < 1.0))
      xml_.fail(e, "occupancy is a probability threshold: it must be in (0, 1)");
    const fs::path file = findModel(e, xml_.requiredText(e, "octomap"));
    const OctomapBoxes boxes = readOctomapBoxes(file, threshold, xml_.at(e));
    problem_.objects.push_back(
        makeEnvironmentObject(xml_.optionalText(e, "name").value_or("environment"), file, boxes,
                              readHome(e), xml_.at(e)));
  }

  double nonNegative(const XMLElement& e, const char* attribute, double fallback = 0.0) const {
    const double value = xml_.number(e, attribute, fallback);
    if (value < 0.0) xml_.fail(e, std::string("attribute ") + attribute + " must not be negative");
    return value;
  }

  double positive(const XMLElement& e, const char* attribute, double fallback) const {
    const double value = xml_.number(e, attribute, fallback);
    if (!(value > 0.0)) xml_.fail(e, std::string("attribute ") + attribute + " must be positive");
    return value;
  }

  void readPhysics(const XMLElement& e) {
    xml_.allowAttributes(
        e, {"stepSize", "gravity", "maxContacts", "solverIterations", "overRelaxation", "friction",
            "erp", "cfm", "sleep", "sleepSpeed", "sleepSteps"});
    PhysicsSettings& p = problem_.physics;
    p.where = xml_.at(e);
    p.stepSize = xml_.number(e, "stepSize", p.stepSize);
    p.gravity = xml_.vector3(e, "gravity", p.gravity);
    p.maxContacts = xml_.integer(e, "maxContacts", p.maxContacts);
    p.solverIterations = xml_.integer(e, "solverIterations", p.solverIterations);
    p.overRelaxation = xml_.number(e, "overRelaxation", p.overRelaxation);
    p.friction = nonNegative(e, "friction", p.friction);
    p.erp = nonNegative(e, "erp", p.erp);
    p.cfm = nonNegative(e, "cfm", p.cfm);
    p.sleep = xml_.flag(e, "sleep", p.sleep);
    p.sleepSpeed = xml_.number(e, "sleepSpeed", p.sleepSpeed);
    p.sleepSteps = xml_.integer(e, "sleepSteps", p.sleepSteps);
    // The ranges, checked once the element is read: the same rules hold --physics overrides.
    if (const std::optional<std::string> error = physicsSettingsError(p)) xml_.fail(e, *error);
  }

  void readInteraction(const XMLElement& e) {
    xml_.allowAttributes(
        e, {"maxObjectSpeed", "maxDisplacement", "maxTilt", "targetTolerance", "support"});
    InteractionConstraints& c = problem_.interaction;
    c.where = xml_.at(e);
    c.maxObjectSpeed = positive(e, "maxObjectSpeed", c.maxObjectSpeed);
    c.maxDisplacement = positive(e, "maxDisplacement", c.maxDisplacement);
    c.maxTilt = positive(e, "maxTilt", c.maxTilt);
    c.targetTolerance = positive(e, "targetTolerance", c.targetTolerance);
    c.supportObject = xml_.optionalText(e, "support").value_or("");
  }

  void readKinodynamics(const XMLElement& e) {
    xml_.allowAttributes(e, {"jointLimitTolerance", "jointSpeedFactor", "maxLinkSpeed"});
    KinodynamicLimits& k = problem_.kinodynamics;
    k.where = xml_.at(e);
    k.jointLimitTolerance = nonNegative(e, "jointLimitTolerance", k.jointLimitTolerance);
    k.jointSpeedFactor = positive(e, "jointSpeedFactor", k.jointSpeedFactor);
    k.maxLinkSpeed = positive(e, "maxLinkSpeed", k.maxLinkSpeed);
    if (k.jointSpeedFactor < 1.0)
      xml_.fail(e, "jointSpeedFactor must be at least 1: the motors themselves reach the limit");
  }

  void readWorkspace(const XMLElement& e) {
    xml_.allowAttributes(e, {"min", "max"});
    workspaceElement_ = &e;
    problem_.workspace.min() = xml_.vector3(e, "min", {});
    problem_.workspace.max() = xml_.vector3(e, "max", {});
    if (!xml_.optionalText(e, "min") || !xml_.optionalText(e, "max"))
      xml_.fail(e, "<Workspace> needs min=\"x y z\" and max=\"x y z\"");
    if (!(problem_.workspace.min().array() < problem_.workspace.max().array()).all())
      xml_.fail(e, "<Workspace> needs min < max on every axis");
  }

  void setControlsElement(const XMLElement& e) {
    if (controlsElement_) xml_.fail(e, "only one <Controls> is supported (one robot)");
    controlsElement_ = &e;
  }

  /// Kautham's <Controls robot="file.cntr"/>: the planner's controls for the robot.
  void readControls() {
    if (!controlsElement_) return;
    const XMLElement& e = *controlsElement_;
    xml_.allowAttributes(e, {"robot", "obstacle"});
    if (xml_.optionalText(e, "obstacle"))
      xml_.fail(e, "controls for obstacles are not supported: objects move only when pushed");
    const SourceLocation where = xml_.at(e);
    const fs::path file = findModel(e, xml_.requiredText(e, "robot"));
    RobotInstance& robot = problem_.robot;
    try {
      robot.controls = loadControlSet(file, robot.model, where, absorbedDofs_);
      coupleMimicJoints(/*ownControls=*/false);
    } catch (const InputError& error) {
      if (error.where().file == where.file) throw;
      throw InputError(error.where(),
                       std::string(error.what()).substr(error.where().str().size() + 2) +
                           "\n  (control set loaded at " + where.str() + ")");
    }
    // Without an <Init>, every control sits at its middle: the joints at the set's offset.
    robot.initialJoints =
        problem_.jointValuesFromControls(std::vector<double>(robot.controls.size(), 0.5));
  }

  void setPlannerElement(const XMLElement& e) {
    if (plannerElement_) xml_.fail(e, "only one <Planner> block is supported");
    plannerElement_ = &e;
  }

  void readPlanner(const XMLElement& e) {
    xml_.allowChildren(e, {"Parameters", "Queries"});
    xml_.atMostOnce(e, {"Parameters", "Queries"});
    problem_.planner.where = xml_.at(e);
    const XMLElement* parameters = e.FirstChildElement("Parameters");
    if (!parameters) xml_.fail(e, "<Planner> needs a <Parameters> block with a <Name>");
    readParameters(*parameters);
    const XMLElement* queries = e.FirstChildElement("Queries");
    if (!queries) xml_.fail(e, "<Planner> needs a <Queries> block with at least one <Query>");
    for (const XMLElement* q = queries->FirstChildElement(); q; q = q->NextSiblingElement())
      readQuery(*q);
    if (problem_.queries.empty()) xml_.fail(*queries, "<Queries> has no <Query>");
    applyFinalLinkGoal();
    applyControlDimensions();
  }

  /// Kautham's `only final link position?` 1 (its planar chain): the goal is the position of the
  /// chain's end link, not the joint values (FinalLinkGoal.h). Read before `Control Dimensions`,
  /// so a control that only the goal configuration moves may be held.
  void applyFinalLinkGoal() {
    const auto given = std::find_if(
        problem_.planner.parameters.begin(), problem_.planner.parameters.end(),
        [](const PlannerParameter& p) { return p.name == "only final link position?"; });
    if (given == problem_.planner.parameters.end() || std::atof(given->value.c_str()) == 0.0)
      return;
    for (Query& query : problem_.queries) {
      if (!query.goal.isConfiguration()) continue;
      query.goal = finalLinkGoal(problem_, query.goal);
      const Eigen::Vector3d& at = query.goal.offset;
      std::ostringstream message;
      message.precision(3);
      message << std::fixed << given->where.str() << ": Kautham's 'only final link position?' "
              << given->value << ": query '" << query.name << "' ends when '" << query.goal.link
              << "' is within " << query.goal.tolerance << " m of (" << at.x() << ", " << at.y()
              << ", " << at.z()
              << "), where the goal configuration puts it; the joint values are not compared";
      warning(message.str());
    }
  }

  /// Kautham's 2D physics planners (KnowledgeOrientedKPIECE2DPlanner, ...) push the robot with
  /// the first `Control Dimensions` controls only (a force along x and y): the others stay where
  /// the query puts them. Its Sphere demos name a third control, z, which here would let the
  /// sphere leave the floor it slides on in Kautham (it passes through the ground, as a robot
  /// does here). The controls past that count are kept where every query has them; if the
  /// queries move one, all controls stay, with a warning.
  void applyControlDimensions() {
    const auto given =
        std::find_if(problem_.planner.parameters.begin(), problem_.planner.parameters.end(),
                     [](const PlannerParameter& p) { return p.name == "Control Dimensions"; });
    if (given == problem_.planner.parameters.end()) return;
    ControlSet& controls = problem_.robot.controls;
    char* end = nullptr;
    const long count = std::strtol(given->value.c_str(), &end, 10);
    if (*end != '\0' || count <= 0 || static_cast<std::size_t>(count) >= controls.size()) return;
    const auto kept = static_cast<std::size_t>(count);
    std::vector<std::optional<double>> at(controls.size());
    for (const Query& query : problem_.queries)
      for (const std::vector<double>* values : {&query.init, &query.goal.controls})
        for (std::size_t j = kept; j < values->size(); ++j) {
          if (at[j] && std::abs(*at[j] - (*values)[j]) > 1e-12) {
            warning(given->where.str() + ": Kautham's 'Control Dimensions' " + given->value +
                    " would hold control '" + controls.names[j] +
                    "' still, but the queries move it: all " + std::to_string(controls.size()) +
                    " controls are planned");
            return;
          }
          at[j] = (*values)[j];
        }
    std::vector<double> values(controls.size(), 0.5);
    std::string held;
    for (std::size_t j = kept; j < controls.size(); ++j) {
      values[j] = at[j].value_or(0.5);
      held += (held.empty() ? "'" : ", '") + controls.names[j] + "'";
    }
    warning(given->where.str() + ": Kautham's 'Control Dimensions' " + given->value +
            ": its planner drives the first " + given->value + " of the " +
            std::to_string(controls.size()) + " controls; " + held +
            (kept + 1 == controls.size() ? " stays" : " stay") + " where the queries put it");
    controls.keepFirst(kept, values);
    for (Query& query : problem_.queries)
      for (std::vector<double>* v : {&query.init, &query.goal.controls})
        if (v->size() > kept) v->resize(kept);
  }

  void readParameters(const XMLElement& parameters) {
    xml_.allowChildren(parameters, {"Name", "Parameter"});
    xml_.atMostOnce(parameters, {"Name"});
    const XMLElement* name = parameters.FirstChildElement("Name");
    if (!name || xml_.elementText(*name).empty())
      xml_.fail(parameters, "<Parameters> needs <Name>PlannerName</Name>");
    problem_.planner.name = xml_.elementText(*name);
    problem_.planner.nameWhere = xml_.at(*name);
    std::optional<SourceLocation> kauthamContact;  // where Kautham's ERP or CFM was given
    for (const XMLElement* p = parameters.FirstChildElement("Parameter"); p;
         p = p->NextSiblingElement("Parameter")) {
      PlannerParameter parameter{xml_.requiredText(*p, "name"), xml_.elementText(*p), xml_.at(*p)};
      if (parameter.value.empty()) xml_.fail(*p, "parameter '" + parameter.name + "' has no value");
      if (!applyKauthamPhysicsParameter(parameter, problem_.physics, xml_, *p))
        problem_.planner.parameters.push_back(parameter);
      else if (parameter.name != "Max Contacts" && !kauthamContact)
        kauthamContact = parameter.where;
    }
    if (kauthamContact) readKauthamContact(*kauthamContact);
  }

  /// The step Kautham simulated with: OMPL's OpenDE propagator, which Kautham's ODE planners
  /// use, makes one ODE step of the whole PropagationStepSize (Kautham's default 0.05 s).
  double kauthamStep() const {
    for (const PlannerParameter& p : problem_.planner.parameters)
      if (p.name == "PropagationStepSize" || p.name == "propagation_step_size") {
        char* end = nullptr;
        const double value = std::strtod(p.value.c_str(), &end);
        if (end != p.value.c_str() && value > 0.0) return value;
      }
    return 0.05;
  }

  /// Kautham's 'Error Reduction Parameter' and 'Constraint Force Mixing' are ODE's per-contact
  /// soft_erp and soft_cfm at Kautham's step, so this program reads them as the contact spring
  /// and damper they make there, at its own (smaller) physics step: objects then rest as deep in
  /// the ground and push as softly as in Kautham (SoftContact.h).
  void readKauthamContact(const SourceLocation& where) {
    PhysicsSettings& physics = problem_.physics;
    const SoftContact given{physics.erp, physics.cfm};
    const double step = kauthamStep();
    if (!(given.cfm > 0.0) || std::abs(step - physics.stepSize) < 1e-12) return;
    const SoftContact here = softContactAtStep(given, step, physics.stepSize);
    std::ostringstream message;
    message.precision(3);
    message << where.str() << ": Kautham's ERP " << given.erp << " and CFM " << given.cfm
            << " are for its ODE steps of " << step
            << " s (PropagationStepSize); the same contact spring and damper ("
            << contactSpring(given, step) << " N/m, " << contactDamper(given)
            << " N s/m per contact point) at this program's " << physics.stepSize
            << " s steps: ERP " << here.erp << ", CFM " << here.cfm;
    warning(message.str());
    physics.erp = here.erp;
    physics.cfm = here.cfm;
  }

  void readQuery(const XMLElement& q) {
    if (std::strcmp(q.Name(), "Query") != 0)
      xml_.fail(q, std::string("unexpected <") + q.Name() + "> inside <Queries>; expected <Query>");
    xml_.allowAttributes(q, {"name"});
    xml_.allowChildren(q, {"Init", "Goal", "GoalRegion", "RobotControl"});
    xml_.atMostOnce(q, {"Init", "Goal", "GoalRegion", "RobotControl"});
    Query query;
    query.where = xml_.at(q);
    query.name =
        xml_.optionalText(q, "name").value_or("query" + std::to_string(problem_.queries.size()));
    const XMLElement* init = q.FirstChildElement("Init");
    const XMLElement* goal = q.FirstChildElement("Goal");
    const XMLElement* region = q.FirstChildElement("GoalRegion");
    if (const XMLElement* named = q.FirstChildElement("RobotControl")) {
      if (init || goal)
        xml_.fail(*named, "give either <RobotControl init=.. goal=..> or <Init>/<Goal>, not both");
      readRobotControl(*named, query, region != nullptr);
    } else {
      if (init && init->FirstChildElement())
        query.initJoints = readInitJoints(*init);
      else if (init)
        query.init = readControls(*init, xml_.numbersInText(*init), "<Init>");
      if (goal) query.goal.controls = readControls(*goal, xml_.numbersInText(*goal), "<Goal>");
    }
    if (region) {
      if (query.goal.isConfiguration())
        xml_.fail(*region, "a query has one goal: a <Goal> configuration or a <GoalRegion>");
      query.goal = readGoalRegion(*region);
    } else if (query.goal.isConfiguration()) {
      query.goal.where = xml_.at(goal ? *goal : *q.FirstChildElement("RobotControl"));
      query.goal.link = tipLink();
    } else {
      xml_.fail(q,
                "<Query> needs a goal: a <GoalRegion link=.. relativeTo=.. offset=..> or a "
                "<Goal> configuration");
    }
    problem_.queries.push_back(query);
  }

  /// <Init><Joint name="elbow" value="1.57"/>...</Init>: a start a person can write, joint by
  /// joint in radians (metres for prismatic joints), by joint or child link name. Joints not
  /// named start where the controls' middle puts them; mimic joints follow their leader.
  std::vector<double> readInitJoints(const XMLElement& init) const {
    xml_.allowChildren(init, {"Joint"});
    if (!xml_.elementText(init).empty())
      xml_.fail(init,
                "<Init> holds either normalized controls as text or <Joint> elements, not both");
    const KinematicModel& model = problem_.robot.model;
    const std::vector<int> movable = model.movableJoints();
    std::vector<double> values = problem_.robot.initialJoints;
    std::vector<bool> given(movable.size(), false);
    for (const XMLElement* j = init.FirstChildElement("Joint"); j;
         j = j->NextSiblingElement("Joint")) {
      xml_.allowAttributes(*j, {"name", "value"});
      const std::string name = xml_.requiredText(*j, "name");
      std::optional<std::size_t> dof;
      for (std::size_t i = 0; i < movable.size(); ++i) {
        const Joint& joint = model.joints[movable[i]];
        if (name == joint.name || name == model.links[joint.childLink].name) dof = i;
      }
      if (!dof) {
        std::string known;
        for (int m : movable) known += " " + model.joints[m].name;
        xml_.fail(*j, "<Joint name=\"" + name + "\"> names no movable joint of '" +
                          problem_.robot.name + "'; its movable joints:" + known);
      }
      const Joint& joint = model.joints[movable[*dof]];
      if (joint.mimic)
        xml_.fail(*j, "joint '" + joint.name + "' mimics '" + joint.mimic->joint +
                          "' (URDF <mimic>): give its leader's value instead");
      if (given[*dof]) xml_.fail(*j, "joint '" + joint.name + "' is given twice");
      const double value = xml_.requiredNumber(*j, "value");
      if (value < joint.lower - 1e-9 || value > joint.upper + 1e-9)
        xml_.fail(*j, "joint '" + joint.name + "' = " + std::to_string(value) +
                          " is outside its limits [" + std::to_string(joint.lower) + ", " +
                          std::to_string(joint.upper) +
                          (joint.type == JointType::Prismatic ? "] m" : "] rad"));
      values[*dof] = value;
      given[*dof] = true;
    }
    for (std::size_t i = 0; i < movable.size(); ++i) {
      const Joint& joint = model.joints[movable[i]];
      if (!joint.mimic) continue;
      for (std::size_t l = 0; l < movable.size(); ++l)
        if (model.joints[movable[l]].name == joint.mimic->joint)
          values[i] = std::clamp(joint.mimic->multiplier * values[l] + joint.mimic->offset,
                                 joint.lower, joint.upper);
    }
    return values;
  }

  /// A named query line: <RobotControl name="robot" init="c1 c2 .." goal="c1 c2 .."/>.
  void readRobotControl(const XMLElement& e, Query& query, bool hasRegion) const {
    xml_.allowAttributes(e, {"name", "init", "goal", "tolerance"});
    const std::string robot = xml_.requiredText(e, "name");
    if (robot != problem_.robot.name && robot != problem_.robot.model.name)
      xml_.fail(e, "<RobotControl name=\"" + robot + "\"> names no robot; the robot is '" +
                       problem_.robot.name + "'");
    query.init = readControls(e, xml_.numbersInAttribute(e, "init"), "init");
    if (xml_.optionalText(e, "goal")) {
      if (hasRegion) xml_.fail(e, "a query has one goal: goal=\"..\" or a <GoalRegion>");
      query.goal.controls = readControls(e, xml_.numbersInAttribute(e, "goal"), "goal");
      query.goal.jointTolerance = positive(e, "tolerance", query.goal.jointTolerance);
    }
  }

  /// Normalized controls of <Init>/<Goal>: one per control of the robot, each in [0, 1].
  std::vector<double> readControls(const XMLElement& e, std::vector<double> values,
                                   const std::string& what) const {
    const std::size_t count = problem_.robot.controls.size();
    if (const auto dim = xml_.optionalText(e, "dim"); dim && std::to_string(count) != *dim)
      xml_.fail(e, what + " says dim=\"" + *dim + "\" but the robot has " + std::to_string(count) +
                       " controls");
    if (values.size() != count)
      xml_.fail(e, what + " needs " + std::to_string(count) +
                       " normalized values (one per control), got " +
                       std::to_string(values.size()));
    for (double v : values)
      if (v < 0.0 || v > 1.0) xml_.fail(e, what + " values are normalized: each in [0, 1]");
    return values;
  }

  /// The robot's deepest link: what a configuration goal's progress is measured by. Depth
  /// counts the joints the control set moves (a held finger is no deeper than the palm), then
  /// all joints; of equally deep links the last in the file wins (a tool frame after fingers).
  std::string tipLink() const {
    const KinematicModel& model = problem_.robot.model;
    const std::vector<int> movable = model.movableJoints();
    auto controlled = [&](int joint) {
      const auto dof = std::find(movable.begin(), movable.end(), joint) - movable.begin();
      return dof < static_cast<long>(movable.size()) &&
             problem_.robot.controls.moves(static_cast<std::size_t>(dof));
    };
    std::size_t best = static_cast<std::size_t>(model.rootLink);
    std::pair<int, int> bestDepth{-1, -1};
    for (std::size_t l = 0; l < model.links.size(); ++l) {
      std::pair<int, int> depth{0, 0};
      for (int j = model.links[l].parentJoint; j >= 0;
           j = model.links[static_cast<std::size_t>(model.joints[j].parentLink)].parentJoint) {
        depth.first += controlled(j) ? 1 : 0;
        depth.second += 1;
      }
      if (depth >= bestDepth) {
        bestDepth = depth;
        best = l;
      }
    }
    return model.links[best].name;
  }

  GoalRegion readGoalRegion(const XMLElement& e) const {
    xml_.allowAttributes(
        e, {"link", "relativeTo", "offset", "tolerance", "approach", "approachTolerance",
            "levelAxis", "freeSpace", "freeSpaceCenter", "approachCorridor"});
    GoalRegion goal;
    goal.where = xml_.at(e);
    goal.link = xml_.requiredText(e, "link");
    goal.relativeTo = xml_.optionalText(e, "relativeTo").value_or("");
    goal.offset = xml_.vector3(e, "offset", goal.offset);
    goal.tolerance = positive(e, "tolerance", goal.tolerance);
    if (xml_.optionalText(e, "approach")) {
      const Eigen::Vector3d approach = xml_.vector3(e, "approach", {});
      if (!(approach.norm() > 1e-9)) xml_.fail(e, "approach must be a non-zero direction");
      goal.approach = approach.normalized();
      goal.approachTolerance = positive(e, "approachTolerance", goal.approachTolerance);
      if (goal.approachTolerance > M_PI) xml_.fail(e, "approachTolerance must be at most pi");
    } else if (xml_.optionalText(e, "approachTolerance")) {
      xml_.fail(e, "approachTolerance needs an approach=\"x y z\" direction");
    }
    readGoalSideGrasp(e, goal);
    return goal;
  }

  /// levelAxis, freeSpace and freeSpaceCenter: what makes a side pre-grasp real.
  void readGoalSideGrasp(const XMLElement& e, GoalRegion& goal) const {
    if (xml_.optionalText(e, "levelAxis")) {
      if (!goal.approach) xml_.fail(e, "levelAxis needs an approach=\"x y z\" direction");
      const Eigen::Vector3d axis = xml_.vector3(e, "levelAxis", {});
      if (!(axis.norm() > 1e-9) || !std::isfinite(axis.squaredNorm()))
        xml_.fail(e, "levelAxis must be a non-zero direction of moderate length, e.g. \"0 1 0\"");
      goal.levelAxis = axis.normalized();
    }
    if (xml_.optionalText(e, "freeSpace")) {
      GoalRegion::FreeSpace box;
      box.size = xml_.vector3(e, "freeSpace", {});
      if (!(box.size.minCoeff() > 0.0) || !(box.size.maxCoeff() < 1.0))
        xml_.fail(e, "freeSpace must be three box sides in (0, 1) m, e.g. \"0.04 0.12 0.155\"");
      box.center = xml_.vector3(e, "freeSpaceCenter", box.center);
      if (!(box.center.cwiseAbs().maxCoeff() < 1.0))
        xml_.fail(e, "freeSpaceCenter must lie within 1 m of the goal link, e.g. \"0 0 0.0175\"");
      goal.freeSpace = box;
    } else if (xml_.optionalText(e, "freeSpaceCenter")) {
      xml_.fail(e, "freeSpaceCenter needs a freeSpace=\"x y z\" box size");
    }
    if (xml_.optionalText(e, "approachCorridor")) {
      if (!goal.freeSpace || !goal.levelAxis)
        xml_.fail(e, "approachCorridor needs freeSpace and levelAxis (its width and direction)");
      goal.approachCorridor = positive(e, "approachCorridor", 0.0);
    }
  }

  // ----- checks of the whole problem -----

  /// Files in Kautham's own form (no roles): what Kautham's planner would do with them. Its
  /// geometric and kinematic planners treat every obstacle as fixed, whatever its <inertial>;
  /// its ODE environment adds a ground plane at z = 0.
  void applyKauthamDefaults() {
    if (rolesGiven_) return;
    if (isKauthamKinematicPlanner(problem_.planner.name)) {
      for (ObjectInstance& object : problem_.objects) {
        object.role = ObjectRole::Fixed;
        object.uncertainty = {};
      }
      return;
    }
    problem_.groundHeight = 0.0;
    restOnGround(*problem_.groundHeight);
  }

  /// In Kautham's ODE environment an object placed above the ground with nothing under it falls
  /// onto it when the simulation starts; here a falling object would break the interaction
  /// rules before the robot moves. It is put where it would land, and the user is told.
  void restOnGround(double ground) {
    for (ObjectInstance& object : problem_.objects) {
      if (object.role == ObjectRole::Fixed) continue;
      const Eigen::AlignedBox3d box = boundsAtHome(object);
      if (box.isEmpty()) continue;
      const double gap = box.min().z() - ground;
      if (gap <= 1e-3) continue;
      bool supported = false;
      for (const ObjectInstance& other : problem_.objects) {
        if (&other == &object) continue;
        const Eigen::AlignedBox3d below = boundsAtHome(other);
        if (below.isEmpty() || below.max().z() > box.min().z() + 1e-3) continue;
        supported |= below.max().z() > ground + 1e-3 && below.min().x() < box.max().x() &&
                     box.min().x() < below.max().x() && below.min().y() < box.max().y() &&
                     box.min().y() < below.max().y();
      }
      if (supported) continue;
      object.home.position.z() -= gap;
      warning(object.where.str() + ": object '" + object.name + "' starts " +
              std::to_string(gap).substr(0, 5) +
              " m above Kautham's ground (z = 0) with nothing under it; it starts on the ground, "
              "where Kautham's physics would drop it");
    }
  }

  void check(const XMLElement& root) {
    applyKauthamDefaults();
    checkNames();
    checkObjects(root);
    checkSupport();
    if (!workspaceElement_) problem_.workspace = defaultWorkspace();
    for (const Query& query : problem_.queries) checkGoal(query.goal);
  }

  void checkNames() const {
    std::set<std::string> names{problem_.robot.name};
    for (const ObjectInstance& object : problem_.objects)
      if (!names.insert(object.name).second)
        throw InputError(object.where, "the name '" + object.name +
                                           "' is used twice; give each instance its own "
                                           "<KauthamName name=\"..\"/>");
  }

  void checkObjects(const XMLElement& root) const {
    const ObjectInstance* target = nullptr;
    for (const ObjectInstance& object : problem_.objects) {
      if (object.role != ObjectRole::Target) continue;
      if (target)
        throw InputError(object.where, "a second target '" + object.name +
                                           "': the problem needs exactly one <Obstacle "
                                           "role=\"target\">, and '" +
                                           target->name + "' is one already");
      target = &object;
    }
    // Kautham's own files give no roles and need no target; ours name exactly one.
    if (!target && rolesGiven_)
      xml_.fail(root, "the problem needs exactly one <Obstacle role=\"target\">, found none");
    for (const ObjectInstance& object : problem_.objects) {
      // A fixed object's joints would be frozen at zero; a moving one's would be dropped.
      if (!object.model.movableJoints().empty())
        throw InputError(object.where,
                         "object '" + object.name + "' has movable joints; objects must be rigid");
      if (object.role == ObjectRole::Fixed) continue;
      requireMass(object);
    }
  }

  /// A movable or target object is a free body: it needs mass. A link whose <mass> is written
  /// as zero is the line to fix; without any <inertial>, the links need one.
  static void requireMass(const ObjectInstance& object) {
    double mass = 0.0;
    for (const Link& link : object.model.links) mass += link.inertial.mass;
    if (mass > 0.0) return;
    const std::string what =
        "the " + std::string(toString(object.role)) + " object '" + object.name + "' has no mass";
    for (const Link& link : object.model.links)
      if (link.inertial.massLine > 0)
        throw InputError({object.urdf, link.inertial.massLine},
                         "link '" + link.name + "' has a zero <mass>, so " + what +
                             ": give the link its real, positive mass (kg)\n  (model loaded at " +
                             object.where.str() + ")");
    throw InputError(object.where, what + ": give its URDF links an <inertial>");
  }

  void checkSupport() {
    InteractionConstraints& c = problem_.interaction;
    if (c.supportObject.empty()) return;
    auto index = problem_.findObject(c.supportObject);
    if (!index || problem_.objects[*index].role != ObjectRole::Fixed)
      throw InputError(
          c.where, "support '" + c.supportObject + "' must name a fixed <Obstacle> (the table)");
  }

  /// Without <Workspace> (Kautham's files): the scene's bounding box, with room around it. The
  /// robot counts at every corner of its mobile base's range (joints at 0, within limits), so a
  /// base that drives across the room keeps its goal inside.
  Eigen::AlignedBox3d defaultWorkspace() const {
    constexpr double kMargin = 0.25;  // m
    const RobotInstance& robot = problem_.robot;
    const KinematicModel& model = robot.model;
    const std::vector<int> movable = model.movableJoints();
    std::vector<double> values;
    std::vector<std::size_t> base;  ///< indices into `values` of the base's joints
    for (std::size_t i = 0; i < movable.size(); ++i) {
      const Joint& joint = model.joints[movable[i]];
      values.push_back(std::clamp(0.0, joint.lower, joint.upper));
      if (joint.name.rfind("base_", 0) == 0 && joint.type == JointType::Prismatic)
        base.push_back(i);
    }
    Eigen::AlignedBox3d box;
    for (unsigned corner = 0; corner < (1u << base.size()); ++corner) {
      for (std::size_t b = 0; b < base.size(); ++b) {
        const Joint& joint = model.joints[movable[base[b]]];
        values[base[b]] = (corner >> b) & 1u ? joint.upper : joint.lower;
      }
      const auto poses = model.linkPoses(robot.home.isometry(), values);
      for (std::size_t l = 0; l < model.links.size(); ++l) {
        box.extend(poses[l].translation());
        for (const CollisionShape& c : model.links[l].collisions)
          box.extend(boundingBox(c.shape, poses[l] * c.origin));
      }
    }
    for (const ObjectInstance& object : problem_.objects) box.extend(boundsAtHome(object));
    box.min().array() -= kMargin;
    box.max().array() += kMargin;
    return box;
  }

  /// A goal relative to an object that stands farther from the workspace than the goal's
  /// offset is long lies outside it whatever the offset's direction: the object's <Home> is
  /// what to fix, not the goal. (A target just outside, such as a glass above the workspace's
  /// slab, is normal: its offset brings the goal in.)
  void requireObjectNearWorkspace(const GoalRegion& goal) const {
    if (goal.relativeTo.empty()) return;
    const std::string& name = goal.relativeTo;
    const ObjectInstance& object = problem_.objects[*problem_.findObject(name)];
    const Eigen::Vector3d p = object.home.position;
    const double distance = problem_.workspace.exteriorDistance(p);
    if (distance <= goal.offset.norm()) return;
    const auto mm = [](double metres) { return std::round(metres * 1000.0) / 1000.0; };
    const Eigen::Vector3d lo = problem_.workspace.min();
    const Eigen::Vector3d hi = problem_.workspace.max();
    std::ostringstream message;
    message << "object '" << name << "' stands at (" << p.x() << ", " << p.y() << ", " << p.z()
            << "), " << mm(distance) << " m from the <Workspace> (" << lo.x() << " " << lo.y()
            << " " << lo.z() << " to " << hi.x() << " " << hi.y() << " " << hi.z()
            << "), farther than the goal's offset (" << mm(goal.offset.norm())
            << " m) reaches, so the goal relative to it lies outside the workspace; move the "
               "object's <Home> where the robot can reach it, or widen the <Workspace>";
    throw InputError(object.homeWhere, message.str());
  }

  void checkGoal(const GoalRegion& goal) const {
    if (!problem_.robot.model.findLink(goal.link)) {
      std::vector<std::string> links;
      for (const Link& link : problem_.robot.model.links) links.push_back(link.name);
      throw InputError(goal.where, "the robot '" + problem_.robot.name + "' has no link '" +
                                       goal.link + "'; its links are " + someNames(links));
    }
    if (!goal.relativeTo.empty() && !problem_.findObject(goal.relativeTo)) {
      std::vector<std::string> objects;
      for (const ObjectInstance& object : problem_.objects) objects.push_back(object.name);
      throw InputError(goal.where, "relativeTo names no object: '" + goal.relativeTo +
                                       "'; the objects are " + someNames(objects));
    }
    const Eigen::Vector3d position = problem_.goalPosition(goal);
    if (!problem_.workspace.contains(position) && !goal.isConfiguration())
      requireObjectNearWorkspace(goal);
    if (!problem_.workspace.contains(position))
      throw InputError(goal.where, "the goal (" + std::to_string(position.x()) + ", " +
                                       std::to_string(position.y()) + ", " +
                                       std::to_string(position.z()) +
                                       ") lies outside the <Workspace>");
  }

  XmlReader xml_;
  std::vector<fs::path> modelDirs_;
  Problem problem_;
  const XMLElement* robotElement_ = nullptr;
  const XMLElement* plannerElement_ = nullptr;
  const XMLElement* controlsElement_ = nullptr;
  bool rolesGiven_ = false;
  std::set<std::string> absorbedDofs_;  ///< base DOFs a .cntr may name that have no joint
  /// Objects with an <Uncertainty> of their own (index into Problem::objects, the element).
  std::vector<std::pair<std::size_t, const XMLElement*>> ownUncertainty_;
  const XMLElement* workspaceElement_ = nullptr;
};

}  // namespace

Problem loadProblem(const fs::path& problemFile, const std::vector<fs::path>& modelDirs) {
  return ProblemReader(problemFile, modelDirs).read();
}

}  // namespace kautham::core
