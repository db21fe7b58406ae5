// Simplified versions of meshes (cutaway/geometry/simplify.hpp): the measured error against a
// brute-force two-sided distance, triangle counts, closedness, and where none are made.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "cutaway/geometry/simplify.hpp"
#include "cutaway/scene/scene.hpp"

using namespace cutaway;

namespace {

// A unit sphere of rings × sectors quads (closed), or its upper `rings` rings only (open:
// a cap with a border), with a radial bump pattern so that edge collapses cost unevenly.
Mesh bumpySphere(int rings, int sectors, bool open) {
  Mesh m;
  const float pi = 3.14159265f;
  const auto point = [&](int i, int j) {
    const float t = pi * float(i) / float(rings), p = 2.0f * pi * float(j) / float(sectors);
    const float r = 1.0f + 0.05f * std::sin(5.0f * t) * std::cos(3.0f * p);
    return r * glm::vec3(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
  };
  const int last = open ? rings / 2 : rings;
  m.positions.push_back(point(0, 0));
  for (int i = 1; i < last || (open && i == last); ++i)
    for (int j = 0; j < sectors; ++j) m.positions.push_back(point(i, j));
  const auto at = [&](int i, int j) { return unsigned(1 + (i - 1) * sectors + j % sectors); };
  for (int j = 0; j < sectors; ++j) {
    m.triangles.emplace_back(0u, at(1, j), at(1, j + 1));
    for (int i = 1; i + 1 < last || (open && i < last); ++i) {
      m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  if (!open) {
    m.positions.push_back(point(rings, 0));
    const unsigned south = unsigned(m.positions.size() - 1);
    for (int j = 0; j < sectors; ++j)
      m.triangles.emplace_back(south, at(rings - 1, j + 1), at(rings - 1, j));
  }
  computeVertexNormals(m);
  analyzeTopology(m);
  return m;
}

// Distance from p to triangle abc, by its closest point as barycentric coordinates clamped
// to the triangle: the unconstrained minimum if inside, else the best over the three edges.
double distance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                const glm::dvec3& c) {
  const auto onSegment = [&](const glm::dvec3& u, const glm::dvec3& v) {
    const glm::dvec3 d = v - u;
    const double t =
        glm::dot(d, d) > 0 ? std::clamp(glm::dot(p - u, d) / glm::dot(d, d), 0.0, 1.0) : 0.0;
    return glm::length(p - u - t * d);
  };
  const glm::dvec3 e0 = b - a, e1 = c - a, w = p - a;
  const double d00 = glm::dot(e0, e0), d01 = glm::dot(e0, e1), d11 = glm::dot(e1, e1);
  const double det = d00 * d11 - d01 * d01;
  if (det > 0) {
    const double s = (d11 * glm::dot(w, e0) - d01 * glm::dot(w, e1)) / det;
    const double t = (d00 * glm::dot(w, e1) - d01 * glm::dot(w, e0)) / det;
    if (s >= 0 && t >= 0 && s + t <= 1) return glm::length(p - (a + s * e0 + t * e1));
  }
  return std::min({onSegment(a, b), onSegment(b, c), onSegment(c, a)});
}

double toSurface(const glm::dvec3& p, const Mesh& m) {
  double nearest = INFINITY;
  for (const glm::uvec3& t : m.triangles)
    nearest = std::min(nearest, distance(p, m.positions[t.x], m.positions[t.y], m.positions[t.z]));
  return nearest;
}

// The documented error, brute force: the mesh's vertices to the version's surface, and the
// version's corners, edge midpoints and centroids to the mesh's.
double bruteForceError(const Mesh& mesh, const Mesh& version) {
  double worst = 0;
  for (const glm::vec3& p : mesh.positions) worst = std::max(worst, toSurface(p, version));
  for (const glm::uvec3& t : version.triangles) {
    const glm::dvec3 a = version.positions[t.x], b = version.positions[t.y],
                     c = version.positions[t.z];
    for (const glm::dvec3& p :
         {a, b, c, (a + b) / 2.0, (b + c) / 2.0, (c + a) / 2.0, (a + b + c) / 3.0})
      worst = std::max(worst, toSurface(p, mesh));
  }
  return worst;
}

}  // namespace

// Each version's error is the brute-force two-sided distance (to float rounding); versions
// halve the triangles, keep the mesh's own vertices and normals, and stay closed or open as
// the mesh is.
TEST(Simplify, VersionsHalveTheTrianglesAndMeasureTheirErrorAsBruteForceDoes) {
  for (const bool open : {false, true}) {
    const Mesh mesh = bumpySphere(24, 48, open);
    ASSERT_EQ(mesh.report.watertight, !open);
    const std::vector<SimplifiedMesh> versions = simplifiedVersions(mesh, 32);
    ASSERT_GE(versions.size(), 3u) << "open " << open;
    std::size_t before = mesh.triangles.size();
    for (const SimplifiedMesh& v : versions) {
      const std::size_t n = v.mesh.triangles.size();
      EXPECT_LE(4 * n, 3 * before);
      EXPECT_GE(n, before / 2 - 2);  // half, give or take a collapse that removes two
      before = n;
      EXPECT_EQ(v.mesh.report.watertight, !open);
      EXPECT_EQ(v.mesh.report.boundaryEdges == 0, !open);
      for (std::size_t i = 0; i < v.mesh.positions.size(); ++i) {
        bool found = false;  // a vertex of the mesh, normal and all
        for (std::size_t k = 0; k < mesh.positions.size() && !found; ++k)
          found = mesh.positions[k] == v.mesh.positions[i] && mesh.normals[k] == v.mesh.normals[i];
        EXPECT_TRUE(found) << "vertex " << i;
      }
      const double expected = bruteForceError(mesh, v.mesh);
      EXPECT_NEAR(v.error, expected, 1e-6 + 1e-5 * expected) << n << " triangles, open " << open;
      EXPECT_GT(v.error, 0.0f);
    }
    EXPECT_LE(8 * versions.back().mesh.triangles.size(), mesh.triangles.size());
    EXPECT_LT(versions.front().error, 0.05f) << "the first version is near the mesh";
  }
}

TEST(Simplify, NoVersionsOfAGridOrOfAFewTriangles) {
  Mesh grid;
  for (int r = 0; r < 40; ++r)
    for (int c = 0; c < 40; ++c)
      grid.positions.emplace_back(float(c), std::sin(float(r * c)), float(r));
  grid.normals.assign(grid.positions.size(), glm::vec3(0, 1, 0));
  grid.grid = GridLayout{40, 40};
  EXPECT_TRUE(simplifiedVersions(grid).empty());
  const Mesh few = bumpySphere(12, 24, false);  // 528 triangles
  EXPECT_TRUE(simplifiedVersions(few, 300).empty());
  EXPECT_FALSE(simplifiedVersions(few, 32).empty());
  // Seams everywhere (a coarse sphere's normals split at each crease): no step can halve it.
  const Mesh creased = bumpySphere(8, 16, false);
  ASSERT_GT(creased.positions.size(), 2 * (7 * 16 + 2) - 10);
  EXPECT_TRUE(simplifiedVersions(creased, 16).empty());
}

// addSimplifiedVersions gives every object drawn whole its mesh's versions, shares them
// between objects of one mesh and between calls, leaves objects with versions of their own
// alone, and forgets the meshes a later scene no longer has.
TEST(Simplify, ASceneTakesEachMeshsVersionsOnce) {
  Scene scene;
  const auto sphere = std::make_shared<const Mesh>(bumpySphere(24, 48, false));
  const auto cap = std::make_shared<const Mesh>(bumpySphere(24, 48, true));
  for (const auto& mesh : {sphere, sphere, cap}) {
    SceneObject o;
    o.mesh = mesh;
    scene.objects.push_back(o);
  }
  SceneObject own;
  own.mesh = cap;
  own.coarser.push_back({0.5f, sphere});
  scene.objects.push_back(own);
  SimplifiedCache cache;
  addSimplifiedVersions(scene, cache);
  EXPECT_EQ(cache.size(), 2u);
  ASSERT_FALSE(scene.objects[0].coarser.empty());
  EXPECT_EQ(scene.objects[0].coarser[0].mesh, scene.objects[1].coarser[0].mesh);
  EXPECT_EQ(scene.objects[0].coarser.size(), simplifiedVersions(*sphere).size());
  EXPECT_EQ(scene.objects[2].coarser.size(), simplifiedVersions(*cap).size());
  ASSERT_EQ(scene.objects[3].coarser.size(), 1u);
  EXPECT_EQ(scene.objects[3].coarser[0].mesh, sphere);
  const auto first = scene.objects[2].coarser[0].mesh;
  Scene again = scene;
  for (SceneObject& o : again.objects) o.coarser.clear();
  again.objects.erase(again.objects.begin(), again.objects.begin() + 2);
  addSimplifiedVersions(again, cache);
  EXPECT_EQ(again.objects[0].coarser[0].mesh, first) << "kept between calls";
  EXPECT_EQ(cache.size(), 1u) << "the sphere is gone from the scene";
}
