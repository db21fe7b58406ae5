// Shadows from the key light (the first light) by shadow mapping (Williams 1978, "Casting
// curved shadows on curved surfaces"), with percentage-closer filtering (Reeves, Salesin,
// Cook 1987) and a slope-scaled depth bias, usable with every style: the geometry pass
// passes the key light's visibility to the style in SurfacePoint.keyLightVisibility.
//
// The "shadowMap" pass draws the casters from the light into a depth target; the light's
// frustum is an orthographic box fitted to the scene bounds for a directional light, a
// perspective frustum from the light's position around the bounds for a point light. Which
// objects cast: every visible object except those of role `exterior` (a closed outer shell
// would otherwise shadow everything inside it); the object parameter `castsShadow` overrides.
//
//   ShadowMap shadows(sceneGpu, scene.style.shadows, frame, sizeof(FrameUniforms));
//   // per frame: fill shadows.lightUniforms() with the frame uniforms seen from the light,
//   // then after the pass: shadows.bindForLookup();
#pragma once

#include <cstddef>
#include <functional>

#include <glm/glm.hpp>

#include "cutaway/geometry/mesh.hpp"
#include "cutaway/render/frame.hpp"
#include "cutaway/scene/scene.hpp"
#include "render/scene_gpu.hpp"

namespace cutaway {

// Texture unit of the shadow map in the geometry pass (src/styles/shadows/shadow_lookup.glsl).
constexpr GLuint kShadowMapUnit = 15;

struct LightFrustum {
  glm::mat4 view, projection;
  bool orthographic;
  float near, far;  // along the light's axis, scene units
};

// The key light's frustum around `bounds` (world space). `lightVector` is the light as the
// renderer passes it: w = 0, the direction the light travels; w = 1, its position.
LightFrustum keyLightFrustum(const glm::vec4& lightVector, const Bounds& bounds);

// world → [0, 1]³ shadow-map coordinates (texture s, t and window depth).
glm::mat4 shadowMatrix(const LightFrustum& frustum);

// Whether `object` is drawn into the shadow map.
bool castsShadow(const SceneObject& object);

class ShadowMap {
 public:
  // Declares the targets "shadowMap" (AOV: linear depth from the light) and "shadowDepth",
  // and adds the "shadowMap" pass to `frame`. `uniformBytes`: size of the frame uniform
  // block, of which the pass binds its own copy (the light as the camera) while it draws.
  ShadowMap(const SceneGpu& sceneGpu, const ShadowStyle& style, Frame& frame,
            std::size_t uniformBytes);
  // The uniform buffer the pass binds at binding 0 instead of the frame's.
  GLuint lightUniforms() const { return lightUniforms_.id(); }
  // Whether this frame has a key light to cast shadows from (the pass draws nothing without).
  void setActive(bool active) { active_ = active; }
  // Binds the depth map, with hardware depth comparison, for the geometry pass.
  void bindForLookup() const;
  // Casters that are no scene object (Konev18's billboard pipes): drawn after the objects,
  // into the same targets, with the light's uniforms bound.
  void setOtherCasters(std::function<void()> draw) { otherCasters_ = std::move(draw); }

 private:
  const SceneGpu& sceneGpu_;
  ShadowStyle style_;
  Frame& frame_;
  gl::Program program_;
  gl::Buffer lightUniforms_;
  bool active_ = false;
  std::function<void()> otherCasters_;
};

}  // namespace cutaway
