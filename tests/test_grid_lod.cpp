// Chunked level of detail of grid meshes (cutaway/geometry/grid_lod.hpp): which meshes get
// one, the geometric errors against their closed form, the levels a view picks, and that
// every mix of levels leaves the surface closed.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <tuple>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "cutaway/geometry/grid_lod.hpp"
#include "cutaway/scene/benchmark_city.hpp"

namespace {

using cutaway::GridLod;
using cutaway::Mesh;
using Pattern = std::array<std::array<int, 3>, 2>;

// The benchmark city's cells, a raster terrain's, and cells split along the other diagonal.
constexpr Pattern kCity{{{0, 1, 2}, {1, 3, 2}}};
constexpr Pattern kRaster{{{0, 2, 1}, {1, 2, 3}}};
constexpr Pattern kMainDiagonal{{{0, 1, 3}, {0, 3, 2}}};

// A grid of `columns × rows` nodes one unit apart in x and z, at heights h(c, r).
template <class Height>
Mesh gridMesh(int columns, int rows, const Pattern& pattern, Height h) {
  Mesh m;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      m.positions.emplace_back(float(c), h(c, r), float(r));
      m.normals.emplace_back(0.0f, 1.0f, 0.0f);
    }
  for (int r = 0; r + 1 < rows; ++r)
    for (int c = 0; c + 1 < columns; ++c) {
      const unsigned n[4] = {unsigned(r * columns + c), unsigned(r * columns + c + 1),
                             unsigned((r + 1) * columns + c), unsigned((r + 1) * columns + c + 1)};
      for (const auto& t : pattern) m.triangles.emplace_back(n[t[0]], n[t[1]], n[t[2]]);
    }
  m.grid = cutaway::GridLayout{columns, rows};
  return m;
}

Mesh flatGrid(int columns, int rows, const Pattern& pattern = kCity) {
  return gridMesh(columns, rows, pattern, [](int, int) { return 0.0f; });
}

TEST(GridLod, OnlyAMeshLaidOutAsItsGridSaysGetsOne) {
  for (const Pattern& p : {kCity, kRaster, kMainDiagonal})
    EXPECT_TRUE(GridLod::build(flatGrid(70, 9, p)));
  Mesh noGrid = flatGrid(5, 5);
  noGrid.grid.reset();
  EXPECT_FALSE(GridLod::build(noGrid));
  Mesh wrongCount = flatGrid(5, 5);
  wrongCount.grid->rows = 4;
  EXPECT_FALSE(GridLod::build(wrongCount));
  Mesh lostTriangle = flatGrid(5, 5);
  lostTriangle.triangles.pop_back();
  EXPECT_FALSE(GridLod::build(lostTriangle));
  // One cell split along the other diagonal, or wound the other way.
  Mesh otherSplit = flatGrid(5, 5);
  const Mesh main = flatGrid(5, 5, kMainDiagonal);
  otherSplit.triangles[10] = main.triangles[10], otherSplit.triangles[11] = main.triangles[11];
  EXPECT_FALSE(GridLod::build(otherSplit));
  Mesh flipped = flatGrid(5, 5);
  std::swap(flipped.triangles[7].y, flipped.triangles[7].z);
  EXPECT_FALSE(GridLod::build(flipped));
  // Appending makes a mesh that is no grid.
  Mesh appended = flatGrid(5, 5);
  appended.append(flatGrid(2, 2), glm::mat4(1.0f));
  EXPECT_FALSE(appended.grid);
}

// A grid may leave its triangles implied by its layout's cell: the same triangles, in the same
// order, the same levels of detail, and an appended copy stores them.
TEST(GridLod, ImpliedTrianglesAreTheStoredOnes) {
  for (const Pattern& p : {kCity, kRaster, kMainDiagonal}) {
    const Mesh stored =
        gridMesh(70, 9, p, [](int c, int r) { return std::sin(0.3f * float(c)) * float(r); });
    Mesh implied = stored;
    implied.triangles.clear();
    implied.grid->cell = p;
    ASSERT_TRUE(implied.impliedTriangles());
    ASSERT_EQ(implied.triangleCount(), stored.triangles.size());
    for (std::size_t i = 0; i < stored.triangles.size(); ++i)
      ASSERT_EQ(implied.triangle(i), stored.triangles[i]) << i;
    const auto a = GridLod::build(stored), b = GridLod::build(implied);
    ASSERT_TRUE(a && b);
    for (int mix = 0; mix < 8; ++mix) {
      std::vector<std::uint8_t> levels(std::size_t(a->chunkCount()));
      for (std::size_t i = 0; i < levels.size(); ++i)
        levels[i] = std::uint8_t((i * 5 + std::size_t(mix) * 3) % GridLod::kLevels);
      EXPECT_EQ(a->triangles(levels), b->triangles(levels));
    }
    Mesh appended;
    appended.append(implied, glm::mat4(1.0f));
    EXPECT_EQ(appended.triangles, stored.triangles);
    implied.append(flatGrid(2, 2), glm::mat4(1.0f));  // the grid's own triangles kept
    EXPECT_EQ(implied.triangles.size(), stored.triangles.size() + 2);
    EXPECT_FALSE(implied.grid);
  }
  // A grid whose stored triangles are all dropped as degenerate (a flat line of nodes) is no
  // grid, not one whose triangles are implied.
  Mesh collapsed = gridMesh(4, 3, kCity, [](int, int) { return 0.0f; });
  for (glm::vec3& p : collapsed.positions) p.z = 0.0f;
  EXPECT_EQ(cutaway::dropDegenerateTriangles(collapsed), 12u);
  EXPECT_FALSE(collapsed.grid);
  EXPECT_EQ(collapsed.triangleCount(), 0u);
  // A cell the layout does not split in two gets no level of detail.
  Mesh bad = flatGrid(5, 5);
  bad.triangles.clear();
  bad.grid->cell = {{{0, 1, 2}, {0, 1, 2}}};
  EXPECT_FALSE(GridLod::build(bad));
  bad.grid->cell = {{{0, 1, 4}, {1, 3, 2}}};
  EXPECT_FALSE(GridLod::build(bad));
}

