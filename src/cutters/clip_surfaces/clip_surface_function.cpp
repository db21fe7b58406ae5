// Trapp & Döllner 2013: offset maps (§4.2), the clip-surface function (eqs. 1–3), derived
// relief maps, and the CPU side of the volumetric parity test (§5.3) with its ray-parity
// reference. src/cutters/clip_surfaces/*.glsl evaluate the same per fragment.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "core/worker_threads.hpp"
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

namespace {

// Eq. 1 over a world box for surface `cs` whose relief lifts by S_z·h, h in `heights`: the
// plane's part P·N − N·O at the box's corners (linear in P: its extremes are corners), and a
// margin for the shaders' 32-bit rounding of its terms.
struct OverBox {
  glm::dvec3 n;
  double offset, least, lowLift, highLift, margin;
  bool keeps() const { return least + lowLift > margin; }
};

OverBox overBox(const ClipSurface& cs, glm::vec2 heights, const Bounds& box) {
  OverBox o{.n = glm::dvec3(cs.normal())};
  o.offset = glm::dot(o.n, glm::dvec3(cs.origin));
  o.least = std::numeric_limits<double>::max();
  double terms = std::abs(o.offset);
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 corner{(k & 1) ? box.max.x : box.min.x, (k & 2) ? box.max.y : box.min.y,
                            (k & 4) ? box.max.z : box.min.z};
    o.least = std::min(o.least, glm::dot(corner, o.n) - o.offset);
    terms = std::max(terms, std::abs(glm::dot(corner, o.n)) + std::abs(o.offset));
  }
  o.lowLift = double(std::min(heights.x, heights.y)) * double(cs.scale.z);  // S_z ≥ 0
  o.highLift = double(std::max(heights.x, heights.y)) * double(cs.scale.z);
  o.margin = 1e-5 * (terms + std::abs(o.highLift));
  return o;
}

}  // namespace

bool clipSurfacesKeepBox(const ClipSurfaceOptions& options, const std::vector<glm::vec2>& heights,
                         const Bounds& box) {
  bool enabled = false, anyKeeps = false, allKeep = true;
  for (std::size_t i = 0; i < options.surfaces.size(); ++i) {
    if (!options.surfaces[i].enabled) continue;
    enabled = true;
    const bool keeps = overBox(options.surfaces[i], heights[i], box).keeps();
    anyKeeps |= keeps;
    allKeep &= keeps;
  }
  if (!enabled) return true;
  return options.combine == ClipSurfaceOptions::Combine::Union ? allKeep : anyKeeps;
}

std::optional<ClipSurfaceSlab> clipSurfacesSlab(const ClipSurfaceOptions& options,
                                                const std::vector<glm::vec2>& heights,
                                                const Bounds& box) {
  std::optional<OverBox> only;
  int enabled = 0;
  for (std::size_t i = 0; i < options.surfaces.size(); ++i) {
    if (!options.surfaces[i].enabled) continue;
    ++enabled;
    const OverBox o = overBox(options.surfaces[i], heights[i], box);
    if (o.keeps()) continue;  // under a union, this one clips nothing of the box
    if (only) return std::nullopt;
    only = o;
  }
  // An intersection of several decides by all of them.
  if (!only || (enabled > 1 && options.combine == ClipSurfaceOptions::Combine::Intersection))
    return std::nullopt;
  const glm::dvec3 n = only->n;
  return ClipSurfaceSlab{
      .kept = glm::vec4(glm::vec3(n), float(-only->offset + only->lowLift - only->margin)),
      .removed = glm::vec4(glm::vec3(n), float(-only->offset + only->highLift + only->margin))};
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
  // Horizon-based occlusion: in each of 8 directions, the steepest rise of the relief within 12
  // texels (seen from the cut's side, higher h is nearer) bounds the open sky; AO = 1 − mean
  // sin(horizon). The taps are the same at every texel: worked out once.
  constexpr int kDirections = 8, kSteps = 12;
  struct Tap {
    int dx, dy;
    float run;  // scene units
  };
  std::array<std::array<Tap, kSteps>, kDirections> taps{};
  for (int d = 0; d < kDirections; ++d) {
    const float angle = 2.0f * 3.14159265f * float(d) / float(kDirections);
    const float cx = std::cos(angle), cy = std::sin(angle);
    for (int s = 1; s <= kSteps; ++s) {
      Tap& t = taps[std::size_t(d)][std::size_t(s - 1)];
      t.dx = int(std::lround(cx * float(s))), t.dy = int(std::lround(cy * float(s)));
      const float dx = float(t.dx) * texelU, dy = float(t.dy) * texelV;
      t.run = std::sqrt(dx * dx + dy * dy);
    }
  }
  const auto texel = [&](int x, int y, bool inside) {
    // Away from the edges the taps need no wrapping.
    const auto tap = [&](int dx, int dy) {
      return inside ? h.data[std::size_t(y + dy) * std::size_t(h.width) + std::size_t(x + dx)]
                    : at(x + dx, y + dy);
    };
    float* o = out.at(x, y);
    const float centre = at(x, y);
    o[0] = centre;
    o[1] = (tap(1, 0) - tap(-1, 0)) * float(h.width) * 0.5f;  // ∂h/∂s, central difference
    o[2] = (tap(0, 1) - tap(0, -1)) * float(h.height) * 0.5f;
    float occlusion = 0.0f;
    for (const auto& direction : taps) {
      float steepest = 0.0f;
      for (const Tap& t : direction) {
        if (t.run <= 0.0f) continue;
        steepest = std::max(steepest, (tap(t.dx, t.dy) - centre) * height / t.run);
      }
      occlusion += steepest / std::sqrt(1.0f + steepest * steepest);  // sin(atan(slope))
    }
    o[3] = 1.0f - occlusion / float(kDirections);
  };
  // Rows shared out to threads: a large map takes seconds on one.
  std::atomic<int> nextRow{0};
  const auto work = [&] {
    for (int y; (y = nextRow++) < h.height;) {
      const bool rowInside = y >= kSteps && y + kSteps < h.height;
      for (int x = 0; x < h.width; ++x)
        texel(x, y, rowInside && x >= kSteps && x + kSteps < h.width);
    }
  };
  // At most a thread for each 64 rows: a small map is not worth starting threads for.
  runOnThreads(std::min(hardwareThreads(8), 1 + h.height / 64), work);
  return out;
}

