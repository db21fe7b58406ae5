// Konev18 §4 on the CPU: the distance texture and eqs. 1–3, mirrored per fragment by
// terrain_opening.glsl.
#include <algorithm>
#include <cmath>
#include <utility>

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
  f.distance = std::move(d.distance);
  for (float& v : f.distance) v = std::min(v, kFar) / kFar;
  return f;
}

float openingThreshold(const TerrainOpeningOptions& o, float cameraDistance) {
  if (!o.cameraDistance) return o.w * o.s;
  return o.w * (o.s * o.s - cameraDistance) / o.s;  // eq. 1
}

TerrainFate terrainFate(const TerrainField& field, const TerrainOpeningOptions& options,
                        const glm::vec3& p, const glm::vec3& eye, const glm::vec3& ray,
                        TerrainWall* wall) {
  const glm::vec2 uv = (glm::vec2(p.x, p.z) - field.min) / field.size;
  const float t = openingThreshold(options, glm::length(eye - p));
  if (field.at(uv) >= t) return TerrainFate::Terrain;  // eq. 2
  const float across = glm::length(glm::vec2(ray.x, ray.z));
  // The ray's horizontal direction in the world, and per world unit in texture space.
  const glm::vec2 along = across > 0.0f ? glm::vec2(ray.x, ray.z) / across : glm::vec2(0.0f);
  const glm::vec2 perUnit = along / field.size;
  const float n = float(field.resolution);
  float found = -1.0f;  // world distance along `along` to the thickness
  if (options.wall == 0.0f) {
    // Eq. 3's peek, ε = √2/T along the view's horizontal direction in texture space.
    const float len = glm::length(perUnit);
    const glm::vec2 v = len > 0.0f ? perUnit / len : glm::vec2(0.0f);
    if (field.at(uv + v * (std::sqrt(2.0f) / n)) > t) found = 0.0f;
  } else if (ray.y < 0.0f && across > 0.0f) {
    // The wall H = wall · t · 255 texels deep; the ray covers `reach` horizontally meanwhile.
    const float texel = std::sqrt(field.size.x * field.size.y) / n;
    const float reach = options.wall * t * kFar * texel * across / -ray.y;
    const int steps = int(std::clamp(std::ceil(reach / texel), 1.0f, 64.0f));
    const float step = reach / float(steps);
    float below = 0.0f;
    for (int k = 1; k <= steps && found < 0.0f; ++k) {
      const float d = float(k) * step;
      if (field.at(uv + perUnit * d) > t)
        found = d;
      else
        below = d;
    }
    for (int k = 0; k < 6 && found > 0.0f; ++k) {  // bisection: the crossing within a step
      const float mid = 0.5f * (below + found);
      (field.at(uv + perUnit * mid) > t ? found : below) = mid;
    }
  }
  if (found < 0.0f) return TerrainFate::Discard;  // eq. 3
  if (wall) {
    wall->point = found > 0.0f ? p + ray * (found / across) : p;
    // Beyond the paper (its §4 suggestion): lit as a wall facing the closest pipe.
    const glm::vec2 at = uv + perUnit * found;
    const float h = 1.0f / n;  // central differences a texel apart, in texture space
    const glm::vec2 g =
        glm::vec2(field.at(at + glm::vec2(h, 0.0f)) - field.at(at - glm::vec2(h, 0.0f)),
                  field.at(at + glm::vec2(0.0f, h)) - field.at(at - glm::vec2(0.0f, h))) /
        field.size;
    wall->normal = glm::dot(g, g) > 0.0f ? glm::normalize(glm::vec3(-g.x, 0.0f, -g.y))
                                         : -glm::vec3(along.x, 0.0f, along.y);
    if (glm::dot(wall->normal, wall->normal) == 0.0f) wall->normal = {0.0f, 1.0f, 0.0f};
  }
  return TerrainFate::Thickness;
}

}  // namespace cutaway
