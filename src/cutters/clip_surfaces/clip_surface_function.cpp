// Trapp & Döllner 2013: offset maps (§4.2), the clip-surface function (eqs. 1–3), derived
// relief maps, and the CPU side of the volumetric parity test (§5.3) with its ray-parity
// reference. src/cutters/clip_surfaces/*.glsl evaluate the same per fragment.
#include <algorithm>
#include <cmath>

#include "cutaway/core/noise.hpp"
#include "cutaway/cutters/clip_surfaces.hpp"

namespace cutaway {

FloatImage makeOffsetMap(const OffsetMapRecipe& r) {
  FloatImage map(r.size, r.size, 1);
  const int frequency = std::max(1, r.frequency);
  for (int y = 0; y < r.size; ++y)
    for (int x = 0; x < r.size; ++x) {
      // Texel centres, in lattice cells; the lattice wraps so the map tiles.
      const float u = (float(x) + 0.5f) / float(r.size), v = (float(y) + 0.5f) / float(r.size);
      float h = 0.0f;
      switch (r.pattern) {
        case OffsetPattern::Flat:
          break;
        case OffsetPattern::Sawtooth: {
          const float t = u * float(frequency);
          h = 1.0f - std::abs(2.0f * (t - std::floor(t)) - 1.0f);
          break;
        }
        case OffsetPattern::Noise:
        case OffsetPattern::Ridged: {
          float sum = 0.0f, weight = 1.0f, total = 0.0f;
          for (int o = 0; o < r.octaves; ++o) {
            const int period = frequency << o;
            float n =
                valueNoise(u * float(period), v * float(period), r.seed + unsigned(o), period);
            // Ridged: sharp creases where the noise crosses its middle ("broken material").
            if (r.pattern == OffsetPattern::Ridged) n = 1.0f - std::abs(2.0f * n - 1.0f);
            sum += weight * n;
            total += weight;
            weight *= 0.5f;
          }
          h = sum / total;
          break;
        }
      }
      map.at(x, y)[0] = h;
    }
  return map;
}

FloatImage blendOffsetMaps(const FloatImage& a, const FloatImage& b, OffsetBlend op, float weight) {
  const FloatImage& big = a.width * a.height >= b.width * b.height ? a : b;
  FloatImage out(big.width, big.height, 1);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const float u = (float(x) + 0.5f) / float(out.width),
                  v = (float(y) + 0.5f) / float(out.height);
      const float p = sampleRepeat(a, u, v), q = sampleRepeat(b, u, v);
      float h = 0.0f;
      switch (op) {
        case OffsetBlend::Add:
          h = p + q;
          break;
        case OffsetBlend::Multiply:
          h = p * q;
          break;
        case OffsetBlend::Max:
          h = std::max(p, q);
          break;
        case OffsetBlend::Min:
          h = std::min(p, q);
          break;
        case OffsetBlend::Mix:
          h = p * (1.0f - weight) + q * weight;
          break;
        case OffsetBlend::Screen:
          h = 1.0f - (1.0f - p) * (1.0f - q);
          break;
      }
      out.at(x, y)[0] = std::clamp(h, 0.0f, 1.0f);
    }
  return out;
}

glm::vec2 clipSurfaceTexCoord(const ClipSurface& cs, const glm::vec3& p) {
  const glm::vec3 n = cs.normal();
  const glm::vec3 pn = p - glm::dot(p - cs.origin, n) * n;  // eq. 3
  const float lu = glm::length(cs.u), lv = glm::length(cs.v);
  return {glm::dot(pn - cs.origin, cs.u / lu) / lu * cs.scale.x,  // eq. 2
          glm::dot(pn - cs.origin, cs.v / lv) / lv * cs.scale.y};
}

float clipSurfaceFunction(const ClipSurface& cs, const glm::vec3& p) {
  const glm::vec3 n = cs.normal();
  const glm::vec2 t = clipSurfaceTexCoord(cs, p);
  const float h = sampleRepeat(cs.offsetMap, t.x, t.y);
  return glm::dot(p, n) - glm::dot(n, cs.origin) + h * cs.scale.z;  // eq. 1
}

