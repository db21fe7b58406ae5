// cutaway/core/noise.hpp — lattice value noise shared by the jitter and offset-map patterns.
// The bit operations are mirrored in GLSL (src/cutters/cutout/cutout.glsl), so results on the
// CPU and GPU agree.
#pragma once

#include <cmath>
#include <cstdint>

namespace cutaway {

// A hash of a lattice point (and a seed) into [0, 1).
inline float latticeValue(std::int32_t ix, std::int32_t iy, std::uint32_t seed = 0) {
  std::uint32_t h =
      std::uint32_t(ix) * 0x8da6b343u + std::uint32_t(iy) * 0xd8163841u + seed * 0xcb1ab31fu;
  h ^= h >> 15;
  h *= 0x2c1b3c6du;
  h ^= h >> 12;
  h *= 0x297a2d39u;
  h ^= h >> 15;
  return float(h >> 8) * (1.0f / 16777216.0f);
}

// Value noise at (x, y) in [0, 1): smoothstep interpolation of the lattice values; with
// period > 0 the lattice wraps every `period` cells, so the noise tiles.
inline float valueNoise(float x, float y, std::uint32_t seed = 0, std::int32_t period = 0) {
  const float fx = std::floor(x), fy = std::floor(y);
  const float ax = x - fx, ay = y - fy;
  const float sx = ax * ax * (3.0f - 2.0f * ax), sy = ay * ay * (3.0f - 2.0f * ay);
  auto wrap = [period](std::int32_t i) {
    return period > 0 ? ((i % period) + period) % period : i;
  };
  const auto ix = std::int32_t(fx), iy = std::int32_t(fy);
  const float a = latticeValue(wrap(ix), wrap(iy), seed),
              b = latticeValue(wrap(ix + 1), wrap(iy), seed);
  const float c = latticeValue(wrap(ix), wrap(iy + 1), seed),
              d = latticeValue(wrap(ix + 1), wrap(iy + 1), seed);
  const float bottom = a * (1.0f - sx) + b * sx, top = c * (1.0f - sx) + d * sx;
  return bottom * (1.0f - sy) + top * sy;
}

}  // namespace cutaway
