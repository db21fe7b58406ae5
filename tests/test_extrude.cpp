// Footprint extrusion (geometry/extrude.hpp): the ear-clipped roof covers exactly the
// shoelace area (holes subtracted), the prism is watertight and faces outwards, and its
// volume by the divergence theorem equals area × height — on squares, concave and holed
// footprints, either orientation, repeated and collinear nodes, and random star polygons.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cutaway/geometry/extrude.hpp"

using namespace cutaway;

namespace {

double triangulatedArea(const Footprint& f, const std::vector<glm::uvec3>& triangles) {
  std::vector<glm::vec2> all = f.outer;
  for (const auto& h : f.holes) all.insert(all.end(), h.begin(), h.end());
  double area = 0.0;
  for (const glm::uvec3& t : triangles) {
    const glm::dvec2 a = all[t.x], b = all[t.y], c = all[t.z];
    const double twice = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    EXPECT_GE(twice, 0.0) << "a clockwise triangle";
    area += 0.5 * twice;
  }
  return area;
}

double shoelaceArea(const Footprint& f) {
  double area = std::abs(twiceSignedArea(f.outer)) / 2.0;
  for (const auto& h : f.holes) area -= std::abs(twiceSignedArea(h)) / 2.0;
  return area;
}

// Divergence theorem: V = Σ (a · (b × c)) / 6 over outward triangles.
double volume(const Mesh& m) {
  double v = 0.0;
  for (const glm::uvec3& t : m.triangles)
    v += glm::dot(glm::dvec3(m.positions[t.x]),
                  glm::cross(glm::dvec3(m.positions[t.y]), glm::dvec3(m.positions[t.z]))) /
         6.0;
  return v;
}

// Checks every property of the file's header on one footprint; `tolerance` relative.
void checkFootprint(const Footprint& f, double tolerance = 1e-9) {
  const double area = shoelaceArea(f);
  EXPECT_NEAR(triangulatedArea(f, triangulateFootprint(f)), area, tolerance * area);
  const float base = -3.0f, top = 9.5f;
  Mesh m = extrudeFootprint(f, base, top);
  analyzeTopology(m);
  EXPECT_TRUE(m.report.watertight)
      << m.report.boundaryEdges << " boundary, " << m.report.nonManifoldEdges << " non-manifold, "
      << m.report.misorientedEdges << " misoriented edges";
  // Positive: outward. Float positions, so relative 1e-5.
  EXPECT_NEAR(volume(m), area * (top - base), 1e-5 * area * (top - base));
  // Flat normals agree with each triangle's own orientation.
  for (const glm::uvec3& t : m.triangles) {
    const glm::vec3 n =
        glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
    if (glm::length(n) > 1e-6f) EXPECT_GT(glm::dot(n, m.normals[t.x]), 0.0f);
  }
}

std::vector<glm::vec2> reversed(std::vector<glm::vec2> ring) {
  std::reverse(ring.begin(), ring.end());
  return ring;
}

}  // namespace

TEST(Extrude, SquareInEitherOrientation) {
  const std::vector<glm::vec2> square = {{0, 0}, {10, 0}, {10, 8}, {0, 8}};
  checkFootprint({square, {}});
  checkFootprint({reversed(square), {}});
  const Mesh m = extrudeFootprint({square, {}}, 0.0f, 12.0f);
  EXPECT_EQ(m.triangles.size(), 2u + 2u + 8u);  // roof, floor, four walls
}

TEST(Extrude, ConcaveLShapeAndComb) {
  checkFootprint({{{0, 0}, {6, 0}, {6, 2}, {2, 2}, {2, 7}, {0, 7}}, {}});
  std::vector<glm::vec2> comb = {{0, 0}, {9, 0}, {9, 5}};
  for (int k = 4; k >= 0; --k) {
    comb.emplace_back(2 * k + 1, 5);
    comb.emplace_back(2 * k + 1, 1);
    comb.emplace_back(2 * k, 1);
    comb.emplace_back(2 * k, 5);
  }
  comb.pop_back();
  comb.back() = {0, 5};
  checkFootprint({comb, {}});
  checkFootprint({reversed(comb), {}});
}

TEST(Extrude, HolesInEitherOrientation) {
  const std::vector<glm::vec2> outer = {{0, 0}, {20, 0}, {20, 12}, {0, 12}};
  const std::vector<glm::vec2> a = {{2, 2}, {6, 2}, {6, 6}, {2, 6}};
  const std::vector<glm::vec2> b = {{9, 3}, {14, 4}, {12, 9}};
  const std::vector<glm::vec2> c = {{15, 2}, {18, 2}, {18, 10}, {15, 10}, {16.5f, 6}};
  checkFootprint({outer, {a}});
  checkFootprint({outer, {a, reversed(b), c}});
  checkFootprint({reversed(outer), {reversed(a), b, reversed(c)}});
  // A courtyard whose bridge ray meets a vertex of the boundary exactly.
  checkFootprint({{{0, 0}, {10, 0}, {10, 4}, {12, 5}, {10, 6}, {10, 10}, {0, 10}},
                  {{{4, 4}, {4, 6}, {6, 5}}}});
}

