#include "InventorMesh.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <map>
#include <mutex>
#include <string>

#include <Inventor/SoDB.h>
#include <Inventor/SoInput.h>
#include <Inventor/SoPrimitiveVertex.h>
#include <Inventor/actions/SoCallbackAction.h>
#include <Inventor/errors/SoDebugError.h>
#include <Inventor/errors/SoReadError.h>
#include <Inventor/nodes/SoSeparator.h>
#include <Inventor/nodes/SoShape.h>

namespace kautham::core {

namespace {

// Coin keeps global state (its type system, error handlers): one file at a time.
std::mutex coinMutex;

struct Collector {
  Eigen::Vector3d scale;
  TriangleMesh mesh;
  std::map<std::array<float, 3>, int> index;  ///< joins corners that coincide exactly

  int vertex(const SbVec3f& p) {
    const std::array<float, 3> key{p[0], p[1], p[2]};
    const auto [it, inserted] = index.emplace(key, static_cast<int>(mesh.vertices.size()));
    if (inserted) mesh.vertices.emplace_back(scale.x() * p[0], scale.y() * p[1], scale.z() * p[2]);
    return it->second;
  }
};

void collectTriangle(void* data, SoCallbackAction* action, const SoPrimitiveVertex* v1,
                     const SoPrimitiveVertex* v2, const SoPrimitiveVertex* v3) {
  auto& collector = *static_cast<Collector*>(data);
  const SbMatrix& model = action->getModelMatrix();
  std::array<int, 3> corners{};
  const SoPrimitiveVertex* vertices[3] = {v1, v2, v3};
  for (int i = 0; i < 3; ++i) {
    SbVec3f world;
    model.multVecMatrix(vertices[i]->getPoint(), world);
    corners[static_cast<std::size_t>(i)] = collector.vertex(world);
  }
  if (corners[0] == corners[1] || corners[1] == corners[2] || corners[0] == corners[2]) return;
  collector.mesh.triangles.push_back(corners);
}

void keepFirstError(const SoError* error, void* data) {
  auto& message = *static_cast<std::string*>(data);
  if (message.empty()) message = error->getDebugString().getString();
}

void ignoreError(const SoError*, void*) {}

}  // namespace

bool isInventorFile(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".iv" || extension == ".wrl" || extension == ".vrml";
}

TriangleMesh loadInventorMesh(const std::filesystem::path& file, const Eigen::Vector3d& scale) {
  std::lock_guard<std::mutex> lock(coinMutex);
  if (!SoDB::isInitialized()) SoDB::init();
  // Coin reports read errors on the console; keep the first one for our message instead.
  std::string firstError;
  SoReadError::setHandlerCallback(keepFirstError, &firstError);
  SoDebugError::setHandlerCallback(ignoreError, nullptr);
  SoInput input;
  SoSeparator* root = nullptr;
  if (input.openFile(file.string().c_str(), TRUE)) {
    root = SoDB::readAll(&input);
    input.closeFile();
  }
  SoReadError::setHandlerCallback(nullptr, nullptr);
  if (!root) {
    // Coin's message starts with its own prefix and repeats the file name; keep the reason.
    while (!firstError.empty() && (firstError.back() == '\n' || firstError.back() == ' '))
      firstError.pop_back();
    throw MeshError("not a readable Open Inventor / VRML file" +
                    (firstError.empty() ? std::string() : " (Coin3D: " + firstError + ")"));
  }
  root->ref();
  Collector collector;
  collector.scale = scale;
  SoCallbackAction action;
  action.addTriangleCallback(SoShape::getClassTypeId(), collectTriangle, &collector);
  action.apply(root);
  root->unref();
  if (collector.mesh.triangles.empty())
    throw MeshError("the Open Inventor / VRML file holds no shape with faces");
  return std::move(collector.mesh);
}

}  // namespace kautham::core
