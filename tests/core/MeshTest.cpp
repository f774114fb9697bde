// Tests of mesh loading (Assimp), convex hulls (Qhull) and mesh geometry in URDFs, on the
// shipped mesh objects of models/objects.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "TestPaths.h"
#include "kautham/core/ConvexHull.h"
#include "kautham/core/Geometry.h"
#include "kautham/core/MeshLoader.h"
#include "kautham/core/MeshSimplify.h"
#include "kautham/core/UrdfLoader.h"

namespace kautham::core {
namespace {

namespace fs = std::filesystem;
using test::repoFile;

Eigen::AlignedBox3d boundsOf(const std::vector<Eigen::Vector3d>& points) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : points) box.extend(p);
  return box;
}

/// The hull is convex (every corner inside or on every face plane), its faces lie on their
/// planes, wind counter-clockwise around outward unit normals, and it holds every point.
void expectValidHull(const ConvexHull& hull, const std::vector<Eigen::Vector3d>& points) {
  ASSERT_GE(hull.vertices.size(), 4u);
  ASSERT_EQ(hull.faces.size(), hull.planes.size());
  ASSERT_GE(hull.faces.size(), 4u);
  const double tolerance = 1e-6;
  for (const Eigen::Vector3d& v : hull.vertices) EXPECT_TRUE(hull.contains(v, tolerance));
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : hull.vertices) centre += v;
  centre /= static_cast<double>(hull.vertices.size());
  for (std::size_t f = 0; f < hull.faces.size(); ++f) {
    const std::vector<int>& face = hull.faces[f];
    const Eigen::Vector3d n = hull.planes[f].head<3>();
    EXPECT_NEAR(n.norm(), 1.0, 1e-9);
    EXPECT_LT(n.dot(centre), hull.planes[f].w()) << "face " << f << " faces inwards";
    ASSERT_GE(face.size(), 3u);
    Eigen::Vector3d area = Eigen::Vector3d::Zero();  // twice the vector area of the polygon
    for (std::size_t k = 0; k < face.size(); ++k) {
      const Eigen::Vector3d& p = hull.vertices[face[k]];
      EXPECT_NEAR(n.dot(p), hull.planes[f].w(), tolerance) << "face " << f;
      area += p.cross(hull.vertices[face[(k + 1) % face.size()]]);
    }
    EXPECT_GT(area.dot(n), 0.0) << "face " << f << " is not counter-clockwise seen from outside";
  }
  for (const Eigen::Vector3d& p : points) EXPECT_TRUE(hull.contains(p, tolerance)) << p.transpose();
}

TEST(MeshLoader, ReadsTheBottleObj) {
  const TriangleMesh mesh = loadMesh(repoFile("models/objects/meshes/bottle.obj"));
  EXPECT_EQ(mesh.vertices.size(), 290u);  // 9 rings of 32 and the two cap centres
  EXPECT_EQ(mesh.triangles.size(), 576u);
  const Eigen::AlignedBox3d box = boundsOf(mesh.vertices);
  EXPECT_NEAR(box.min().z(), -0.125, 1e-6);
  EXPECT_NEAR(box.max().z(), 0.125, 1e-6);
  EXPECT_NEAR(box.max().x(), 0.035, 1e-6);
  EXPECT_NEAR(box.min().x(), -0.035, 1e-6);
  EXPECT_NEAR(box.max().y(), 0.035, 1e-6);
  for (const auto& t : mesh.triangles)
    for (int i : t) ASSERT_LT(static_cast<std::size_t>(i), mesh.vertices.size());
}

TEST(MeshLoader, ReadsTheWineGlassStlJoiningItsRepeatedCorners) {
  // A binary STL repeats each corner in every triangle: 768 triangles, 2304 corners, joined.
  const TriangleMesh mesh = loadMesh(repoFile("models/objects/meshes/wine_glass.stl"));
  EXPECT_EQ(mesh.vertices.size(), 386u);
  EXPECT_EQ(mesh.triangles.size(), 768u);
  const Eigen::AlignedBox3d box = boundsOf(mesh.vertices);
  EXPECT_NEAR(box.min().z(), -0.08, 1e-6);
  EXPECT_NEAR(box.max().z(), 0.08, 1e-6);
  EXPECT_NEAR(box.max().x(), 0.04, 1e-6);  // the bowl
}

