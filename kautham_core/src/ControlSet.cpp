#include "kautham/core/ControlSet.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "XmlReader.h"
#include "kautham/core/Log.h"

namespace kautham::core {

ControlSet ControlSet::onePerJoint(const KinematicModel& model) {
  ControlSet set;
  const std::vector<int> movable = model.movableJoints();
  for (int j : movable) set.names.push_back(model.joints[j].name);
  const auto dof = static_cast<Eigen::Index>(movable.size());
  set.matrix = Eigen::MatrixXd::Identity(dof, dof);
  set.offset = Eigen::VectorXd::Constant(dof, 0.5);
  return set;
}

bool ControlSet::moves(std::size_t dof) const {
  return matrix.row(static_cast<Eigen::Index>(dof)).cwiseAbs().maxCoeff() > 0.0;
}

void ControlSet::keepFirst(std::size_t count, const std::vector<double>& at) {
  const auto kept = static_cast<Eigen::Index>(count);
  for (Eigen::Index j = kept; j < matrix.cols(); ++j)
    offset += matrix.col(j) * (at[static_cast<std::size_t>(j)] - 0.5);
  matrix.conservativeResize(Eigen::NoChange, kept);
  names.resize(count);
}

Eigen::VectorXd ControlSet::normalizedConfiguration(const std::vector<double>& controls) const {
  Eigen::VectorXd c = Eigen::Map<const Eigen::VectorXd>(controls.data(),
                                                        static_cast<Eigen::Index>(controls.size()));
  const Eigen::VectorXd q = matrix * (c.array() - 0.5).matrix() + offset;
  return q.cwiseMax(0.0).cwiseMin(1.0);
}

namespace {

using tinyxml2::XMLElement;

class ControlSetReader {
 public:
  ControlSetReader(const std::filesystem::path& file, const KinematicModel& model,
                   const std::set<std::string>& ignored)
      : xml_(file), model_(model), movable_(model.movableJoints()), ignored_(ignored) {}

  ControlSet read() {
    const XMLElement& root = xml_.root("ControlSet");
    xml_.allowChildren(root, {"Offset", "Control"});
    xml_.atMostOnce(root, {"Offset"});
    ControlSet set;
    set.file = xml_.file();
    const auto dof = static_cast<Eigen::Index>(movable_.size());
    set.offset = Eigen::VectorXd::Constant(dof, 0.5);
    if (const XMLElement* offset = root.FirstChildElement("Offset"))
      for (const XMLElement* d = firstDof(*offset); d; d = d->NextSiblingElement())
        if (const Eigen::Index i = dofIndex(*d); i >= 0) set.offset[i] = normalizedValue(*d);
    std::vector<Eigen::VectorXd> columns;
    for (const XMLElement* c = root.FirstChildElement("Control"); c;
         c = c->NextSiblingElement("Control")) {
      xml_.allowAttributes(*c, {"name", "eigValue"});
      set.names.push_back(xml_.requiredText(*c, "name"));
      const double scale = xml_.number(*c, "eigValue", 1.0);
      Eigen::VectorXd column = Eigen::VectorXd::Zero(dof);
      bool namesIgnored = false;
      for (const XMLElement* d = firstDof(*c); d; d = d->NextSiblingElement()) {
        const Eigen::Index i = dofIndex(*d);
        if (i >= 0)
          column[i] = xml_.requiredNumber(*d, "value") * scale;
        else
          namesIgnored = true;
      }
      if (!(dof > 0 && column.cwiseAbs().maxCoeff() > 0.0)) {
        if (!namesIgnored)
          xml_.fail(*c, "control '" + set.names.back() + "' moves no degree of freedom");
        // Kautham keeps a control whose base axis is pinned (min = max): it moves nothing.
        warning(xml_.at(*c).str() + ": control '" + set.names.back() +
                "' moves only base DOFs pinned by <Limits min = max> (or a fixed rotation): it "
                "moves nothing");
      }
      columns.push_back(column);
    }
    if (columns.empty()) xml_.fail(root, "the control set has no <Control>");
    if (dof == 0)
      xml_.fail(root,
                "the robot has no movable joint for this control set to move (a base DOF X, Y or "
                "Z moves only with <Limits name=\"X\" min=.. max=..> on the <Robot>, min < max)");
    set.matrix.resize(dof, static_cast<Eigen::Index>(columns.size()));
    for (std::size_t i = 0; i < columns.size(); ++i)
      set.matrix.col(static_cast<Eigen::Index>(i)) = columns[i];
    return set;
  }

 private:
  const XMLElement* firstDof(const XMLElement& parent) const {
    xml_.allowChildren(parent, {"DOF"});
    return parent.FirstChildElement("DOF");
  }

  double normalizedValue(const XMLElement& dof) const {
    const double value = xml_.requiredNumber(dof, "value");
    if (value < 0.0 || value > 1.0)
      xml_.fail(dof, "an offset is a normalized joint value: it must lie in [0, 1]");
    return value;
  }

  Eigen::Index dofIndex(const XMLElement& dof) const {
    xml_.allowAttributes(dof, {"name", "value"});
    const std::string full = xml_.requiredText(dof, "name");
    // Kautham writes "robot/link"; the robot part is informative only.
    const std::string name = full.substr(full.find_last_of('/') + 1);
    // Kautham's base DOFs X, Y, Z and X3 are the joints base_X, base_Y, base_Z and base_X3.
    const bool baseDof =
        name == "X" || name == "Y" || name == "Z" || name == "X1" || name == "X2" || name == "X3";
    const std::string jointName = baseDof ? "base_" + name : name;
    for (std::size_t i = 0; i < movable_.size(); ++i) {
      const Joint& joint = model_.joints[movable_[i]];
      if (jointName == joint.name || name == joint.name ||
          name == model_.links[joint.childLink].name)
        return static_cast<Eigen::Index>(i);
    }
    if (ignored_.count(name) || (name.rfind("base_", 0) == 0 && ignored_.count(name.substr(5))))
      return -1;
    if (baseDof)
      xml_.fail(dof, "DOF '" + full + "' is a base DOF, but the robot '" + model_.name +
                         "' has no base there: give the <Robot> a <Limits name=\"" + name +
                         "\" min=.. max=..> (X, Y, Z) or use X3 only with X1's offset 0");
    std::string known;
    for (int j : movable_) known += " " + model_.links[model_.joints[j].childLink].name;
    xml_.fail(dof, "DOF '" + full + "' names no movable joint of '" + model_.name +
                       "'; expected the child link (or joint) name of one of:" + known);
  }

  XmlReader xml_;
  const KinematicModel& model_;
  std::vector<int> movable_;
  const std::set<std::string>& ignored_;
};

}  // namespace

ControlSet loadControlSet(const std::filesystem::path& file, const KinematicModel& model,
                          const SourceLocation& requestedAt, const std::set<std::string>& ignored) {
  ControlSet set = ControlSetReader(file, model, ignored).read();
  set.where = requestedAt;
  return set;
}

}  // namespace kautham::core
