// Diepstraten03 §4 cutout: the wedge's half-spaces and the perturbed signed distance, in C++
// for tests and the CLI; src/cutters/cutout/cutout.glsl is the same arithmetic per fragment.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "cutaway/core/noise.hpp"
#include "cutaway/cutters/cutout.hpp"

namespace cutaway {

CutoutWedge cutoutWedge(const PrincipalAxes& axes, const CutoutOptions& options,
                        const glm::vec3& towardsViewer) {
  CutoutWedge w;
  w.origin = axes.center;
  w.axis = axes.axes[0];
  w.axisLength = std::max(axes.extentMax - axes.extentMin, 1e-6f);
  const glm::vec3 a = w.axis;
  // The wedge's bisector b ⟂ a: at the user's rotation from the second axis, or facing the
  // viewer (Diepstraten03 §4.2: the rotation about the axis is the free parameter).
  glm::vec3 b;
  if (options.rotation) {
    const float phi = glm::radians(*options.rotation);
    b = std::cos(phi) * axes.axes[1] + std::sin(phi) * axes.axes[2];
  } else {
    b = towardsViewer - glm::dot(towardsViewer, a) * a;
    b = glm::dot(b, b) > 1e-12f * glm::dot(towardsViewer, towardsViewer) ? glm::normalize(b)
                                                                         : axes.axes[1];
  }
  const glm::vec3 t = glm::cross(a, b);
  // Two planes through the axis, each at half the relative angle from b; their inward
  // normals point into the wedge (rule 2: an intersection of half-spaces, rule 3: on the
  // main axis).
  const float half = glm::radians(options.angle) * 0.5f;
  for (const float side : {-1.0f, 1.0f}) {
    const glm::vec3 n = std::sin(half) * b + side * std::cos(half) * t;
    w.planes.emplace_back(n, -glm::dot(n, w.origin));
  }
  if (options.axialRange) {
    const float sLo = axes.extentMin + options.axialRange->x * w.axisLength;
    const float sHi = axes.extentMin + options.axialRange->y * w.axisLength;
    w.planes.emplace_back(a, -glm::dot(a, w.origin) - sLo);  // s > sLo
    w.planes.emplace_back(-a, glm::dot(a, w.origin) + sHi);  // s < sHi
  }
  return w;
}

namespace {

// Fractal sum of octaves of value noise, in [−1, 1] (Diepstraten03 §4.5: "fractals,
// synthetic procedural textures like clouds").
float fractalNoise(glm::vec2 p, int octaves) {
  float sum = 0.0f, weight = 1.0f, total = 0.0f;
  for (int o = 0; o < octaves; ++o) {
    sum += weight * (2.0f * valueNoise(p.x, p.y) - 1.0f);
    total += weight;
    weight *= 0.5f;
    p *= 2.0f;
  }
  return sum / total;
}

// Triangle wave in [−1, 1]: a two-texel texture repeated under bilinear filtering
// (Diepstraten03 §4.5, the "tiny texture" that gives sawtooth boundaries).
float triangleWave(float t) {
  return 4.0f * std::abs(t - std::floor(t) - 0.5f) - 1.0f;
}

}  // namespace

float cutoutPerturbation(const CutoutWedge& wedge, const CutoutJitter& jitter, const glm::vec3& x) {
  // Pattern coordinates on the cut: along the axis and away from it, so the boundary is
  // perturbed both on the sides (constant radius) and on end caps (constant axial position).
  const glm::vec3 d = x - wedge.origin;
  const float along = glm::dot(d, wedge.axis);
  const float radial = glm::length(d - along * wedge.axis);
  const glm::vec2 uv = glm::vec2(along, radial) * (jitter.frequency / wedge.axisLength);
  switch (jitter.pattern) {
    case CutoutJitter::Pattern::None:
      return 0.0f;
    case CutoutJitter::Pattern::Sawtooth:
      return 0.5f * (triangleWave(uv.x) + triangleWave(uv.y));
    case CutoutJitter::Pattern::Noise:
      return fractalNoise(uv, jitter.octaves);
    case CutoutJitter::Pattern::Image:
      return 2.0f * sampleRepeat(jitter.imageData, uv.x, uv.y) - 1.0f;
  }
  return 0.0f;
}

float cutoutDistance(const CutoutWedge& wedge, const CutoutJitter& jitter, const glm::vec3& x) {
  float d = 1e30f;
  for (const auto& p : wedge.planes) d = std::min(d, glm::dot(glm::vec3(p), x) + p.w);
  if (jitter.pattern == CutoutJitter::Pattern::None) return d;
  return d + jitter.amplitude * wedge.axisLength * cutoutPerturbation(wedge, jitter, x);
}

std::vector<glm::vec4> cutoutKeptHalfSpaces(const CutoutWedge& wedge, const CutoutJitter& jitter,
                                            const Bounds& box, float beyond) {
  // cutoutDistance ≤ min_i (n_i·x + w_i) + amplitude: a point where one plane's distance lies
  // below −amplitude is kept. The pad covers the GPU's float rounding of the same sums.
  const float amplitude =
      jitter.pattern == CutoutJitter::Pattern::None ? 0.0f : jitter.amplitude * wedge.axisLength;
  const float reach = sceneReach(box.min) + sceneReach(box.max);
  std::vector<glm::vec4> kept;
  for (const glm::vec4& p : wedge.planes) {
    const float pad = 1e-5f * (std::abs(p.w) + reach);
    const glm::vec4 k(-glm::vec3(p), -p.w - std::abs(amplitude) - pad - beyond);
    // The box's corner deepest in k's half-space: whether k holds any of the box.
    const glm::vec3 deepest(k.x > 0 ? box.max.x : box.min.x, k.y > 0 ? box.max.y : box.min.y,
                            k.z > 0 ? box.max.z : box.min.z);
    if (glm::dot(glm::vec3(k), deepest) + k.w >= 0.0f) kept.push_back(k);
  }
  return kept;
}

}  // namespace cutaway
