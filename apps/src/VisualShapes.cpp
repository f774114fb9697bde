#include "VisualShapes.h"

#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "ShapeJson.h"
#include "kautham/core/Log.h"
#include "kautham/core/MeshSimplify.h"

namespace kautham::apps {

namespace {

using nlohmann::json;

/// Where a link is drawn: on a body of the layout (or static), placed in its frame.
struct LinkPlacement {
  int body = -1;  ///< -1: static, `pose` is in the world
  std::string owner;
  Eigen::Isometry3d pose;
};

/// The world records where each robot link is (physics/WorldBuilder): on a body, or built
/// into the static base.
std::optional<LinkPlacement> placeLink(const core::RobotInstance& robot,
                                       const physics::WorldLayout& layout, int link) {
  if (static_cast<std::size_t>(link) >= layout.robotLinks.size()) return std::nullopt;
  const physics::RobotLinkPlacement& at = layout.robotLinks[static_cast<std::size_t>(link)];
  const std::string owner = at.body < 0
                                ? robot.name + "/" + robot.model.links[robot.model.rootLink].name
                                : layout.bodies[static_cast<std::size_t>(at.body)].name;
  return LinkPlacement{at.body, owner, at.pose};
}

/// Reads visual meshes once per file and scale, simplified for the page.
class VisualMeshes {
 public:
  std::optional<json> get(const core::MeshFile& mesh) {
    const auto key = std::make_pair(
        mesh.file.string(), std::array<double, 3>{mesh.scale.x(), mesh.scale.y(), mesh.scale.z()});
    if (auto it = loaded_.find(key); it != loaded_.end()) return it->second;
    std::optional<json> result;
    try {
      const core::TriangleMesh full = core::loadMesh(mesh.file, mesh.scale);
      result =
          meshJson(core::simplifyMesh(full, kMaxVisualTriangles), mesh.file.filename().string());
      (*result)["triangles_in_file"] = full.triangles.size();
    } catch (const core::MeshError& e) {
      core::warnOnce(
          "visual " + mesh.file.string(),
          mesh.file.string() + ": " + e.what() + "; pictures show the link's collision shapes");
    }
    loaded_[key] = result;
    return result;
  }

 private:
  std::map<std::pair<std::string, std::array<double, 3>>, std::optional<json>> loaded_;
};

std::optional<json> visualShapeJson(const core::VisualShape& visual, VisualMeshes& meshes) {
  return std::visit(
      [&meshes](const auto& geometry) -> std::optional<json> {
        if constexpr (std::is_same_v<std::decay_t<decltype(geometry)>, core::MeshFile>)
          return meshes.get(geometry);
        else
          return shapeJson(core::Shape(geometry));
      },
      visual.geometry);
}

/// The link's visuals, or its collision shapes when it has none or one cannot be read.
std::vector<std::pair<json, Eigen::Isometry3d>> linkPicture(const core::Link& link,
                                                            VisualMeshes& meshes) {
  std::vector<std::pair<json, Eigen::Isometry3d>> picture;
  for (const core::VisualShape& visual : link.visuals) {
    std::optional<json> entry = visualShapeJson(visual, meshes);
    if (!entry) {
      picture.clear();
      break;
    }
    if (visual.colour) {
      json rgba = json::array();  // urdfdom's floats, to three decimals
      for (int k = 0; k < 4; ++k) rgba.push_back(std::round((*visual.colour)[k] * 1e3) / 1e3);
      (*entry)["colour"] = rgba;
    }
    picture.emplace_back(std::move(*entry), visual.origin);
  }
  if (!picture.empty()) return picture;
  for (const core::CollisionShape& collision : link.collisions)
    picture.emplace_back(shapeJson(collision.shape), collision.origin);
  return picture;
}

}  // namespace

json visualsJson(const core::Problem& problem, const physics::WorldLayout& layout) {
  const core::RobotInstance& robot = problem.robot;
  const core::KinematicModel& model = robot.model;
  json visuals = json::array();
  bool anyVisual = false;
  for (const core::Link& link : model.links) anyVisual = anyVisual || !link.visuals.empty();
  if (!anyVisual) return visuals;
  VisualMeshes meshes;
  for (std::size_t l = 0; l < model.links.size(); ++l) {
    const std::optional<LinkPlacement> place = placeLink(robot, layout, static_cast<int>(l));
    if (!place) continue;
    for (auto& [entry, origin] : linkPicture(model.links[l], meshes)) {
      entry["owner"] = place->owner;
      entry["link"] = model.links[l].name;
      entry["role"] = "robot";
      entry["body"] = place->body >= 0 ? json(place->body) : json(nullptr);
      entry["pose"] = poseJson(place->pose * origin);
      visuals.push_back(std::move(entry));
    }
  }
  return visuals;
}

}  // namespace kautham::apps
