// ODE against MuJoCo on the dense suite's own scenes: physics steps per second while the arm
// runs a plan's controls through the clutter (docs/performance.md, "MuJoCo on the dense
// suite"). Issue 11 names MuJoCo 2.2.2 (Debian's libmujoco-dev) as a lever if ODE is what
// limits; this program measures that lever before any of the planner is moved onto it.
//
// The MuJoCo model is written from the same parsed problem the ODE world is built from: the
// robot's links (masses, inertias, collision primitives, meshes as their vertices), its joints
// (axes, limits, the 0.1 kg m^2 armature ODE's bodies get), the joints no control moves welded
// at their start values, the robot's weight compensated (ODE's robot has no gravity),
// the fixed objects as static geometry, every movable object and the target a free body at its
// pose in ODE's start state, and the file's timestep, gravity and friction. Robot links do not
// collide with each other (as in the ODE world). ODE drives each controlled joint by a
// velocity motor; here a servo force does, limited to the joint's effort (MuJoCo's velocity
// actuators need the implicit integrator, which in 2.2.2 works on dense matrices: 6 to 10
// times slower on these scenes, and its clamped servo left the arm behind). MuJoCo steps with
// semi-implicit Euler. Both engines run the same joint velocities, step for step, in rounds that
// alternate between them, so a busy moment slows both alike; the table says how far the two
// arms ended apart and which objects each moved, so a reader sees they did the same work.
//
//   kautham plan problems/kuka_clutter_30.xml --seed 1 --set uncertainty=0 -o plan30.json
//   mujoco_throughput --problem problems/kuka_clutter_30.xml --plan plan30.json

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include <mujoco/mujoco.h>
#include <CLI/CLI.hpp>
#include <Eigen/Eigenvalues>
#include <nlohmann/json.hpp>

#include "PlanControls.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/physics/ControlMapping.h"
#include "kautham/physics/PlanningContext.h"

namespace {

using kautham::core::CollisionShape;
using kautham::core::Joint;
using kautham::core::JointType;
using kautham::core::KinematicModel;
using kautham::core::Problem;
using kautham::physics::BodyRole;
using kautham::physics::PlanningContext;
using kautham::physics::WorldLayout;
using Clock = std::chrono::steady_clock;

// As the ODE world's builder: every body behind a revolute joint gets this extra inertia, and
// a massless link that moves on its own joint a small sphere's mass.
constexpr double kArmature = 0.1;
constexpr double kDefaultMass = 0.1;
constexpr double kDefaultRadius = 0.02;

using kautham::benchmarks::PlanControl;
using kautham::benchmarks::readControls;

// ---------------------------------------------------------------------------------------------
// The MJCF text

std::string numbers(std::initializer_list<double> values) {
  std::ostringstream out;
  out << std::setprecision(12);
  bool first = true;
  for (double v : values) {
    out << (first ? "" : " ") << v;
    first = false;
  }
  return out.str();
}

std::string placement(const Eigen::Isometry3d& pose) {
  const Eigen::Vector3d p = pose.translation();
  const Eigen::Quaterniond q(pose.linear());
  return "pos=\"" + numbers({p.x(), p.y(), p.z()}) + "\" quat=\"" +
         numbers({q.w(), q.x(), q.y(), q.z()}) + "\"";
}

/// Writes a model's geometry, inertias and joints as MJCF; `meshes` collects the assets.
class MjcfWriter {
 public:
  explicit MjcfWriter(double friction) : friction_(friction) {}

