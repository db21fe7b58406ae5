// The per-frame uniform block every program reads (std140 mirror of
// frame/frame_uniforms.glsl, binding Bindings::kFrameUniformBlock), and the state of one frame
// that techniques update their own uniforms from.
#pragma once

#include <algorithm>
#include <limits>
#include <utility>

#include <glm/glm.hpp>

#include "cutaway/geometry/mesh.hpp"
#include "cutaway/scene/camera.hpp"

namespace cutaway {

struct FrameUniforms {
  glm::mat4 view, projection, viewProjection, inverseProjection, inverseView;
  glm::vec4 viewport;
  glm::vec4 eye, forward;
  glm::vec4 lightVector[8];
  glm::vec4 lightColor[8];
  glm::ivec4 counts;
  glm::vec4 backgroundTop, backgroundBottom;
  glm::mat4 shadowMatrix;
  glm::vec4 shadowParams;
};

// One frame, as the renderer resolved it before running the passes.
struct FrameState {
  const Camera& camera;  // resolved: near and far set
  float aspect;
  float time;  // seconds of the objects' animation
  const FrameUniforms& uniforms;
};

// The view depths of a world box's nearest and farthest corners.
inline std::pair<float, float> viewDepthRange(const Bounds& b, const glm::mat4& view) {
  float nearest = std::numeric_limits<float>::max(), farthest = -nearest;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner{(i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                           (i & 4) ? b.max.z : b.min.z};
    const float depth = -(view * glm::vec4(corner, 1.0f)).z;
    nearest = std::min(nearest, depth);
    farthest = std::max(farthest, depth);
  }
  return {nearest, farthest};
}

// The world size of a pixel (its longer side) at the farthest view depth of a world box, or
// anywhere orthographic: at view depth 1 a pixel spans 2 / (size · P₀₀) by 2 / (size · P₁₁).
// A fragment's interpolated position may lie this far outside its triangle (multisampled
// fragments are shaded at the pixel's centre).
inline float worldPixel(const Bounds& box, const FrameUniforms& u) {
  const float atOne = std::max(2.0f / (u.viewport.x * u.projection[0][0]),
                               2.0f / (u.viewport.y * u.projection[1][1]));
  return u.counts.y == 1 ? atOne : atOne * std::max(viewDepthRange(box, u.view).second, 0.0f);
}

}  // namespace cutaway
