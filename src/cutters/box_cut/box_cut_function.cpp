// The box cut's decision on the CPU: the same steps as box_cut.glsl.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "cutaway/cutters/box_cut.hpp"

namespace cutaway {

glm::mat3 boxCutAxes(const BoxCutOptions& o) {
  const glm::vec3 r = glm::radians(o.rotation);
  const glm::mat4 m = glm::rotate(glm::mat4(1.0f), r.z, glm::vec3(0, 0, 1)) *
                      glm::rotate(glm::mat4(1.0f), r.y, glm::vec3(0, 1, 0)) *
                      glm::rotate(glm::mat4(1.0f), r.x, glm::vec3(1, 0, 0));
  return glm::mat3(m);
}

bool boxCutMeetsBox(const BoxCutOptions& o, const Bounds& box) {
  if (box.empty()) return false;
  const glm::mat3 axes = boxCutAxes(o);
  const glm::vec3 half = 0.5f * o.size;
  const float margin = 1e-5f * (sceneReach(box.min) + sceneReach(box.max) + sceneReach(o.center) +
                                glm::length(half));
  // The object's box in the cut box's frame, and the cut box in the world's: separated when
  // their extents part along an axis of either.
  Bounds local, cut;
  for (int k = 0; k < 8; ++k) {
    const glm::vec3 corner{(k & 1) ? box.max.x : box.min.x, (k & 2) ? box.max.y : box.min.y,
                           (k & 4) ? box.max.z : box.min.z};
    local.extend(glm::transpose(axes) * (corner - o.center));
    const glm::vec3 sign{(k & 1) ? 1.0f : -1.0f, (k & 2) ? 1.0f : -1.0f, (k & 4) ? 1.0f : -1.0f};
    cut.extend(o.center + axes * (sign * half));
  }
  for (int i = 0; i < 3; ++i)
    if (local.min[i] > half[i] + margin || local.max[i] < -half[i] - margin ||
        box.min[i] > cut.max[i] + margin || box.max[i] < cut.min[i] - margin)
      return false;
  return true;
}

BoxCutFate boxCutFragment(const BoxCutOptions& o, const glm::vec3& x, bool frontFacing,
                          const glm::vec3& rayOrigin) {
  const glm::mat3 axes = boxCutAxes(o);
  const glm::mat3 toLocal = glm::transpose(axes);
  const glm::vec3 half = 0.5f * o.size;
  const glm::vec3 local = toLocal * (x - o.center);
  const bool inside = std::abs(local.x) <= half.x && std::abs(local.y) <= half.y &&
                      std::abs(local.z) <= half.z;
  using Fate = BoxCutFate::Fate;
  if (inside) return {Fate::Discard};
  if (frontFacing) return {Fate::Keep};
  // The view ray from → x against the box's slabs: [tIn, tOut] inside it, and the faces.
  const glm::vec3 from = toLocal * (rayOrigin - o.center), v = local - from;
  float tIn = -1e30f, tOut = 1e30f;
  int outAxis = -1;
  for (int i = 0; i < 3; ++i) {
    if (v[i] == 0.0f) {
      if (std::abs(from[i]) > half[i]) return {Fate::Keep};  // parallel, outside this slab
      continue;
    }
    const float a = (-half[i] - from[i]) / v[i], b = (half[i] - from[i]) / v[i];
    const float near = std::min(a, b), far = std::max(a, b);
    tIn = std::max(tIn, near);
    if (far < tOut) tOut = far, outAxis = i;
  }
  // The wall is where the ray left the box, in front of x.
  if (outAxis < 0 || !(tIn < tOut) || !(tOut > 0.0f && tOut < 1.0f)) return {Fate::Keep};
  // The face's normal towards the viewer: against the ray's direction along that axis.
  glm::vec3 n(0.0f);
  n[outAxis] = v[outAxis] > 0.0f ? -1.0f : 1.0f;
  return {Fate::CutSurface, o.center + axes * (from + tOut * v), axes * n};
}

}  // namespace cutaway