  /// A collision shape as a <geom>. `robot`: collides with objects only.
  void geom(std::ostream& out, const CollisionShape& shape, bool robot) {
    out << "<geom " << placement(shape.origin) << " friction=\"" << friction_
        << " 0.005 0.0001\" contype=\"" << (robot ? 2 : 1) << "\" conaffinity=\"" << (robot ? 1 : 3)
        << "\" ";
    if (const auto* box = std::get_if<kautham::core::Box>(&shape.shape)) {
      const Eigen::Vector3d h = box->size / 2.0;
      out << "type=\"box\" size=\"" << numbers({h.x(), h.y(), h.z()}) << "\"/>\n";
    } else if (const auto* c = std::get_if<kautham::core::Cylinder>(&shape.shape)) {
      out << "type=\"cylinder\" size=\"" << numbers({c->radius, c->length / 2.0}) << "\"/>\n";
    } else if (const auto* s = std::get_if<kautham::core::Sphere>(&shape.shape)) {
      out << "type=\"sphere\" size=\"" << s->radius << "\"/>\n";
    } else {
      const auto& mesh = std::get<kautham::core::Mesh>(shape.shape);
      const std::string name = "mesh" + std::to_string(meshes_.size());
      std::ostringstream vertices;
      vertices << std::setprecision(9);
      for (const Eigen::Vector3d& v : mesh.vertices())
        vertices << v.x() << ' ' << v.y() << ' ' << v.z() << ' ';
      meshes_.push_back("<mesh name=\"" + name + "\" vertex=\"" + vertices.str() + "\"/>");
      out << "type=\"mesh\" mesh=\"" << name << "\"/>\n";
    }
  }

  static void inertial(std::ostream& out, const kautham::core::Inertial& in, bool movesOnItsOwn) {
    double mass = in.mass;
    Eigen::Matrix3d inertia = in.inertia;
    if (mass <= 0.0) mass = movesOnItsOwn ? kDefaultMass : 1e-6;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(inertia);
    if (solver.eigenvalues().minCoeff() <= 0.0)
      inertia = Eigen::Matrix3d::Identity() * 0.4 * mass * kDefaultRadius * kDefaultRadius;
    // fullinertia is in the body's axes (MuJoCo takes no quat with it).
    const Eigen::Matrix3d r = in.origin.linear();
    inertia = r * inertia * r.transpose();
    const Eigen::Vector3d p = in.origin.translation();
    out << "<inertial pos=\"" << numbers({p.x(), p.y(), p.z()}) << "\" mass=\"" << mass
        << "\" fullinertia=\""
        << numbers({inertia(0, 0), inertia(1, 1), inertia(2, 2), inertia(0, 1), inertia(0, 2),
                    inertia(1, 2)})
        << "\"/>\n";
  }

  /// The robot's link `link` and everything below it. `values`: each movable joint's start
  /// value; `isControlled`: the joints a control moves (the others are welded where they start).
  void robotLink(std::ostream& out, const KinematicModel& model, int link,
                 const Eigen::Isometry3d& pose, const std::map<std::string, double>& values,
                 const std::map<std::string, bool>& isControlled) {
    const auto& l = model.links[link];
    const Joint* joint = l.parentJoint >= 0 ? &model.joints[l.parentJoint] : nullptr;
    const bool moves = joint && joint->isMovable() && isControlled.at(joint->name);
    Eigen::Isometry3d frame = pose;
    if (joint && joint->isMovable() && !moves)
      frame = frame * KinematicModel::jointMotion(*joint, values.at(joint->name));
    out << "<body name=\"" << l.name << "\" " << placement(frame) << ">\n";
    inertial(out, l.inertial, moves);
    if (moves) {
      const bool slide = joint->type == JointType::Prismatic;
      out << "<joint name=\"" << joint->name << "\" type=\"" << (slide ? "slide" : "hinge")
          << "\" axis=\"" << numbers({joint->axis.x(), joint->axis.y(), joint->axis.z()}) << "\"";
      if (joint->type != JointType::Continuous)
        out << " limited=\"true\" range=\"" << numbers({joint->lower, joint->upper}) << "\"";
      if (!slide) out << " armature=\"" << kArmature << "\"";
      out << "/>\n";
      controlled_.push_back(*joint);
    }
    for (const CollisionShape& shape : l.collisions) geom(out, shape, true);
    for (int child : l.childJoints) {
      const Joint& j = model.joints[child];
      robotLink(out, model, j.childLink, j.origin, values, isControlled);
    }
    out << "</body>\n";
  }