// A "hole" with a node outside its outer ring (an invalid polygon: a GeoJSON ring beside the
// building) is left out; the block stays the closed prism of the outer ring, where it grew a
// lone open ring of walls; one touching it is kept.
TEST(Extrude, AHoleOutsideTheOuterRingIsLeftOut) {
  const std::vector<glm::vec2> outer = {{100, 100}, {150, 100}, {150, 150}, {100, 150}};
  const std::vector<glm::vec2> away = {{500, 500}, {520, 500}, {520, 520}, {500, 520}};
  const std::vector<glm::vec2> across = {{140, 120}, {160, 120}, {160, 130}, {140, 130}};
  const Mesh alone = extrudeFootprint({outer, {}}, 0.0f, 10.0f);
  for (const auto& hole : {away, across}) {
    Mesh m = extrudeFootprint({outer, {hole}}, 0.0f, 10.0f);
    analyzeTopology(m);
    EXPECT_TRUE(m.report.watertight) << m.report.boundaryEdges << " boundary edges";
    EXPECT_EQ(m.positions, alone.positions);
    EXPECT_EQ(m.triangles, alone.triangles);
  }
  // A hole touching the outer ring mid-edge, its node a float step to either side of the
  // edge, is still a hole.
  const std::vector<glm::vec2> slanted = {{0, 0}, {30.7f, 10.3f}, {10.1f, 40.9f}};
  const std::size_t plain = extrudeFootprint({slanted, {}}, 0.0f, 1.0f).triangles.size();
  for (const double t : {0.3, 0.45, 0.61, 0.77}) {
    const glm::vec2 touch(t * glm::dvec2(slanted[1]));
    const Footprint f{slanted, {{touch, touch + glm::vec2(-1, 3), touch + glm::vec2(-3, 2)}}};
    EXPECT_GT(extrudeFootprint(f, 0.0f, 1.0f).triangles.size(), plain) << t;
  }
  const std::vector<glm::vec2> inside = {{110, 120}, {120, 120}, {120, 130}};
  checkFootprint({outer, {inside}});
  EXPECT_GT(extrudeFootprint({outer, {inside}}, 0.0f, 10.0f).triangles.size(),
            alone.triangles.size());
}

// Valid polygons whose holes touch the outer ring or each other at a point (a vertex, a node
// mid-edge, a shared stretch of edge): the block is still watertight (it was pinched along a
// vertical edge, or open at a T-junction), with the footprint's area to within its sliver.
TEST(Extrude, HolesTouchingTheOuterRingOrEachOtherGiveWatertightBlocks) {
  const std::vector<glm::vec2> outer = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  const std::vector<Footprint> footprints = {
      {outer, {{{0, 0}, {5, 2}, {2, 5}}}},                            // at the outer ring's corner
      {outer, {{{5, 0}, {7, 3}, {3, 3}}}},                            // mid-edge
      {outer, {{{3, 0}, {6, 0}, {5, 3}}}},                            // along an edge
      {outer, {{{2, 2}, {5, 5}, {2, 6}}, {{5, 5}, {8, 2}, {8, 6}}}},  // at each other
      // the outer ring's notch tip on the hole's edge
      {{{0, 0}, {10, 0}, {10, 10}, {5.5f, 10}, {5, 6}, {4.5f, 10}, {0, 10}},
       {{{3, 3}, {7, 3}, {7, 6}, {3, 6}}}},
      {reversed(outer), {reversed({{0, 0}, {5, 2}, {2, 5}})}},
  };
  for (std::size_t i = 0; i < footprints.size(); ++i) {
    Mesh m = extrudeFootprint(footprints[i], 0.0f, 5.0f);
    analyzeTopology(m);
    EXPECT_TRUE(m.report.watertight) << i << ": " << m.report.boundaryEdges << " boundary, "
                                     << m.report.nonManifoldEdges << " non-manifold edges";
    const double area = shoelaceArea(footprints[i]);
    EXPECT_NEAR(volume(m), area * 5.0, 1e-4 * area * 5.0) << i;
  }
}

TEST(Extrude, RepeatedAndCollinearNodesAreRemoved) {
  const Footprint f{{{0, 0}, {0, 0}, {5, 0}, {10, 0}, {10, 0}, {10, 5}, {10, 10}, {0, 10}, {0, 0}},
                    {{{2, 2}, {3, 2}, {4, 2}, {4, 4}, {2, 4}, {2, 2}}}};
  checkFootprint(f);
  const Mesh m = extrudeFootprint(f, 0.0f, 1.0f);
  // 4 + 4 nodes left: 8 roof and 8 floor triangles (n + 2·holes − 2), 8 walls of 2.
  EXPECT_EQ(m.triangles.size(), 2u * 8u + 2u * 8u);
  // Nothing with area: no mesh.
  EXPECT_TRUE(extrudeFootprint({{{0, 0}, {1, 1}, {2, 2}}, {}}, 0.0f, 1.0f).triangles.empty());
  EXPECT_TRUE(triangulateFootprint({{{0, 0}, {1, 0}}, {}}).empty());
}

TEST(Extrude, RandomStarPolygonsWithAndWithoutHoles) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> radius(0.3f, 1.0f);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 3 + trial % 60;
    Footprint f;
    for (int i = 0; i < n; ++i) {
      const float angle = 6.2831853f * float(i) / float(n);
      const float r = 40.0f * radius(random);
      f.outer.emplace_back(100.0f + r * std::cos(angle), -50.0f + r * std::sin(angle));
    }
    if (trial % 2) {  // a small hole around the star's centre, which lies inside every ray
      std::vector<glm::vec2> hole;
      for (int i = 0; i < 7; ++i) {
        const float angle = -6.2831853f * float(i) / 7.0f + 0.1f * float(trial);
        hole.emplace_back(100.0f + 8.0f * std::cos(angle), -50.0f + 8.0f * std::sin(angle));
      }
      f.holes.push_back(hole);
    }
    SCOPED_TRACE("trial " + std::to_string(trial) + ", " + std::to_string(n) + " nodes");
    checkFootprint(f, 1e-6);
  }
}
