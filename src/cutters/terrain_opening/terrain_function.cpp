// Konev18 §4 on the CPU: the distance texture and eqs. 1–3, mirrored per fragment by
// terrain_opening.glsl.
#include <algorithm>
#include <cmath>

#include "cutaway/cutters/terrain_opening.hpp"
#include "cutaway/fields/distance_transform.hpp"

namespace cutaway {

namespace {
constexpr float kFar = 255.0f;  // texels: D_p = 1 from here on, the paper's 8-bit white
}  // namespace

float TerrainField::at(glm::vec2 uv) const {
  const auto texel = [&](int i, int j) {
    i = std::clamp(i, 0, resolution - 1), j = std::clamp(j, 0, resolution - 1);
    return distance[std::size_t(j) * std::size_t(resolution) + std::size_t(i)];
  };
  // Clamped before the conversion to int, which would overflow far outside; the clamp
  // changes no value, the edge texels extend beyond the grid.
  const float n = float(resolution);
  const glm::vec2 g = glm::clamp(uv * n, glm::vec2(-1.0f), glm::vec2(n + 1.0f));
  if (nearest) return texel(int(std::floor(g.x)), int(std::floor(g.y)));
  const glm::vec2 c = g - 0.5f;  // texel centres at (i + ½)/T
  const glm::vec2 base = glm::floor(c), f = c - base;
  const int i = int(base.x), j = int(base.y);
  const float bottom = texel(i, j) + f.x * (texel(i + 1, j) - texel(i, j));
  const float top = texel(i, j + 1) + f.x * (texel(i + 1, j + 1) - texel(i, j + 1));
  return bottom + f.y * (top - bottom);
}

TerrainField terrainField(const TerrainOpeningOptions& options, const Bounds& terrain) {
  TerrainField f;
  f.min = {terrain.min.x, terrain.min.z};
  f.size = glm::max(glm::vec2(terrain.max.x, terrain.max.z) - f.min, glm::vec2(1e-6f));
  f.resolution = options.resolution;
  f.nearest = options.rough;
  std::vector<fields::GridSegment> segments;
  const float t = float(f.resolution);
  for (const auto& line : options.lines)
    for (std::size_t k = 1; k < line.size(); ++k) {
      const glm::vec2 a = (line[k - 1] - f.min) / f.size * t, b = (line[k] - f.min) / f.size * t;
      segments.push_back({{a.x, a.y}, {b.x, b.y}});
    }
  const bool l1 = options.metric == TerrainOpeningOptions::Metric::L1;
  fields::DistanceField d;
  if (options.rough) {
    // The network drawn into the grid (Konev18: "drawn with black lines onto a white
    // texture"), then the distance between texel centres.
    const fields::SeedMask seeds = fields::rasterizeSegments(f.resolution, f.resolution, segments);
    d = l1 ? fields::l1DistanceTransform(seeds) : fields::euclideanDistanceTransform(seeds);
  } else {
    d = fields::segmentDistanceField(f.resolution, f.resolution, segments,
                                     l1 ? fields::Metric::L1 : fields::Metric::Euclidean, kFar);
  }
  f.distance.resize(d.distance.size());
  for (std::size_t i = 0; i < d.distance.size(); ++i)
    f.distance[i] = std::min(d.distance[i], kFar) / kFar;
  return f;
}

float openingThreshold(const TerrainOpeningOptions& o, float cameraDistance) {
  if (!o.cameraDistance) return o.w * o.s;
  return o.w * (o.s * o.s - cameraDistance) / o.s;  // eq. 1
}

TerrainFate terrainFate(const TerrainField& field, const TerrainOpeningOptions& options,
                        const glm::vec3& p, const glm::vec3& eye, const glm::vec3& forward) {
  const glm::vec2 uv = (glm::vec2(p.x, p.z) - field.min) / field.size;
  const float t = openingThreshold(options, glm::length(eye - p));
  if (field.at(uv) >= t) return TerrainFate::Terrain;  // eq. 2
  // The view's horizontal direction in texture space (y, the height, is ignored).
  glm::vec2 v(forward.x / field.size.x, forward.z / field.size.y);
  const float len = glm::length(v);
  v = len > 0.0f ? v / len : glm::vec2(0.0f);
  const float epsilon = std::sqrt(2.0f) / float(field.resolution);
  return field.at(uv + v * epsilon) > t ? TerrainFate::Thickness : TerrainFate::Discard;  // eq. 3
}

}  // namespace cutaway
