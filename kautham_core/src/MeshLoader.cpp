#include "kautham/core/MeshLoader.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <string>

#include "InventorMesh.h"

namespace kautham::core {

namespace {

/// Appends the triangles of `node` and its children, placed by the accumulated transforms.
void collect(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent,
             const Eigen::Vector3d& scale, TriangleMesh& out) {
  const aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;  // points or lines only
    const int first = static_cast<int>(out.vertices.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = transform * mesh.mVertices[v];
      out.vertices.emplace_back(scale.x() * p.x, scale.y() * p.y, scale.z() * p.z);
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines left by triangulation
      out.triangles.push_back({first + static_cast<int>(face.mIndices[0]),
                               first + static_cast<int>(face.mIndices[1]),
                               first + static_cast<int>(face.mIndices[2])});
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c)
    collect(scene, *node.mChildren[c], transform, scale, out);
}

/// A scale with an odd number of negative factors mirrors the mesh, which turns its faces
/// inside out: reverse every triangle so that they stay counter-clockwise seen from outside.
TriangleMesh mirrorAware(TriangleMesh mesh, const Eigen::Vector3d& scale) {
  const int negative = (scale.x() < 0) + (scale.y() < 0) + (scale.z() < 0);
  if (negative % 2 == 1)
    for (auto& triangle : mesh.triangles) std::swap(triangle[1], triangle[2]);
  return mesh;
}

/// Throws MeshError naming the first vertex that is not a finite number, or lies absurdly far
/// (more than kFarthest from the link's origin, scaled): the hull and the physics would take it
/// as a point, and the error would blame the shape ("flat", "too few points") instead.
void requireFiniteVertices(const TriangleMesh& mesh) {
  constexpr double kFarthest = 1000.0;  // m
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const Eigen::Vector3d& p = mesh.vertices[v];
    if (p.allFinite() && p.cwiseAbs().maxCoeff() <= kFarthest) continue;
    throw MeshError(
        "vertex " + std::to_string(v) + " (" + std::to_string(p.x()) + ", " +
        std::to_string(p.y()) + ", " + std::to_string(p.z()) + ", scaled) " +
        (p.allFinite() ? "lies more than 1 km from the origin" : "is not a finite number") +
        ": the file is damaged, or its units are not metres (set the mesh's scale)");
  }
}

}  // namespace

TriangleMesh loadMesh(const std::filesystem::path& file, const Eigen::Vector3d& scale) {
  // Assimp reads no Open Inventor and only VRML 1 badly: those go to Coin3D.
  if (isInventorFile(file)) {
    TriangleMesh mesh = loadInventorMesh(file, scale);
    requireFiniteVertices(mesh);
    return mirrorAware(std::move(mesh), scale);
  }
  Assimp::Importer importer;
  // URDF meshes are in the link's frame as written: keep COLLADA's z-up data as it is.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  // Only positions matter: without normals, texture coordinates and colours, the corners that
  // the faces of STL and OBJ files repeat are joined into one vertex.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS,
                              aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                  aiComponent_COLORS | aiComponent_TEXCOORDS);
  const aiScene* scene =
      importer.ReadFile(file.string(), aiProcess_RemoveComponent | aiProcess_Triangulate |
                                           aiProcess_JoinIdenticalVertices);
  if (!scene || !scene->mRootNode)
    throw MeshError(std::string("not a readable mesh (") + importer.GetErrorString() + ")");
  TriangleMesh mesh;
  collect(*scene, *scene->mRootNode, aiMatrix4x4(), scale, mesh);
  if (mesh.triangles.empty()) throw MeshError("the mesh holds no triangles");
  requireFiniteVertices(mesh);
  return mirrorAware(std::move(mesh), scale);
}

}  // namespace kautham::core
