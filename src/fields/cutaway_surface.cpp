// The cutaway surface C(p) = max_q (z(q) − m‖q − p‖) (Burns11 eq. 4.2, Burns08 eq. 2) by
// brute force (Burns11 §5.1.2.1) and by Borgefors chamfer propagation (Burns11 §5.1.2.2;
// Borgefors 1986), plus the jump-flooding step schedule (Burns08 §5.1) that the CPU kernel in
// jump_flooding.cpp and the GPU passes in src/cutters/adaptive/ share.
#include "cutaway/fields/cutaway_surface.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>

namespace cutaway::fields {

SeedImage::SeedImage(int w, int h, float ux, float uy) : width(w), height(h), unitX(ux), unitY(uy) {
  assert(w > 0 && h > 0 && "a seed image needs at least one pixel");
  const std::size_t n = std::size_t(w) * std::size_t(h);
  seeded.assign(n, 0);
  depth.assign(n, 0.0f);
  slopeE.assign(n, 0.0f);
  slopeF.assign(n, 0.0f);
  floorX.assign(n, 0.0f);
  floorY.assign(n, 0.0f);
}

void SeedImage::set(int x, int y, float z, float mE, float mF, float fx, float fy) {
  assert(x >= 0 && x < width && y >= 0 && y < height && "seed outside the image");
  const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
  seeded[i] = 1;
  depth[i] = z;
  slopeE[i] = mE;
  slopeF[i] = mF;
  floorX[i] = fx;
  floorY[i] = fy;
}

namespace {

// c(p, q) in double precision, literally as cutaway_surface.hpp states it: Burns11 eq. 4.1
// with the directional slope of Burns08 §5.5 / Burns11 eqs. 6.3–6.4 (slopes interpolated
// instead of angles, see src/cutters/adaptive/README.md). α is taken along q − p measured in
// view-plane units, the units f(q) is a unit vector in.
double coneDepth(const SeedImage& s, int px, int py, std::size_t q) {
  const int qx = int(q % std::size_t(s.width)), qy = int(q / std::size_t(s.width));
  const double dx = double(px - qx) * s.unitX, dy = double(py - qy) * s.unitY;
  const double distance = std::sqrt(dx * dx + dy * dy);
  double alpha = 0.0;  // p = q: no direction, the cone's apex (eq. 6.3 is undefined there)
  if (distance > 0.0)
    alpha = std::clamp((-dx * s.floorX[q] - dy * s.floorY[q]) / distance, 0.0, 1.0);
  const double slope = (1.0 - alpha) * s.slopeE[q] + alpha * s.slopeF[q];
  return s.depth[q] - slope * distance;
}

CutawayField emptyField(const SeedImage& s) {
  CutawayField f;
  f.width = s.width;
  f.height = s.height;
  f.depth.resize(std::size_t(s.width) * std::size_t(s.height));
  f.anchor.resize(f.depth.size());
  return f;
}

// A chamfer kernel offset (ox, oy) into the half already visited by the forward pass.
struct ChamferOffset {
  int ox, oy;
};
// Borgefors 1986: the 3×3 kernel's visited half in raster order (rows of smaller y first).
constexpr std::array<ChamferOffset, 4> kForward3x3{{{-1, -1}, {0, -1}, {1, -1}, {-1, 0}}};
// The 5×5 kernel adds the knight's moves (±1, 2), (±2, 1); the other 5×5 offsets are sums of
// 3×3 steps along one direction and would add nothing.
constexpr std::array<ChamferOffset, 8> kForward5x5{
    {{-1, -2}, {1, -2}, {-2, -1}, {-1, -1}, {0, -1}, {1, -1}, {2, -1}, {-1, 0}}};

}  // namespace

CutawayField bruteForce(const SeedImage& seeds, float nearDepth) {
  // Burns11 §5.1.2.1: every pixel against every seed, in seed index order; only a strictly
  // deeper cone replaces the current one, so the lowest index wins ties.
  std::vector<std::size_t> seedIndices;
  for (std::size_t i = 0; i < seeds.seeded.size(); ++i)
    if (seeds.seeded[i]) seedIndices.push_back(i);
  CutawayField f = emptyField(seeds);
  for (int y = 0; y < seeds.height; ++y)
    for (int x = 0; x < seeds.width; ++x) {
      double best = nearDepth;  // eq. 4.2 clamped to the near plane (header: C(p) ≥ nearDepth)
      int anchor = -1;
      for (std::size_t q : seedIndices) {
        const double c = coneDepth(seeds, x, y, q);
        if (c > best) {
          best = c;
          anchor = int(q);
        }
      }
      const std::size_t p = std::size_t(y) * std::size_t(seeds.width) + std::size_t(x);
      f.depth[p] = float(best);
      f.anchor[p] = anchor;
    }
  return f;
}

CutawayField chamfer(const SeedImage& seeds, float nearDepth, ChamferKernel kernel) {
  // Burns11 §5.1.2.2 / Burns11 eq. 5.2: Borgefors' two-pass distance transform run on depths.
  // Each pixel carries the value z(a) − m_E(a)·L (L the length of the kernel steps walked
  // from the anchor a) and a's slope, so a step of length w lowers it by m_E(a)·w: the cone
  // of the anchor that reached the pixel, with ‖Δ‖ replaced by a sum of steps.
  const int w = seeds.width, h = seeds.height;
  const std::span<const ChamferOffset> forward = kernel == ChamferKernel::k3x3
                                                     ? std::span<const ChamferOffset>(kForward3x3)
                                                     : std::span<const ChamferOffset>(kForward5x5);
  // Kernel weights: the exact step lengths in view-plane units (1 and √2 for square pixels).
  std::vector<float> stepLength;
  for (const ChamferOffset& o : forward)
    stepLength.push_back(float(std::hypot(double(o.ox) * seeds.unitX, double(o.oy) * seeds.unitY)));

  constexpr float kNone = -std::numeric_limits<float>::infinity();  // no anchor yet
  const std::size_t n = std::size_t(w) * std::size_t(h);
  std::vector<float> value(n, kNone), slope(n, 0.0f);
  CutawayField f = emptyField(seeds);
  for (std::size_t i = 0; i < n; ++i) {
    f.anchor[i] = seeds.seeded[i] ? int(i) : -1;
    if (seeds.seeded[i]) {
      value[i] = seeds.depth[i];
      slope[i] = seeds.slopeE[i];  // the chamfer ignores the directional constraint
    }
  }
  // One kernel application at (x, y); `sign` = 1 looks at the forward half (pixels already
  // visited by the forward pass), −1 at its mirror image for the backward pass.
  auto relax = [&](int x, int y, int sign) {
    const std::size_t p = std::size_t(y) * std::size_t(w) + std::size_t(x);
    for (std::size_t k = 0; k < forward.size(); ++k) {
      const int nx = x + sign * forward[k].ox, ny = y + sign * forward[k].oy;
      if (nx < 0 || nx >= w || ny < 0 || ny >= h) continue;
      const std::size_t q = std::size_t(ny) * std::size_t(w) + std::size_t(nx);
      if (value[q] == kNone) continue;
      const float candidate = value[q] - slope[q] * stepLength[k];
      if (candidate > value[p]) {
        value[p] = candidate;
        slope[p] = slope[q];
        f.anchor[p] = f.anchor[q];
      }
    }
  };
  // Forward pass: rows of increasing y, x increasing; backward pass: the reverse order.
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) relax(x, y, 1);
  for (int y = h - 1; y >= 0; --y)
    for (int x = w - 1; x >= 0; --x) relax(x, y, -1);

