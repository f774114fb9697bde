#pragma once

// What the robot looks like (its URDF <visual>s) for the plan file and the viewer.

#include <cstddef>

#include <nlohmann/json.hpp>

#include "kautham/core/Problem.h"
#include "kautham/physics/WorldLayout.h"

namespace kautham::apps {

/// At most this many triangles per visual mesh in the plan file: the UR5's DAE meshes hold up to
/// 29k each (6.5 MB of files), which would make every plan and page several MB. Capped, the UR5's
/// visuals add about 0.45 MB to a plan file.
constexpr std::size_t kMaxVisualTriangles = 3000;

/// The planned robot's visual geometry as the plan file's "visuals": entries like its "shapes"
/// (type, owner, role, body, pose in the body frame or, for static links, in the world) plus
/// "link" and an optional "colour" (rgba). A link without <visual>, or whose visual mesh cannot
/// be read, is drawn with its collision shapes, so the visuals show the whole robot. Empty when
/// no link of the robot has a <visual>. Meshes are simplified to kMaxVisualTriangles.
nlohmann::json visualsJson(const core::Problem& problem, const physics::WorldLayout& layout);

}  // namespace kautham::apps