TEST(GridLod, ALevelsErrorIsTheLargestDistanceToItsSurface) {
  // h = a c²: between kept nodes s apart the level's surface is the chord, which lies
  // a t (s − t) above the node t past the cell's start: ε_l = a (2^l / 2)² = a 4^(l−1).
  constexpr float a = 0.01f;
  for (const Pattern& p : {kCity, kRaster, kMainDiagonal}) {
    const auto lod =
        GridLod::build(gridMesh(129, 65, p, [](int c, int) { return a * float(c * c); }));
    ASSERT_TRUE(lod);
    ASSERT_EQ(lod->chunkCount(), 2);
    for (int chunk = 0; chunk < 2; ++chunk) {
      EXPECT_EQ(lod->error(chunk, 0), 0.0f);
      for (int l = 1; l < GridLod::kLevels; ++l)
        EXPECT_NEAR(lod->error(chunk, l), a * std::pow(4.0f, float(l - 1)),
                    1e-3f * std::pow(4.0f, float(l)))
            << "chunk " << chunk << ", level " << l;
    }
  }
  // A plane is exact at every level, even on the partial chunk at the grid's end.
  const auto plane = GridLod::build(
      gridMesh(100, 30, kRaster, [](int c, int r) { return 0.5f * float(c) - 0.25f * float(r); }));
  ASSERT_TRUE(plane);
  for (int chunk = 0; chunk < plane->chunkCount(); ++chunk)
    for (int l = 0; l < GridLod::kLevels; ++l) EXPECT_NEAR(plane->error(chunk, l), 0.0f, 1e-4f);
}

// Every edge of the drawn triangles: interior edges used twice in opposite directions, and an
// edge used once lies on the grid's outer border (a crack or a T-junction would leave a single
// edge inside). Every triangle keeps the pattern's orientation, and together they cover the
// grid's area once.
void expectClosedCover(const GridLod& lod, const Mesh& m, const std::vector<std::uint8_t>& levels,
                       float orientation) {
  const std::vector<glm::uvec3> triangles = lod.triangles(levels);
  const int columns = m.grid->columns, rows = m.grid->rows;
  std::map<std::pair<unsigned, unsigned>, int> edges;  // directed edge → uses
  double area = 0.0;
  for (const glm::uvec3& t : triangles) {
    const glm::vec3 a = m.positions[t.x], b = m.positions[t.y], c = m.positions[t.z];
    const double signedArea = 0.5 * double((b.x - a.x) * (c.z - a.z) - (b.z - a.z) * (c.x - a.x));
    ASSERT_GT(signedArea * orientation, 0.0) << "a folded or degenerate triangle";
    area += std::abs(signedArea);
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  }
  EXPECT_NEAR(area, double(columns - 1) * double(rows - 1), 1e-6);
  const auto onBorder = [&](unsigned n) {
    const int c = int(n) % columns, r = int(n) / columns;
    return std::pair{c == 0 || c == columns - 1, r == 0 || r == rows - 1};
  };
  for (const auto& [edge, uses] : edges) {
    ASSERT_EQ(uses, 1) << "an edge drawn twice in one direction";
    if (edges.count({edge.second, edge.first})) continue;
    const auto [ca, ra] = onBorder(edge.first);
    const auto [cb, rb] = onBorder(edge.second);
    const int c0 = int(edge.first) % columns, c1 = int(edge.second) % columns;
    const int r0 = int(edge.first) / columns, r1 = int(edge.second) / columns;
    const bool alongBorder = (ca && cb && c0 == c1) || (ra && rb && r0 == r1);
    ASSERT_TRUE(alongBorder) << "a crack between nodes " << edge.first << " and " << edge.second;
  }
}