  for (std::size_t i = 0; i < n; ++i) {
    // C(p) = max(nearDepth, ·): the near plane wins ties, as in bruteForce.
    if (!(value[i] > nearDepth)) f.anchor[i] = -1;
    f.depth[i] = std::max(value[i], nearDepth);
  }
  return f;
}

const char* variantName(JumpFloodingVariant v) {
  switch (v) {
    case JumpFloodingVariant::jfa:
      return "jfa";
    case JumpFloodingVariant::jfaPlus1:
      return "jfa+1";
    case JumpFloodingVariant::onePlusJfa:
      return "1+jfa";
    case JumpFloodingVariant::jfaPlus2:
      return "jfa+2";
  }
  return "jfa";
}

bool parseVariant(const std::string& name, JumpFloodingVariant& out) {
  for (JumpFloodingVariant v : {JumpFloodingVariant::jfa, JumpFloodingVariant::jfaPlus1,
                                JumpFloodingVariant::onePlusJfa, JumpFloodingVariant::jfaPlus2})
    if (name == variantName(v)) {
      out = v;
      return true;
    }
  return false;
}

std::vector<int> stepSizes(int width, int height, JumpFloodingVariant variant) {
  // Burns08 §5.1: k = n/2^i for an n×n image, i = 1 … log2 n; a non-power-of-two image
  // floods as the power-of-two square that holds it. A 1-pixel image needs no step.
  std::vector<int> steps;
  if (variant == JumpFloodingVariant::onePlusJfa) steps.push_back(1);
  const unsigned n = std::bit_ceil(unsigned(std::max({width, height, 1})));
  for (int k = int(n / 2); k >= 1; k /= 2) steps.push_back(k);
  // Rong & Tan 2006's variants that repair JFA's rare errors with extra short steps.
  if (variant == JumpFloodingVariant::jfaPlus2) steps.push_back(2);
  if (variant == JumpFloodingVariant::jfaPlus1 || variant == JumpFloodingVariant::jfaPlus2)
    steps.push_back(1);
  return steps;
}

}  // namespace cutaway::fields
