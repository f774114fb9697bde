#include "TreePicture.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/Geometry>

namespace kautham::apps {

namespace {

using nlohmann::json;

constexpr double kPixelsPerMetre = 700.0;
constexpr double kMargin = 0.05;  // metres around what is drawn

const char* roleColour(const std::string& role) {
  if (role == "fixed") return "#9aa1a8";
  if (role == "movable") return "#e8832a";
  if (role == "target") return "#2e9e4f";
  return "#3c4654";
}

/// Blue (far from the goal, or low belief) to yellow (at the goal, or certain), through green.
std::string ramp(double t) {
  t = std::clamp(t, 0.0, 1.0);
  const int r = static_cast<int>(std::lround(68 + t * (253 - 68)));
  const int g = static_cast<int>(std::lround(1 + t * (231 - 1) * (0.35 + 0.65 * t)));
  const int b = static_cast<int>(std::lround(84 + (1.0 - t) * (150 - 84) - t * 47));
  return fmt::format("#{:02x}{:02x}{:02x}", r, g, std::clamp(b, 0, 255));
}

Eigen::Isometry3d poseOf(const json& p) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
  pose.linear() = Eigen::Quaterniond(p[3], p[4], p[5], p[6]).normalized().toRotationMatrix();
  return pose;
}

/// World pose of a shape at the start: static shapes are placed in the world, the others on
/// their body's first-frame pose.
Eigen::Isometry3d startPose(const json& plan, const json& shape) {
  const Eigen::Isometry3d local = poseOf(shape["pose"]);
  if (shape["body"].is_null()) return local;
  return poseOf(plan["frames"][0]["poses"][shape["body"].get<std::size_t>()]) * local;
}

/// A mesh's outline seen from above: the convex hull of its vertices projected on the xy plane,
/// counter-clockwise (Andrew's monotone chain).
std::vector<Eigen::Vector2d> meshOutline(const json& shape, const Eigen::Isometry3d& pose) {
  const json& v = shape["vertices"];
  std::vector<Eigen::Vector2d> points;
  for (std::size_t i = 0; i + 2 < v.size(); i += 3)
    points.push_back(
        (pose * Eigen::Vector3d(v[i].get<double>(), v[i + 1].get<double>(), v[i + 2].get<double>()))
            .head<2>());
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (points.size() < 3) return points;
  const auto turnsLeft = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a,
                            const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x() > 0.0;
  };
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {  // lower chain
    while (k >= 2 && !turnsLeft(hull[k - 2], hull[k - 1], points[i])) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && !turnsLeft(hull[k - 2], hull[k - 1], points[i])) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);  // the last point is the first
  return hull;
}

/// The shape's outline seen from above, as an SVG element in world metres.
std::string outline(const json& shape, const Eigen::Isometry3d& pose, const std::string& style) {
  const Eigen::Vector3d c = pose.translation();
  const std::string type = shape["type"];
  if (type == "mesh") {
    std::string points;
    for (const Eigen::Vector2d& p : meshOutline(shape, pose))
      points += fmt::format("{:.4f},{:.4f} ", p.x(), p.y());
    return fmt::format(R"svg(<polygon points="{}" {}/>)svg", points, style);
  }
  if (type != "box") {
    const double r = shape["radius"];
    return fmt::format(R"svg(<circle cx="{:.4f}" cy="{:.4f}" r="{:.4f}" {}/>)svg", c.x(), c.y(), r,
                       style);
  }
  const double yaw = std::atan2(pose.linear()(1, 0), pose.linear()(0, 0)) * 180.0 / M_PI;
  const double sx = shape["size"][0], sy = shape["size"][1];
  return fmt::format(
      R"svg(<rect x="{:.4f}" y="{:.4f}" width="{:.4f}" height="{:.4f}" transform="rotate({:.2f} {:.4f} {:.4f})" {}/>)svg",
      c.x() - sx / 2, c.y() - sy / 2, sx, sy, yaw, c.x(), c.y(), style);
}

struct Bounds {
  Eigen::AlignedBox2d box;
  void add(double x, double y) { box.extend(Eigen::Vector2d(x, y)); }
};

Bounds drawingBounds(const json& plan) {
  Bounds bounds;
  for (const json& p : plan["tree"]["end_effector"]) bounds.add(p[0], p[1]);
  for (const json& p : plan["goal"]["link_path"]) bounds.add(p[0], p[1]);
  // Everything but the robot, the table included: the search is seen against the scene.
  for (const json& shape : plan["shapes"]) {
    if (shape["role"] == "robot") continue;
    const Eigen::Isometry3d pose = startPose(plan, shape);
    if (shape["type"] == "mesh") {
      for (const Eigen::Vector2d& p : meshOutline(shape, pose)) bounds.add(p.x(), p.y());
      continue;
    }
    Eigen::Vector2d half = Eigen::Vector2d::Constant(shape.value("radius", 0.0));
    if (shape["type"] == "box") {  // the turned rectangle's extent, as for any bounding box
      const Eigen::Vector2d size(shape["size"][0].get<double>(), shape["size"][1].get<double>());
      half = pose.linear().topLeftCorner<2, 2>().cwiseAbs() * size / 2.0;
    }
    const Eigen::Vector2d c = pose.translation().head<2>();
    bounds.add(c.x() - half.x(), c.y() - half.y());
    bounds.add(c.x() + half.x(), c.y() + half.y());
  }
  bounds.box.min().array() -= kMargin;
  bounds.box.max().array() += kMargin;
  return bounds;
}

