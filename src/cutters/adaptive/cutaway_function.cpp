// Burns08 / Burns11 cone math for one seed pixel; mirrored line by line in anchors.frag.
#include <algorithm>
#include <cmath>

#include "cutaway/cutters/adaptive.hpp"
#include "cutaway/scene/scene.hpp"

namespace cutaway {

namespace {
float clamp01(float x) {
  return std::clamp(x, 0.0f, 1.0f);
}
float smoothstep(float a, float b, float x) {
  const float t = clamp01((x - a) / (b - a));
  return t * t * (3.0f - 2.0f * t);
}
constexpr float kPi = 3.14159265358979f;
// θ = 0 would make the slope infinite and tan(float(π/2)) is negative: keep a sliver of
// angle away from both ends.
constexpr float kMinAngle = 1e-4f;
constexpr float kFloorMargin = 2.0f * kPi / 180.0f;
}  // namespace

AnchorCone anchorCone(const glm::vec3& ndc, float theta, const AdaptiveCutawayOptions& o,
                      const CutawayProjection& camera) {
  const glm::mat4& P = camera.projection;
  // Burns11 eq. 5.8: narrow cones near the screen edge, so objects entering the view do not
  // pop in with a full-size cutaway.
  float thetaE = theta;
  if (o.edgeCompression)
    thetaE *= clamp01((1.0f - std::abs(ndc.x)) / o.edgeRegion) *
              clamp01((1.0f - std::abs(ndc.y)) / o.edgeRegion);
  float thetaF = thetaE;
  glm::vec2 floor(0.0f);
  float floorBound = 0.0f;  // the least m_F that keeps the wall off the floor
  if (o.directionalConstraint) {
    const glm::mat4 inverse = glm::inverse(P);
    const glm::vec4 h = inverse * glm::vec4(ndc, 1.0f);
    const glm::vec3 point = glm::vec3(h) / h.w;  // view space
    const glm::vec3 toEye = camera.orthographic ? glm::vec3(0, 0, 1) : glm::normalize(-point);
    const glm::vec3 n = glm::normalize(camera.viewRotation * o.floorNormal);
    // Eq. 6.1: φ, the largest angle that keeps the cone off a surface with normal n.
    // (= asin(n·v), computed as in anchors.frag)
    const float nv = std::clamp(glm::dot(n, toEye), -1.0f, 1.0f);
    const float phi = std::atan2(nv, std::sqrt(1.0f - nv * nv));
    // Eq. 6.2: clamp θ to φ above the floor, open back to θ within 10° below it. The clamp
    // keeps kFloorMargin below φ: at exactly φ the wall of a seed resting on the floor lies
    // in the floor plane and the floor flickers between cut and kept (depth precision).
    thetaF = std::clamp(thetaE, 0.0f, std::max(phi - kFloorMargin, 0.0f)) +
             thetaE * smoothstep(0.0f, kPi / 18.0f, -phi);
    // Eq. 6.3's n̂_proj: the screen direction of n at the seed, d/dt of the projection of
    // point + t·n (quotient rule, no finite difference), in view-plane units.
    const glm::vec4 c = P * glm::vec4(point, 1.0f), dc = P * glm::vec4(n, 0.0f);
    const glm::vec2 d = (glm::vec2(dc) * c.w - glm::vec2(c) * dc.w) / glm::vec2(P[0][0], P[1][1]);
    const float len = glm::length(d);
    if (len > 1e-9f) floor = d / len;
    // Eq. 6.2 asks for a wall no shallower than the floor down the screen; in perspective, eq.
    // 5.7's slope for φ is the floor's only on the view axis (off it, 2 % shallower at the
    // fan room's desk leg, whose wall dug a notch into the floor). The floor plane
    // through the seed has an NDC depth affine in NDC x, y (z = −(L₀ + x·Lx + y·Ly)/Q, from the
    // inverse projection): its own slope along n̂_proj bounds m_F, with the margin's ratio
    // tan φ / tan(φ − margin). (Orthographic slopes are exact.)
    if (o.perspectiveCompensation && !camera.orthographic && phi > kFloorMargin) {
      const float nDotPoint = glm::dot(n, point);
      const auto plane = [&](const glm::vec4& v) {
        return glm::dot(n, glm::vec3(v)) - nDotPoint * v.w;
      };
      const float q = plane(inverse[2]);
      const glm::vec2 gradient =
          -glm::vec2(P[0][0] * plane(inverse[0]), P[1][1] * plane(inverse[1])) / q;
      const float floorSlope = glm::dot(gradient, floor);
      if (std::isfinite(floorSlope) && floorSlope > 0.0f)
        floorBound = floorSlope * std::tan(phi) / std::tan(phi - kFloorMargin);
    }
  }
  auto slope = [&](float angle) {
    const float t = std::tan(std::clamp(angle, kMinAngle, kPi / 2.0f - kMinAngle));
    if (!o.perspectiveCompensation) return P[1][1] / t;     // Burns08 §3: fixed screen-space slope
    if (camera.orthographic) return std::abs(P[2][2]) / t;  // exact: depth is linear
    // Burns11 eq. 5.7: m = −(PM_sz + z)/tan θ, PM_sz = (n + f)/(n − f) = P[2][2].
    return -(P[2][2] + ndc.z) / t;
  };
  return {slope(thetaE), std::max(slope(thetaF), floorBound), floor};
}

bool cutawayOnCpu(const AdaptiveCutawayOptions& options, bool softwareRenderer) {
  return options.compute == AdaptiveCutawayOptions::Compute::Cpu ||
         (options.compute == AdaptiveCutawayOptions::Compute::Auto && softwareRenderer);
}

CutawayProjection cutawayProjection(const Camera& camera, float aspect) {
  return {camera.projectionMatrix(aspect), glm::mat3(camera.view()),
          camera.projection == Projection::Orthographic};
}

fields::SeedImage makeSeedImage(const std::vector<float>& seedDepth,
                                const std::vector<float>& seedAngle, int n,
                                const AdaptiveCutawayOptions& options,
                                const CutawayProjection& camera) {
  // View-plane units per buffer pixel: Δndc / P00 horizontally, Δndc / P11 vertically.
  fields::SeedImage seeds(n, n, 2.0f / float(n) / camera.projection[0][0],
                          2.0f / float(n) / camera.projection[1][1]);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(n) + std::size_t(x);
      if (seedDepth[i] <= 0.0f) continue;  // cleared to the near plane: no seed
      const glm::vec3 ndc((float(x) + 0.5f) / float(n) * 2.0f - 1.0f,
                          (float(y) + 0.5f) / float(n) * 2.0f - 1.0f, seedDepth[i] * 2.0f - 1.0f);
      const AnchorCone cone = anchorCone(ndc, seedAngle[i], options, camera);
      seeds.set(x, y, ndc.z, cone.slopeE, cone.slopeF, cone.floor.x, cone.floor.y);
    }
  return seeds;
}