  const std::vector<std::string>& meshes() const { return meshes_; }
  /// The joints a control moves, in the order of the model's joints.
  const std::vector<Joint>& controlled() const { return controlled_; }

 private:
  double friction_;
  std::vector<std::string> meshes_;
  std::vector<Joint> controlled_;
};

struct Solver {
  std::string name;  ///< "newton" or "pgs"
  int iterations = 100;
};

/// "solver:iterations", e.g. "newton:100" or "pgs:40".
Solver parseSolver(const std::string& text) {
  Solver solver;
  std::istringstream in(text);
  std::string iterations;
  std::getline(in, solver.name, ':');
  std::getline(in, iterations);
  if ((solver.name != "newton" && solver.name != "pgs") || iterations.empty())
    throw std::runtime_error("--solver " + text + ": expected solver:iterations, e.g. pgs:40");
  solver.iterations = std::stoi(iterations);
  return solver;
}

/// The whole scene as MJCF, the objects where ODE's start state has them.
std::string sceneMjcf(const Problem& problem, PlanningContext& ode, const Solver& solver,
                      std::vector<Joint>& controlled) {
  const kautham::physics::World& world = ode.world();
  const WorldLayout& layout = ode.layout();
  const std::vector<double>& start = ode.startState();
  MjcfWriter writer(problem.physics.friction);
  std::ostringstream body;
  // The robot, welded to the world at its home pose.
  std::map<std::string, double> values;
  std::map<std::string, bool> isControlled;
  const std::vector<double> joints = world.jointPositions();
  for (std::size_t i = 0; i < layout.joints.size(); ++i) {
    values[layout.joints[i].name] = joints[i];
    isControlled[layout.joints[i].name] = !layout.joints[i].held;
  }
  const KinematicModel& robot = problem.robot.model;
  writer.robotLink(body, robot, robot.rootLink, problem.robot.home.isometry(), values,
                   isControlled);
  // Fixed objects as static geometry, the others as free bodies.
  for (std::size_t b = 0; b < layout.bodies.size(); ++b) {
    const auto& info = layout.bodies[b];
    if (info.role == BodyRole::Robot) continue;
    const auto& object = problem.objects[static_cast<std::size_t>(info.objectIndex)];
    if (object.model.links.size() != 1)  // never a scene with a part of an object missing
      throw std::runtime_error(object.name + " has " + std::to_string(object.model.links.size()) +
                               " links; only objects of one link are written to MuJoCo");
    const auto& link = object.model.links[object.model.rootLink];
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = WorldLayout::position(start.data(), b);
    pose.linear() = WorldLayout::orientation(start.data(), b).toRotationMatrix();
    pose = pose * info.linkInBody.inverse();
    body << "<body name=\"" << info.name << "\" " << placement(pose) << ">\n<freejoint/>\n";
    MjcfWriter::inertial(body, link.inertial, true);
    for (const CollisionShape& shape : link.collisions) writer.geom(body, shape, false);
    body << "</body>\n";
  }
  for (const auto& object : problem.objects) {
    if (object.role != kautham::core::ObjectRole::Fixed) continue;
    for (const CollisionShape& shape : kautham::core::shapesAtHome(object))
      writer.geom(body, shape, false);
  }
  controlled = writer.controlled();
  std::ostringstream mjcf;
  const auto& g = problem.physics.gravity;
  mjcf << std::setprecision(12) << "<mujoco model=\"" << problem.name << "\">\n"
       << "<compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n"
       << "<option timestep=\"" << problem.physics.stepSize << "\" gravity=\""
       << numbers({g.x(), g.y(), g.z()}) << "\" integrator=\"Euler\" solver=\""
       << (solver.name == "pgs" ? "PGS" : "Newton") << "\" iterations=\"" << solver.iterations
       << "\"/>\n<asset>\n";
  for (const std::string& mesh : writer.meshes()) mjcf << mesh << "\n";
  mjcf << "</asset>\n<worldbody>\n" << body.str() << "</worldbody>\n</mujoco>\n";
  return mjcf.str();
}

// ---------------------------------------------------------------------------------------------
// The two engines along the plan

/// Joint velocity targets for each physics step of the plan, one value per joint of the ODE
/// world (held joints included, at 0).
std::vector<std::vector<double>> velocityPerStep(const Problem& problem, const PlanningContext& ode,
                                                 const std::vector<PlanControl>& controls) {
  const kautham::physics::ControlMapping mapping(problem.robot.controls, ode.layout().joints);
  std::vector<std::vector<double>> steps;
  for (const PlanControl& c : controls) {
    std::vector<double> v(ode.layout().joints.size());
    mapping.jointVelocities(c.values.data(), v.data());
    const long n = std::lround(c.duration / problem.physics.stepSize);
    for (long s = 0; s < n; ++s) steps.push_back(v);
  }
  return steps;
}

struct Outcome {
  double seconds = 0.0;
  double contacts = 0.0;       ///< mean per step (MuJoCo only)
  double movedObjects = 0.0;   ///< objects moved more than 1 cm by the end
  double largestMove = 0.0;    ///< m
  std::vector<double> joints;  ///< every joint at the end, in the ODE world's order