/// Per tree state, a value in [0, 1]: its belief if recorded, else nearness to the goal.
std::vector<double> shades(const json& tree, const std::string& key) {
  std::vector<double> values;
  if (key == "belief") {
    for (const json& b : tree["belief"]) values.push_back(b.get<double>());
    return values;
  }
  double far = 1e-9;
  for (const json& d : tree["goal_distance"]) far = std::max(far, d.get<double>());
  for (const json& d : tree["goal_distance"]) values.push_back(1.0 - d.get<double>() / far);
  return values;
}

std::string treeLines(const json& tree, const std::vector<double>& shade) {
  std::string svg;
  const json& points = tree["end_effector"];
  const json& parents = tree["parent"];
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int parent = parents[i];
    if (parent < 0) continue;
    svg += fmt::format(
        R"svg(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="0.0015"/>)svg",
        points[parent][0].get<double>(), points[parent][1].get<double>(),
        points[i][0].get<double>(), points[i][1].get<double>(), ramp(shade[i]));
    svg += "\n";
  }
  for (std::size_t i = 0; i < points.size(); ++i)
    svg += fmt::format(R"svg(<circle cx="{}" cy="{}" r="0.003" fill="{}"/>)svg",
                       points[i][0].get<double>(), points[i][1].get<double>(), ramp(shade[i])) +
           "\n";
  return svg;
}

std::string pathLine(const json& path) {
  std::string points;
  for (const json& p : path)
    points += fmt::format("{:.4f},{:.4f} ", p[0].get<double>(), p[1].get<double>());
  return fmt::format(
      R"svg(<polyline points="{}" fill="none" stroke="#d62728" stroke-width="0.004" stroke-linejoin="round"/>)svg",
      points);
}

}  // namespace

std::string treeToSvg(const json& plan) {
  const Bounds bounds = drawingBounds(plan);
  const Eigen::Vector2d size = bounds.box.sizes();
  const double width = size.x() * kPixelsPerMetre, height = size.y() * kPixelsPerMetre;
  const json& tree = plan["tree"];
  const bool byBelief = tree.contains("belief");

  std::string svg = fmt::format(
      R"svg(<svg xmlns="http://www.w3.org/2000/svg" width="{:.0f}" height="{:.0f}" viewBox="0 0 {:.0f} {:.0f}">)svg",
      width, height + 50, width, height + 50);
  svg += "\n<rect width=\"100%\" height=\"100%\" fill=\"#f4f6f8\"/>\n";
  // World metres to pixels, y up (SVG's y points down).
  svg += fmt::format(
      R"svg(<g transform="translate(0 {:.1f}) scale({} {}) translate({:.4f} {:.4f})">)svg", height,
      kPixelsPerMetre, -kPixelsPerMetre, -bounds.box.min().x(), -bounds.box.min().y());
  svg += "\n";
  for (const json& shape : plan["shapes"]) {
    const std::string role = shape["role"];
    if (role == "robot") continue;
    const std::string style =
        role == "fixed" ? R"svg(fill="#dfe3e7" stroke="#9aa1a8" stroke-width="0.002")svg"
                        : fmt::format(R"svg(fill="none" stroke="{}" stroke-width="0.003")svg",
                                      roleColour(role));
    svg += outline(shape, startPose(plan, shape), style) + "\n";
  }
  svg += treeLines(tree, shades(tree, byBelief ? "belief" : "distance"));
  svg += pathLine(plan["goal"]["link_path"]) + "\n";
  const json& goal = plan["goal"]["position"];
  svg += fmt::format(
      R"svg(<circle cx="{}" cy="{}" r="{}" fill="none" stroke="#d62728" stroke-width="0.003" stroke-dasharray="0.01 0.006"/>)svg",
      goal[0].get<double>(), goal[1].get<double>(), plan["goal"]["tolerance"].get<double>());
  svg += "\n</g>\n";
  svg += fmt::format(
      R"svg(<text x="10" y="{:.0f}" font-family="sans-serif" font-size="13" fill="#263238">{}: {} tree states, coloured by {} (blue low, yellow high).</text>)svg",
      height + 22, plan["problem"]["name"].get<std::string>(), tree["end_effector"].size(),
      byBelief ? "belief" : "nearness to the goal");
  svg += fmt::format(
      R"svg(<text x="10" y="{:.0f}" font-family="sans-serif" font-size="13" fill="#263238">Red: the plan's path and the goal region. Outlines: objects at the start.</text>)svg",
      height + 40);
  svg += "\n</svg>\n";
  return svg;
}

}  // namespace kautham::apps
