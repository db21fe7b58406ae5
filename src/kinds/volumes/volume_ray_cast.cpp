#include "cutaway/kinds/volume_ray_cast.hpp"

#include <algorithm>
#include <cmath>

namespace cutaway {

namespace {
glm::vec3 worldAtWindow(const glm::mat4& inverseViewProjection, glm::vec2 uv, float depth) {
  const glm::vec4 h =
      inverseViewProjection * glm::vec4(uv * 2.0f - 1.0f, depth * 2.0f - 1.0f, 1.0f);
  return glm::vec3(h) / h.w;
}

// Trilinear interpolation of per-voxel quantities `at` at index-space point p, with
// GL_CLAMP_TO_EDGE and texel centres at integers: beyond the last centre, the edge value.
template <class T, class At>
T trilinear(const Volume& v, glm::vec3 p, At at) {
  const glm::vec3 hi = glm::vec3(v.dims - 1);
  p = glm::clamp(p, glm::vec3(-0.5f), glm::vec3(v.dims) - 0.5f);
  const glm::vec3 base = glm::floor(p), f = p - base;
  T sum(0.0f);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::ivec3 o(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    const glm::vec3 w = glm::mix(1.0f - f, f, glm::vec3(o));
    sum += w.x * w.y * w.z * at(glm::ivec3(glm::clamp(base + glm::vec3(o), glm::vec3(0.0f), hi)));
  }
  return sum;
}
}  // namespace

float sampleVolume(const Volume& v, glm::vec3 p) {
  return trilinear<float>(v, p, [&](glm::ivec3 c) { return v.at(c); });
}

float smallestVoxelSpacing(const SceneVolume& v) {
  const glm::mat3 m(v.indexToWorld());
  return std::min({glm::length(m[0]), glm::length(m[1]), glm::length(m[2])});
}

glm::vec3 voxelGradient(const Volume& v, glm::ivec3 c) {
  const auto at = [&](glm::ivec3 q) { return v.at(glm::clamp(q, glm::ivec3(0), v.dims - 1)); };
  return 0.5f * glm::vec3(at(c + glm::ivec3(1, 0, 0)) - at(c - glm::ivec3(1, 0, 0)),
                          at(c + glm::ivec3(0, 1, 0)) - at(c - glm::ivec3(0, 1, 0)),
                          at(c + glm::ivec3(0, 0, 1)) - at(c - glm::ivec3(0, 0, 1)));
}

glm::vec3 sampleGradient(const Volume& v, glm::vec3 p) {
  return trilinear<glm::vec3>(v, p, [&](glm::ivec3 c) { return voxelGradient(v, c); });
}

float volumeJitter(glm::uvec2 p) {
  // The same integer hash as volume.frag's pixelJitter.
  std::uint32_t h = (p.x * 0x8da6b343u) ^ (p.y * 0xd8163841u);
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return float(h >> 8) * (1.0f / 16777216.0f);
}

VolumeRay castVolumeRay(const SceneVolume& sv, const glm::mat4& view, const glm::mat4& projection,
                        glm::ivec2 size, glm::ivec2 pixel, float opaqueDepth,
                        const std::function<bool(const glm::vec3&)>& keep) {
  VolumeRay ray;
  const Volume& volume = *sv.volume;
  const glm::mat4 inverse = glm::inverse(projection * view);
  const glm::vec2 uv = (glm::vec2(pixel) + 0.5f) / glm::vec2(size);
  const glm::vec3 origin = worldAtWindow(inverse, uv, 0.0f);
  const glm::vec3 direction = glm::normalize(worldAtWindow(inverse, uv, 1.0f) - origin);
  const float tOpaque =
      opaqueDepth < 1.0f ? glm::distance(origin, worldAtWindow(inverse, uv, opaqueDepth)) : 1e30f;
  const glm::mat4 worldToIndex = sv.worldToIndex();
  const glm::vec3 o = glm::vec3(worldToIndex * glm::vec4(origin, 1.0f));
  const glm::vec3 d = glm::mat3(worldToIndex) * direction;
  const glm::vec3 a = (glm::vec3(-0.5f) - o) / d, b = (glm::vec3(volume.dims) - 0.5f - o) / d;
  const glm::vec3 lo = glm::min(a, b), hi = glm::max(a, b);
  const float tIn = std::max({lo.x, lo.y, lo.z, 0.0f});
  const float tOut = std::min({hi.x, hi.y, hi.z, tOpaque});
  if (!(tIn < tOut)) return ray;
  const float step = sv.sampleDistance * smallestVoxelSpacing(sv);
  const float exponent = sv.sampleDistance / sv.opacityDistance;
  const float offset = sv.jitter ? volumeJitter(glm::uvec2(pixel)) : 0.5f;
  const auto viewDepth = [&](const glm::vec3& p) { return -(view * glm::vec4(p, 1.0f)).z; };
  // A two-dimensional transfer function's material at an index-space point: the value's at the
  // magnitude of the world gradient there (value units per world unit).
  const glm::mat3 gradientToWorld = glm::transpose(glm::mat3(worldToIndex));
  const auto material = [&](float value, glm::vec3 index) {
    if (!sv.transfer.twoDimensional()) return sv.material(value);
    return sv.material(value, glm::length(gradientToWorld * sampleGradient(volume, index)));
  };
  float maxValue = -1e30f, maxT = 0.0f, previousValue = 0.0f;
  bool previousKept = false;
  const float t0 = tIn + offset * step;
  for (int k = 0; t0 + float(k) * step < tOut; ++k) {
    const float t = t0 + float(k) * step;
    const glm::vec3 p = origin + t * direction;
    const glm::vec3 index = o + t * d;
    // A label volume is sampled at the nearest voxel (GL_NEAREST).
    const float value = sv.labels ? volume.at(glm::clamp(glm::ivec3(glm::floor(index + 0.5f)),
                                                         glm::ivec3(0), volume.dims - 1))
                                  : sampleVolume(volume, index);
    const TransferPoint c = material(value, index);
    // Samples of no opacity are no material: the cutters are not asked (as on the GPU).
    if (sv.mode == VolumeMode::Composite && c.opacity == 0.0f) {
      previousKept = false;
      continue;
    }
    if (keep && !keep(p)) {
      previousKept = false;
      continue;
    }
    if (std::isnan(ray.entryDepth)) ray.entryDepth = viewDepth(p);
    if (sv.mode == VolumeMode::Maximum) {
      if (value > maxValue) maxValue = value, maxT = t;
    } else if (sv.mode == VolumeMode::Isosurface) {
      if (value >= sv.isoValue) {
        float tHit = t;
        if (previousKept) tHit = t - step * (value - sv.isoValue) / (value - previousValue);
        ray.color = material(sv.isoValue, o + tHit * d).color;
        ray.opacity = 1.0f;
        ray.hitDepth = viewDepth(origin + tHit * direction);
        break;
      }
    } else {
      const float alpha = 1.0f - std::pow(1.0f - c.opacity, exponent);
      if (alpha > 0.0f) {
        ray.color += (1.0f - ray.opacity) * glm::clamp(c.color, 0.0f, 1.0f) * alpha;
        ray.opacity += (1.0f - ray.opacity) * alpha;
        if (std::isnan(ray.hitDepth) && ray.opacity >= 0.5f) ray.hitDepth = viewDepth(p);
        if (ray.opacity > 0.995f) break;
      }
    }
    previousKept = true;
    previousValue = value;
  }
  if (sv.mode == VolumeMode::Maximum && maxValue > -1e30f) {
    const TransferPoint c = material(maxValue, o + maxT * d);
    ray.color = c.color * c.opacity;
    ray.opacity = c.opacity;
    ray.hitDepth = viewDepth(origin + maxT * direction);
  }
  return ray;
}

}  // namespace cutaway