GreatestDepth::GreatestDepth(std::vector<float> depth, int n) {
  levels_.push_back(std::move(depth));
  sizes_.push_back(n);
  for (int size = n; size > 1;) {
    const int half = (size + 1) / 2;
    const std::vector<float>& below = levels_.back();
    std::vector<float> level(std::size_t(half) * std::size_t(half));
    for (int y = 0; y < half; ++y)
      for (int x = 0; x < half; ++x) {
        float m = below[std::size_t(2 * y) * std::size_t(size) + std::size_t(2 * x)];
        for (int k = 1; k < 4; ++k) {
          const int bx = std::min(2 * x + (k & 1), size - 1),
                    by = std::min(2 * y + (k >> 1), size - 1);
          m = std::max(m, below[std::size_t(by) * std::size_t(size) + std::size_t(bx)]);
        }
        level[std::size_t(y) * std::size_t(half) + std::size_t(x)] = m;
      }
    levels_.push_back(std::move(level));
    sizes_.push_back(size = half);
  }
}

float GreatestDepth::over(glm::vec2 lo, glm::vec2 hi) const {
  if (levels_.empty()) return 1.0f;
  const int n = sizes_[0];
  // The texels the samples mix (centres at (k + ½)/n); the texture repeats, so a footprint
  // past an edge takes the whole axis.
  const auto span = [n](float a, float b) {
    const float first = std::floor(a * float(n) - 0.5f),
                last = std::floor(b * float(n) - 0.5f) + 1.0f;
    return first < 0.0f || last > float(n - 1) ? glm::ivec2(0, n - 1)
                                               : glm::ivec2(int(first), int(last));
  };
  glm::ivec2 xs = span(lo.x, hi.x), ys = span(lo.y, hi.y);
  std::size_t level = 0;
  while (level + 1 < levels_.size() && std::max(xs.y - xs.x, ys.y - ys.x) > 1)
    xs /= 2, ys /= 2, ++level;
  float m = 0.0f;
  for (int y = ys.x; y <= ys.y; ++y)
    for (int x = xs.x; x <= xs.y; ++x)
      m = std::max(m, levels_[level][std::size_t(y) * std::size_t(sizes_[level]) + std::size_t(x)]);
  return m;
}

bool cutawayKeepsBox(const Bounds& box, const glm::mat4& viewProjection, const GreatestDepth& c) {
  glm::vec2 lo(1e30f), hi(-1e30f);
  float nearest = 1e30f;
  for (int k = 0; k < 8; ++k) {
    const glm::vec4 clip =
        viewProjection * glm::vec4((k & 1) ? box.max.x : box.min.x, (k & 2) ? box.max.y : box.min.y,
                                   (k & 4) ? box.max.z : box.min.z, 1.0f);
    if (clip.w <= 0.0f || clip.z < -clip.w) return false;
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    lo = glm::min(lo, glm::vec2(ndc)), hi = glm::max(hi, glm::vec2(ndc));
    nearest = std::min(nearest, 0.5f * ndc.z + 0.5f);  // window depth grows with view depth
  }
  const float greatest = c.over(0.5f * lo + 0.5f, 0.5f * hi + 0.5f);
  return nearest >= greatest;
}

}  // namespace cutaway