  /// Counts an object that moved `distance` metres from start to end.
  void addMove(double distance) {
    largestMove = std::max(largestMove, distance);
    if (distance > 0.01) ++movedObjects;
  }
};

Outcome runOde(PlanningContext& ode, const std::vector<std::vector<double>>& steps) {
  kautham::physics::World& world = ode.world();
  const std::vector<double>& start = ode.startState();
  world.writeState(start.data());
  world.resetSolverSeed();
  const Clock::time_point t0 = Clock::now();
  for (const auto& v : steps) {
    world.setJointVelocities(v.data());
    world.step();
  }
  Outcome out;
  out.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  std::vector<double> end(start.size());
  world.readState(end.data());
  out.joints = world.jointPositions();
  for (std::size_t b = 0; b < ode.layout().bodies.size(); ++b) {
    if (ode.layout().bodies[b].role == BodyRole::Robot) continue;
    out.addMove(
        (WorldLayout::position(end.data(), b) - WorldLayout::position(start.data(), b)).norm());
  }
  return out;
}

class MujocoScene {
 public:
  MujocoScene(const std::string& mjcf, const std::vector<Joint>& controlled,
              const WorldLayout& layout, const std::vector<double>& jointStart) {
    const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                       ("kautham_mujoco_" + std::to_string(::getpid()) + ".xml");
    std::ofstream(file) << mjcf;
    char error[1000] = "";
    model_ = mj_loadXML(file.c_str(), nullptr, error, sizeof error);
    std::filesystem::remove(file);
    if (!model_) throw std::runtime_error(std::string("MuJoCo rejected the scene: ") + error);
    data_ = mj_makeData(model_);
    jointStart_ = jointStart;
    // Each controlled joint's addresses, and which of the ODE world's joints it is.
    for (const Joint& j : controlled) {
      const int id = mj_name2id(model_, mjOBJ_JOINT, j.name.c_str());
      const auto it = std::find_if(layout.joints.begin(), layout.joints.end(),
                                   [&](const auto& info) { return info.name == j.name; });
      odeJoint_.push_back(static_cast<std::size_t>(it - layout.joints.begin()));
      qposAddress_.push_back(model_->jnt_qposadr[id]);
      dofAddress_.push_back(model_->jnt_dofadr[id]);
      effort_.push_back(j.maxEffort);
    }
    for (int b = 1; b < model_->nbody; ++b)
      if (model_->body_jntnum[b] == 1 && model_->jnt_type[model_->body_jntadr[b]] == mjJNT_FREE)
        freeBodies_.push_back(b);
  }
  ~MujocoScene() {
    mj_deleteData(data_);
    mj_deleteModel(model_);
  }
  MujocoScene(const MujocoScene&) = delete;
  MujocoScene& operator=(const MujocoScene&) = delete;

