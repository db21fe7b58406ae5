// The per-frame uniform block every program reads (std140 mirror of
// frame/frame_uniforms.glsl, binding Bindings::kFrameUniformBlock), and the state of one frame
// that techniques update their own uniforms from.
#pragma once

#include <glm/glm.hpp>

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

}  // namespace cutaway
