// cutaway/cutters/terrain_opening.hpp — the terrain opened above a pipe network (Konev et al.
// 2018, §4): over a grid aligned with the terrain, D_p, the distance to the closest pipe (L1
// or Euclidean; to the lines themselves and interpolated, or, rough, between the texels the
// lines are drawn into, as the paper's texture); each terrain fragment compares it with a
// threshold t that shrinks with the camera distance (eq. 1), and draws terrain, an artificial
// thickness, or nothing (eqs. 2–3). Mirrored in src/cutters/terrain_opening/terrain_opening.glsl.
//
//   scene.cutters.enable<cutaway::TerrainOpeningOptions>() = {.terrain = "ground", .lines = {...}};
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cutaway/core/options.hpp"
#include "cutaway/geometry/mesh.hpp"

namespace cutaway {

struct TerrainOpeningOptions {
  static constexpr const char* kKey = "terrainOpening";
  std::string terrain;        // regular expression: the terrain objects' names (whole match)
  std::string buildings;      // regular expression: building objects ("" none)
  bool cutBuildings = false;  // buildings opened by the same rule, or left whole
  // The network in world coordinates (x, z), y up: scene CRS easting E and northing N map to
  // x = E − offset.x, z = −(N − offset.y), so north is −z.
  std::vector<std::vector<glm::vec2>> lines;
  int resolution = 1024;  // T: texels per side of the distance texture
  enum class Metric { L1, Euclidean } metric = Metric::L1;
  // Konev18's texture as the paper builds it: the network drawn into texels, distances
  // between texel centres, the nearest texel looked up (its "rough cutaway", zig-zag edges
  // of a texel's size); false: distances to the polylines themselves, bilinear (smooth).
  bool rough = false;
  float w = 0.015f;            // eq. 1: width of the opening
  float s = 10.0f;             // eq. 1: size; the opening closes at camera distance s²
  bool cameraDistance = true;  // false: t = w·s everywhere
  // Beyond the paper: the artificial thickness as a trench wall this many half-widths of the
  // opening (t · 255 texels) deep, where the view ray continued below the ground meets it;
  // 0: eq. 3's peek of one texel.
  float wall = 1.0f;
  std::optional<glm::vec3> thicknessColor;  // default kSoilColor
};
inline constexpr glm::vec3 kSoilColor{0.58f, 0.43f, 0.3f};
const OptionsSchema& terrainOpeningSchema();

// D_p over the terrain's extent: texel (i, j) covers x ∈ min.x + [i, i+1)·size.x/T and
// z ∈ min.y + [j, j+1)·size.y/T; values min(distance in texels, 255) / 255, scaled as the
// paper's 8-bit texture (0 on a pipe, 1 from 255 texels on) but kept in float. Rough: the
// distance from the texel's centre to the nearest drawn texel's; else to the nearest
// polyline itself.
struct TerrainField {
  glm::vec2 min{0.0f}, size{1.0f};  // world x, z
  int resolution = 0;
  bool nearest = false;          // rough: look up the nearest texel, else bilinear
  std::vector<float> distance;   // resolution², rows of increasing z
  // D_p at uv ∈ [0,1]²: the texel uv falls in, or bilinear between the four texel centres
  // around it (clamped to the edge texels).
  float at(glm::vec2 uv) const;
};
TerrainField terrainField(const TerrainOpeningOptions& options, const Bounds& terrainBounds);

// Eq. 1: t = w(s² − d_c)/s (or w·s without the camera-distance dependency).
float openingThreshold(const TerrainOpeningOptions& options, float cameraDistance);

enum class TerrainFate { Terrain, Thickness, Discard };
// Eqs. 2–3 for a terrain point p seen from `eye` (d_c = |eye − p|) along the view ray `ray`
// (p − eye, or the view direction when orthographic): terrain where D_p(P_uv) ≥ t. Else, with
// `wall` 0, eq. 3's peek one texel further along the ray's horizontal direction (ε = √2/T in
// texture space): thickness where D_p > t there. With `wall` > 0, the ray continued below the
// ground: thickness where, within the horizontal distance it covers while descending the
// wall's depth, it reaches D_p > t (the first such point, to 1/64 of the marching step, is the
// wall point); else discard. `wall`, if given, receives the thickness as shown: its world
// position, and its normal against D_p's gradient (central differences a texel apart, per
// world unit; where D_p is flat, against the ray's horizontal direction; else up).
struct TerrainWall {
  glm::vec3 point, normal;
};
TerrainFate terrainFate(const TerrainField& field, const TerrainOpeningOptions& options,
                        const glm::vec3& p, const glm::vec3& eye, const glm::vec3& ray,
                        TerrainWall* wall = nullptr);

}  // namespace cutaway