  Outcome run(const std::vector<std::vector<double>>& steps) {
    mj_resetData(model_, data_);
    for (std::size_t i = 0; i < qposAddress_.size(); ++i)
      data_->qpos[qposAddress_[i]] = jointStart_[odeJoint_[i]];
    mj_forward(model_, data_);
    std::vector<Eigen::Vector3d> before;
    for (int b : freeBodies_)
      before.emplace_back(data_->xpos[3 * b], data_->xpos[3 * b + 1], data_->xpos[3 * b + 2]);
    double contacts = 0.0;
    const Clock::time_point t0 = Clock::now();
    for (const auto& v : steps) {
      for (std::size_t i = 0; i < odeJoint_.size(); ++i) {
        const int dof = dofAddress_[i];
        // ODE's robot has no gravity: hold the arm's weight as the last step's bias had it.
        data_->qfrc_applied[dof] = data_->qfrc_bias[dof] + servoForce(i, v[odeJoint_[i]]);
      }
      mj_step(model_, data_);
      contacts += data_->ncon;
    }
    Outcome out;
    out.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    out.contacts = contacts / static_cast<double>(steps.size());
    out.joints = jointStart_;
    for (std::size_t i = 0; i < odeJoint_.size(); ++i)
      out.joints[odeJoint_[i]] = data_->qpos[qposAddress_[i]];
    for (std::size_t k = 0; k < freeBodies_.size(); ++k) {
      const int b = freeBodies_[k];
      const Eigen::Vector3d now(data_->xpos[3 * b], data_->xpos[3 * b + 1], data_->xpos[3 * b + 2]);
      out.addMove((now - before[k]).norm());
    }
    return out;
  }

  /// The servo's force for Euler: what would take the joint to its target rate in one step,
  /// were it alone (its diagonal of the mass matrix, armature included), limited to the joint's
  /// effort as ODE's motor is. The joints are coupled: at a gain of 0.8 the KUKA's first joint
  /// swung between -4 and 4 rad/s at full effort; at 0.3 it follows ODE's within 0.01 rad.
  double servoForce(std::size_t i, double target) const {
    constexpr double kGain = 0.3;
    const int dof = dofAddress_[i];
    const double inertia = data_->qM[model_->dof_Madr[dof]];
    const double force = kGain * inertia * (target - data_->qvel[dof]) / model_->opt.timestep;
    return std::clamp(force, -effort_[i], effort_[i]);
  }

  int warnings() const {
    int total = 0;
    for (int w = 0; w < mjNWARNING; ++w) total += data_->warning[w].number;
    return total;
  }

