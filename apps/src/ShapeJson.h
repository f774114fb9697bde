#pragma once

// How the plan file writes a shape: shared by its collision "shapes" and its "visuals".

#include <string>

#include <nlohmann/json.hpp>

#include "kautham/core/Geometry.h"
#include "kautham/core/MeshLoader.h"

namespace kautham::apps {

/// A box, cylinder, sphere or mesh as the viewer reads it ({"type": ...}); a mesh as loaded (not
/// its hull).
nlohmann::json shapeJson(const core::Shape& shape);

/// A triangle mesh as flat arrays, coordinates rounded to 0.1 mm: a viewer draws it, and it must
/// stay small. `file` is the mesh file's name, for people reading the plan.
nlohmann::json meshJson(const core::TriangleMesh& mesh, const std::string& file);

/// A pose as the plan file writes it: x y z qw qx qy qz.
nlohmann::json poseJson(const Eigen::Isometry3d& pose);

}  // namespace kautham::apps