bool volumetricParityTest(const VolumetricDepthSprite& vds, const glm::vec3& p) {
  const glm::vec4 t = vds.toTexture * glm::vec4(p, 1.0f);
  if (t.x < 0.0f || t.x >= 1.0f || t.y < 0.0f || t.y >= 1.0f || t.z < 0.0f || t.z >= 1.0f)
    return false;
  const auto layer = [&](int i, int x, int y) {
    x = std::clamp(x, 0, vds.width - 1), y = std::clamp(y, 0, vds.height - 1);
    return vds.layers[(std::size_t(i) * std::size_t(vds.height) + std::size_t(y)) *
                          std::size_t(vds.width) +
                      std::size_t(x)];
  };
  // Each layer bilinearly between the four texel centres around T where their rays cross as
  // many layers (parity.glsl says why), else the texel containing T.
  const float tx = t.x * float(vds.width) - 0.5f, ty = t.y * float(vds.height) - 0.5f;
  const int x0 = int(std::floor(tx)), y0 = int(std::floor(ty));
  const float wx = tx - float(x0), wy = ty - float(y0);
  const int nx = std::min(int(t.x * float(vds.width)), vds.width - 1);
  const int ny = std::min(int(t.y * float(vds.height)), vds.height - 1);
  std::array<int, 4> count{};
  for (int i = 0; i < vds.depthComplexity; ++i)
    for (int k = 0; k < 4; ++k) count[k] += layer(i, x0 + (k & 1), y0 + (k >> 1)) < 1.0f;
  const bool sameSheets = count[0] == count[1] && count[0] == count[2] && count[0] == count[3];
  int crossings = 0;
  for (int i = 0; i < vds.depthComplexity; ++i) {
    float depth = layer(i, nx, ny);
    if (sameSheets && i < count[0])
      depth = glm::mix(glm::mix(layer(i, x0, y0), layer(i, x0 + 1, y0), wx),
                       glm::mix(layer(i, x0, y0 + 1), layer(i, x0 + 1, y0 + 1), wx), wy);
    crossings += depth <= t.z;
  }
  return crossings % 2 == 1;
}

bool insideMesh(const Mesh& mesh, const glm::vec3& p) {
  // A direction no axis-aligned or diagonal model feature lines up with.
  const glm::vec3 dir = glm::normalize(glm::vec3(0.3137f, 0.7719f, 0.5531f));
  return rayHits(mesh, p, dir).size() % 2 == 1;
}

glm::vec2 reliefRangeOver(const FloatImage& map, glm::vec2 lo, glm::vec2 hi) {
  if (map.data.empty()) return glm::vec2(0.0f);
  // Texel centres sit at (k + 0.5)/size: sampleRepeat reads texels floor(x) and floor(x) + 1 of
  // x = T·size − 0.5. A range wider than the map covers all of it.
  const auto texels = [](float a, float b, int size) {
    const float first = std::floor(a * float(size) - 0.5f),
                last = std::floor(b * float(size) - 0.5f) + 1.0f;
    return last - first + 1.0f >= float(size) ? glm::ivec2(0, size - 1)
                                              : glm::ivec2(int(first), int(last));
  };
  const glm::ivec2 cols = texels(lo.x, hi.x, map.width), rows = texels(lo.y, hi.y, map.height);
  const auto wrap = [](int k, int size) { return ((k % size) + size) % size; };
  glm::vec2 range(1e30f, -1e30f);
  for (int y = rows.x; y <= rows.y; ++y)
    for (int x = cols.x; x <= cols.y; ++x) {
      const float h = map.at(wrap(x, map.width), wrap(y, map.height))[0];
      range = glm::vec2(std::min(range.x, h), std::max(range.y, h));
    }
  return range;
}