 private:
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
  std::vector<std::size_t> odeJoint_;
  std::vector<int> qposAddress_, dofAddress_;
  std::vector<double> effort_;      ///< per controlled joint
  std::vector<double> jointStart_;  ///< every joint of the ODE world at the start
  std::vector<int> freeBodies_;
};

/// MuJoCo's warnings (an unstable simulation) on the console, not in a MUJOCO_LOG.TXT of the
/// working folder.
void printWarning(const char* message) { std::fprintf(stderr, "MuJoCo: %s\n", message); }

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "ODE against MuJoCo 2.2.2 on a problem's own scene: physics steps per second while the "
      "robot runs a plan's controls (docs/performance.md)"};
  std::string problemFile, planFile, mjcfFile;
  unsigned rounds = 3;
  std::vector<std::string> solvers{"newton:100", "newton:20", "pgs:40"};
  app.add_option("--problem", problemFile, "problem file")->required();
  app.add_option("--plan", planFile, "plan file (from kautham plan -o)")->required();
  app.add_option("--rounds", rounds, "alternating rounds of each engine (default 3)");
  app.add_option("--solver", solvers, "MuJoCo solver:iterations to measure (newton or pgs)")
      ->delimiter(',');
  app.add_option("--mjcf", mjcfFile, "also write the MuJoCo scene (of the first solver) here");
  CLI11_PARSE(app, argc, argv);
  mju_user_warning = printWarning;
  try {
    const Problem problem = kautham::core::loadProblem(problemFile);
    const std::vector<PlanControl> controls = readControls(planFile);
    PlanningContext ode(problem, 0, {});
    // ODE as the file sets it (objects at rest sleep), and with every object stepped, as MuJoCo
    // steps them (2.2.2 has no sleeping bodies).
    Problem awake = problem;
    awake.physics.sleep = false;
    PlanningContext odeAwake(awake, 0, {});
    const auto steps = velocityPerStep(problem, ode, controls);
    const std::vector<double> jointStart = ode.world().jointPositions();
    std::vector<std::unique_ptr<MujocoScene>> scenes;
    for (const std::string& s : solvers) {
      const Solver solver = parseSolver(s);
      std::vector<Joint> controlled;
      const std::string mjcf = sceneMjcf(problem, ode, solver, controlled);
      if (!mjcfFile.empty() && scenes.empty()) std::ofstream(mjcfFile) << mjcf;
      scenes.push_back(std::make_unique<MujocoScene>(mjcf, controlled, ode.layout(), jointStart));
    }
    std::printf(
        "%s, %s: %zu physics steps of %.3f s, ODE at %d iterations (sleep %s); ratio: "
        "speed against the first row\n",
        problemFile.c_str(), planFile.c_str(), steps.size(), problem.physics.stepSize,
        problem.physics.solverIterations, problem.physics.sleep ? "on" : "off");
    std::printf("%-24s %9s %7s %9s %10s %9s %11s\n", "engine", "steps/s", "ratio", "contacts",
                "moved>1cm", "largest", "joint gap");
    double odeSeconds = 0.0, awakeSeconds = 0.0;
    Outcome awakeLast;
    std::vector<double> mjSeconds(scenes.size(), 0.0);
    Outcome odeLast;
    std::vector<Outcome> mjLast(scenes.size());
    for (unsigned r = 0; r < rounds; ++r) {
      odeLast = runOde(ode, steps);
      odeSeconds += odeLast.seconds;
      awakeLast = runOde(odeAwake, steps);
      awakeSeconds += awakeLast.seconds;
      for (std::size_t k = 0; k < scenes.size(); ++k) {
        mjLast[k] = scenes[k]->run(steps);
        mjSeconds[k] += mjLast[k].seconds;
      }
    }
    const double total = static_cast<double>(steps.size()) * rounds;
    std::printf("%-24s %9.0f %7.2f %9s %10.0f %7.1fcm %11s\n", "ODE", total / odeSeconds, 1.0, "-",
                odeLast.movedObjects, 100.0 * odeLast.largestMove, "-");
    std::printf("%-24s %9.0f %7.2f %9s %10.0f %7.1fcm %11s\n", "ODE, no sleep",
                total / awakeSeconds, odeSeconds / awakeSeconds, "-", awakeLast.movedObjects,
                100.0 * awakeLast.largestMove, "-");
    for (std::size_t k = 0; k < scenes.size(); ++k) {
      // How far the MuJoCo arm ended from ODE's: whether both ran the same motion.
      double gap = 0.0;
      for (std::size_t j = 0; j < odeLast.joints.size(); ++j)
        gap = std::max(gap, std::abs(std::remainder(mjLast[k].joints[j] - odeLast.joints[j],
                                                    2.0 * M_PI)));  // a continuous joint wraps
      std::printf("%-24s %9.0f %7.2f %9.1f %10.0f %7.1fcm %7.3f rad%s\n",
                  ("MuJoCo " + solvers[k]).c_str(), total / mjSeconds[k], odeSeconds / mjSeconds[k],
                  mjLast[k].contacts, mjLast[k].movedObjects, 100.0 * mjLast[k].largestMove, gap,
                  scenes[k]->warnings() ? "  (MuJoCo warned)" : "");
    }
  } catch (const std::exception& e) {
    std::cerr << "mujoco_throughput: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