TEST(MeshLoader, ScalesEachAxis) {
  const TriangleMesh mesh =
      loadMesh(repoFile("models/objects/meshes/bottle.obj"), Eigen::Vector3d(2.0, 1.0, 0.5));
  const Eigen::AlignedBox3d box = boundsOf(mesh.vertices);
  EXPECT_NEAR(box.max().x(), 0.07, 1e-6);
  EXPECT_NEAR(box.max().z(), 0.0625, 1e-6);
}

TEST(MeshLoader, TextIsNotAMesh) {
  EXPECT_THROW(loadMesh(repoFile("tests/data/malformed/meshes/not_a_mesh.stl")), MeshError);
  EXPECT_THROW(loadMesh(repoFile("tests/data/malformed/meshes/no_faces.obj")), MeshError);
}

TEST(MeshLoader, AVertexNotFiniteOrAbsurdlyFarIsNamed) {
  // Such a vertex was taken as a point: the hull then called the mesh "flat" or "too few points".
  const fs::path folder = fs::temp_directory_path() / ("kautham_nan_" + std::to_string(getpid()));
  fs::create_directories(folder);
  const auto message = [&](const std::string& third) {
    std::ofstream(folder / "t.obj")
        << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv " << third << "\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n";
    try {
      loadMesh(folder / "t.obj");
    } catch (const MeshError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message("0 0 1"), "");  // the tetrahedron itself loads
  EXPECT_NE(message("0 0 nan").find("is not a finite number"), std::string::npos)
      << message("0 0 nan");
  EXPECT_NE(message("0 0 1e30").find("lies more than 1 km from the origin"), std::string::npos)
      << message("0 0 1e30");
  fs::remove_all(folder);
}

TEST(ConvexHull, OfTheBottleIsConvexAndHoldsEveryVertex) {
  const TriangleMesh mesh = loadMesh(repoFile("models/objects/meshes/bottle.obj"));
  const ConvexHull hull = convexHull(mesh.vertices);
  expectValidHull(hull, mesh.vertices);
  EXPECT_LT(hull.vertices.size(), mesh.vertices.size());  // the neck's corners are inside
  // Coplanar facets are merged: the flat bottom is one face of 32 corners.
  bool bottom = false;
  for (std::size_t f = 0; f < hull.faces.size(); ++f)
    if (hull.planes[f].z() < -0.999) bottom = hull.faces[f].size() == 32;
  EXPECT_TRUE(bottom);
}

TEST(ConvexHull, OfTheWineGlassIsConvexAndHoldsEveryVertex) {
  const TriangleMesh mesh = loadMesh(repoFile("models/objects/meshes/wine_glass.stl"));
  expectValidHull(convexHull(mesh.vertices), mesh.vertices);
}

TEST(ConvexHull, OfACubeHasSixSquareFaces) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 8; ++i) points.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  points.emplace_back(0.5, 0.5, 0.5);  // inside: not a corner
  const ConvexHull hull = convexHull(points);
  expectValidHull(hull, points);
  EXPECT_EQ(hull.vertices.size(), 8u);
  ASSERT_EQ(hull.faces.size(), 6u);
  for (const auto& face : hull.faces) EXPECT_EQ(face.size(), 4u);
  EXPECT_FALSE(hull.contains({1.1, 0.5, 0.5}));
}

TEST(ConvexHull, FlatOrTooFewPointsHaveNone) {
  EXPECT_THROW(convexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}), DegenerateHullError);
  EXPECT_THROW(convexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5, 0.2, 0}}),
               DegenerateHullError);
  EXPECT_THROW(convexHull({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}}), DegenerateHullError);
}