TEST(GridLod, EveryMixOfLevelsLeavesTheSurfaceClosed) {
  std::mt19937 random(7);
  // Chunks of 64 cells and partial ones of 21, 33, 1, 2, 5 and 35 cells.
  const std::pair<int, int> sizes[] = {{150, 98}, {130, 66}, {67, 70}, {100, 100}};
  for (const auto& [columns, rows] : sizes)
    for (const Pattern& p : {kCity, kRaster, kMainDiagonal}) {
      const Mesh m =
          gridMesh(columns, rows, p, [](int c, int r) { return std::sin(0.1f * float(c * r)); });
      const auto lod = GridLod::build(m);
      ASSERT_TRUE(lod);
      const std::size_t chunks = std::size_t(lod->chunkCount());
      // The pattern's orientation in the grid's (x, z) plane.
      const glm::vec3 a = m.positions[m.triangles[0].x], b = m.positions[m.triangles[0].y],
                      c = m.positions[m.triangles[0].z];
      const float orientation =
          (b.x - a.x) * (c.z - a.z) - (b.z - a.z) * (c.x - a.x) > 0 ? 1.0f : -1.0f;
      for (int l = 0; l < GridLod::kLevels; ++l)
        expectClosedCover(*lod, m, std::vector<std::uint8_t>(chunks, std::uint8_t(l)), orientation);
      // At level 0 everywhere: the mesh's own triangles.
      std::vector<glm::uvec3> full = lod->triangles(std::vector<std::uint8_t>(chunks, 0)),
                              own = m.triangles;
      const auto order = [](const glm::uvec3& x, const glm::uvec3& y) {
        return std::tie(x.x, x.y, x.z) < std::tie(y.x, y.y, y.z);
      };
      std::sort(full.begin(), full.end(), order), std::sort(own.begin(), own.end(), order);
      EXPECT_EQ(full, own);
      std::uniform_int_distribution<int> level(0, GridLod::kLevels - 1);
      for (int trial = 0; trial < 100; ++trial) {
        std::vector<std::uint8_t> levels(chunks);
        for (auto& l : levels) l = std::uint8_t(level(random));
        expectClosedCover(*lod, m, levels, orientation);
        if (HasFatalFailure()) return;
      }
    }
}

TEST(GridLod, AViewDrawsEachChunkAtTheCoarsestLevelWithinThePixelError) {
  const Mesh m = gridMesh(
      257, 257, kCity, [](int c, int r) { return 0.002f * float(c * c) + 0.001f * float(r * r); });
  const auto lod = GridLod::build(m);
  ASSERT_TRUE(lod);
  GridLod::View view;
  view.eye = {128.0f, 150.0f, 450.0f};  // every chunk in view
  const glm::mat4 lookAt =
      glm::lookAt(view.eye, glm::vec3(128.0f, 0.0f, 128.0f), glm::vec3(0, 1, 0));
  view.projection = glm::perspective(glm::radians(60.0f), 1.0f, 1.0f, 2000.0f);
  view.viewProjection = view.projection * lookAt;
  view.viewportHeight = 600.0f;
  view.pixelError = 0.5f;
  const float k = 0.5f * view.viewportHeight / std::tan(glm::radians(30.0f));
  const std::vector<std::uint8_t> levels = lod->select(view);
  bool someCoarse = false, someFine = false;
  for (int chunk = 0; chunk < lod->chunkCount(); ++chunk) {
    const cutaway::Bounds& b = lod->chunkBounds(chunk);
    const float d = glm::length(glm::max(glm::max(b.min - view.eye, view.eye - b.max), 0.0f));
    const int l = levels[std::size_t(chunk)];
    EXPECT_LE(lod->error(chunk, l) * k / d, view.pixelError) << "chunk " << chunk;
    if (l + 1 < GridLod::kLevels)
      EXPECT_GT(lod->error(chunk, l + 1) * k / d, view.pixelError) << "chunk " << chunk;
    someCoarse |= l > 0, someFine |= l < GridLod::kLevels - 1;
  }
  EXPECT_TRUE(someCoarse && someFine);
  // τ = 0 keeps every triangle; a view turned away draws every chunk at its coarsest level.
  view.pixelError = 0.0f;
  EXPECT_EQ(lod->triangles(lod->select(view)).size(), m.triangles.size());
  view.viewProjection =
      view.projection * glm::lookAt(view.eye, view.eye + glm::vec3(0, 0, 1), glm::vec3(0, 1, 0));
  for (std::uint8_t l : lod->select(view)) EXPECT_EQ(l, GridLod::kLevels - 1);
}

TEST(GridLod, TheBenchmarkCitysTerrainIsAGrid) {
  const cutaway::Scene city = cutaway::benchmarkCity({});
  ASSERT_FALSE(city.objects.empty());
  EXPECT_TRUE(GridLod::build(*city.objects[0].mesh));
}

}  // namespace