bool clippedBySurfaces(const ClipSurfaceOptions& options, const glm::vec3& p) {
  bool any = false, all = true, enabled = false;
  for (const auto& cs : options.surfaces) {
    if (!cs.enabled) continue;
    enabled = true;
    const bool clipped = clipSurfaceFunction(cs, p) < 0.0f;
    any |= clipped;
    all &= clipped;
  }
  if (!enabled) return false;
  return options.combine == ClipSurfaceOptions::Combine::Union ? any : all;
}

FloatImage deriveReliefMaps(const ClipSurface& cs) {
  const FloatImage& h = cs.offsetMap;
  FloatImage out(h.width, h.height, 4);
  auto at = [&](int x, int y) {
    return h.at(((x % h.width) + h.width) % h.width, ((y % h.height) + h.height) % h.height)[0];
  };
  // Scene units per texel along s and t, and of a unit of height.
  const float texelU = glm::length(cs.u) / (cs.scale.x * float(h.width));
  const float texelV = glm::length(cs.v) / (cs.scale.y * float(h.height));
  const float height = cs.scale.z;
  constexpr int kDirections = 8, kSteps = 12;
  for (int y = 0; y < h.height; ++y)
    for (int x = 0; x < h.width; ++x) {
      float* o = out.at(x, y);
      const float centre = at(x, y);
      o[0] = centre;
      o[1] = (at(x + 1, y) - at(x - 1, y)) * float(h.width) * 0.5f;  // ∂h/∂s, central difference
      o[2] = (at(x, y + 1) - at(x, y - 1)) * float(h.height) * 0.5f;
      // Horizon-based occlusion: in each direction, the steepest rise of the relief (seen from
      // the cut's side, higher h is nearer) bounds the open sky; AO = 1 − mean sin(horizon).
      float occlusion = 0.0f;
      for (int d = 0; d < kDirections; ++d) {
        const float angle = 2.0f * 3.14159265f * float(d) / float(kDirections);
        const float cx = std::cos(angle), cy = std::sin(angle);
        float steepest = 0.0f;
        for (int s = 1; s <= kSteps; ++s) {
          const int qx = x + int(std::lround(cx * float(s))),
                    qy = y + int(std::lround(cy * float(s)));
          const float dx = float(qx - x) * texelU, dy = float(qy - y) * texelV;
          const float run = std::sqrt(dx * dx + dy * dy);
          if (run <= 0.0f) continue;
          steepest = std::max(steepest, (at(qx, qy) - centre) * height / run);
        }
        occlusion += steepest / std::sqrt(1.0f + steepest * steepest);  // sin(atan(slope))
      }
      o[3] = 1.0f - occlusion / float(kDirections);
    }
  return out;
}

bool volumetricParityTest(const VolumetricDepthSprite& vds, const glm::vec3& p) {
  const glm::vec4 t = vds.toTexture * glm::vec4(p, 1.0f);
  if (t.x < 0.0f || t.x >= 1.0f || t.y < 0.0f || t.y >= 1.0f || t.z < 0.0f || t.z >= 1.0f)
    return false;
  const int x = std::min(int(t.x * float(vds.width)), vds.width - 1);
  const int y = std::min(int(t.y * float(vds.height)), vds.height - 1);
  int crossings = 0;
  for (int i = 0; i < vds.depthComplexity; ++i)
    crossings += vds.layers[(std::size_t(i) * std::size_t(vds.height) + std::size_t(y)) *
                                std::size_t(vds.width) +
                            std::size_t(x)] <= t.z;
  return crossings % 2 == 1;
}

bool insideMesh(const Mesh& mesh, const glm::vec3& p) {
  // A direction no axis-aligned or diagonal model feature lines up with.
  const glm::vec3 dir = glm::normalize(glm::vec3(0.3137f, 0.7719f, 0.5531f));
  return rayHits(mesh, p, dir).size() % 2 == 1;
}

}  // namespace cutaway