TEST(UrdfMesh, TheBottleUrdfGetsItsMeshFromItsOwnFolder) {
  const KinematicModel model = loadUrdf(repoFile("models/objects/bottle.urdf"), 1.0, {});
  ASSERT_EQ(model.links.size(), 1u);
  ASSERT_EQ(model.links[0].collisions.size(), 1u);
  const auto* mesh = std::get_if<Mesh>(&model.links[0].collisions[0].shape);
  ASSERT_NE(mesh, nullptr);
  EXPECT_EQ(fs::weakly_canonical(mesh->data->source),
            fs::weakly_canonical(repoFile("models/objects/meshes/bottle.obj")));
  EXPECT_EQ(mesh->vertices().size(), 290u);
  expectValidHull(mesh->hull(), mesh->vertices());
  const Eigen::AlignedBox3d box =
      boundingBox(Shape(*mesh), Eigen::Isometry3d(Eigen::Translation3d(1, 2, 3)));
  EXPECT_NEAR(box.min().z(), 3 - 0.125, 1e-6);
  EXPECT_NEAR(box.max().x(), 1 + 0.035, 1e-6);
  EXPECT_NEAR(model.links[0].inertial.mass, 0.4, 1e-12);
}

TEST(UrdfMesh, ProblemScaleAndMeshScaleMultiply) {
  const fs::path folder = fs::temp_directory_path() / ("kautham_mesh_" + std::to_string(getpid()));
  fs::create_directories(folder / "shapes");
  fs::copy_file(repoFile("models/objects/meshes/bottle.obj"), folder / "shapes" / "b.obj",
                fs::copy_options::overwrite_existing);
  std::ofstream(folder / "tall.urdf") << R"(<?xml version="1.0"?>
<robot name="tall">
  <link name="body">
    <collision><geometry><mesh filename="shapes/b.obj" scale="1 1 2"/></geometry></collision>
  </link>
</robot>
)";
  const KinematicModel model = loadUrdf(folder / "tall.urdf", 0.5, {});
  const Shape& shape = model.links[0].collisions[0].shape;
  const Eigen::AlignedBox3d box = boundingBox(shape, Eigen::Isometry3d::Identity());
  EXPECT_NEAR(box.max().z(), 0.125, 1e-6);   // 0.125 * 2 * 0.5
  EXPECT_NEAR(box.max().x(), 0.0175, 1e-6);  // 0.035 * 0.5
  fs::remove_all(folder);
}

/// A UV sphere of radius 1 with `rings` x `segments` quads split into triangles.
TriangleMesh uvSphere(int rings, int segments) {
  TriangleMesh mesh;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double theta = M_PI * r / rings, phi = 2 * M_PI * s / segments;
      mesh.vertices.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                 std::cos(theta));
    }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const int a = r * segments + s, b = r * segments + (s + 1) % segments;
      mesh.triangles.push_back({a, a + segments, b});
      mesh.triangles.push_back({b, a + segments, b + segments});
    }
  return mesh;
}

TEST(MeshSimplify, CapsTheTrianglesAndKeepsTheShape) {
  const TriangleMesh sphere = uvSphere(100, 200);  // 40000 triangles
  const TriangleMesh small = simplifyMesh(sphere, 3000);
  EXPECT_LE(small.triangles.size(), 3000u);
  EXPECT_GT(small.triangles.size(), 1000u);  // the smallest cell that fits, not a coarse one
  for (const Eigen::Vector3d& v : small.vertices) EXPECT_NEAR(v.norm(), 1.0, 0.1);
  const Eigen::AlignedBox3d box = boundsOf(small.vertices);
  EXPECT_NEAR(box.sizes().minCoeff(), 2.0, 0.2);
  for (const auto& t : small.triangles)
    for (int corner : t) EXPECT_LT(corner, static_cast<int>(small.vertices.size()));
}

TEST(MeshSimplify, LeavesAMeshWithinTheCapAsItIs) {
  const TriangleMesh sphere = uvSphere(4, 8);
  const TriangleMesh same = simplifyMesh(sphere, 3000);
  EXPECT_EQ(same.triangles, sphere.triangles);
  EXPECT_EQ(same.vertices.size(), sphere.vertices.size());
}

}  // namespace
}  // namespace kautham::core