std::vector<std::uint8_t> capTiles(const Mesh& mesh, const glm::mat4& model, const ClipSurface& cs,
                                   glm::vec2 relief, glm::vec4 rect, glm::ivec2 tiles,
                                   float margin) {
  const int nx = tiles.x, ny = tiles.y;
  std::vector<std::uint8_t> crossed(std::size_t(nx) * std::size_t(ny), 0);
  const glm::vec3 n = cs.normal(), U = cs.u, V = cs.v, O = cs.origin;
  // The displaced surface X = O + sU + tV − S_z·h·N lies at n·(X − O) ∈ [−S_z h_max, −S_z h_min].
  const float slabLow = -cs.scale.z * relief.y, slabHigh = -cs.scale.z * relief.x;
  const glm::vec2 size(rect.z - rect.x, rect.w - rect.y);
  if (size.x <= 0.0f || size.y <= 0.0f) return crossed;
  // A tile index along one side, of a surface coordinate (may lie outside the grid).
  const auto tileOf = [&](float st, int axis) {
    return (st - rect[axis]) / size[axis] * float(axis == 0 ? nx : ny);
  };
  std::vector<glm::vec3> world(mesh.positions.size());
  for (std::size_t i = 0; i < world.size(); ++i)
    world[i] = glm::vec3(model * glm::vec4(mesh.positions[i], 1.0f));
  for (std::size_t i = 0, count = mesh.triangleCount(); i < count; ++i) {
    const glm::uvec3 tri = mesh.triangle(i);
    float dLow = 1e30f, dHigh = -1e30f;
    glm::vec2 lo(1e30f), hi(-1e30f);
    for (int c = 0; c < 3; ++c) {
      const glm::vec3 d = world[tri[c]] - O;
      const float h = glm::dot(d, n);
      dLow = std::min(dLow, h), dHigh = std::max(dHigh, h);
      const glm::vec2 st(glm::dot(d, U) / glm::dot(U, U), glm::dot(d, V) / glm::dot(V, V));
      lo = glm::min(lo, st), hi = glm::max(hi, st);
    }
    if (dHigh < slabLow - margin || dLow > slabHigh + margin) continue;
    lo -= glm::vec2(margin / glm::length(U), margin / glm::length(V));
    hi += glm::vec2(margin / glm::length(U), margin / glm::length(V));
    const int x0 = std::max(0, int(std::floor(tileOf(lo.x, 0)))),
              x1 = std::min(nx - 1, int(std::floor(tileOf(hi.x, 0)))),
              y0 = std::max(0, int(std::floor(tileOf(lo.y, 1)))),
              y1 = std::min(ny - 1, int(std::floor(tileOf(hi.y, 1))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) crossed[std::size_t(y) * std::size_t(nx) + std::size_t(x)] = 1;
  }
  // The other tiles in runs connected through shared sides, each run decided by the parity
  // of its first tile's centre halfway through the slab (in the object's own space).
  std::vector<std::uint8_t> keep = crossed;
  std::vector<std::uint8_t> seen = crossed;
  const glm::mat4 toObject = glm::inverse(model);
  std::vector<int> run;
  for (int start = 0; start < nx * ny; ++start) {
    if (seen[std::size_t(start)]) continue;
    run.assign(1, start);
    seen[std::size_t(start)] = 1;
    for (std::size_t k = 0; k < run.size(); ++k) {
      const int x = run[k] % nx, y = run[k] / nx;
      const int next[4][2] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
      for (const auto& q : next) {
        if (q[0] < 0 || q[1] < 0 || q[0] >= nx || q[1] >= ny) continue;
        const std::size_t i = std::size_t(q[1]) * std::size_t(nx) + std::size_t(q[0]);
        if (!seen[i]) seen[i] = 1, run.push_back(q[1] * nx + q[0]);
      }
    }
    const glm::vec2 st(rect.x + (float(start % nx) + 0.5f) / float(nx) * size.x,
                       rect.y + (float(start / nx) + 0.5f) / float(ny) * size.y);
    const glm::vec3 p = O + st.x * U + st.y * V + 0.5f * (slabLow + slabHigh) * n;
    if (insideMesh(mesh, glm::vec3(toObject * glm::vec4(p, 1.0f))))
      for (int i : run) keep[std::size_t(i)] = 1;
  }
  return keep;
}

}  // namespace cutaway
