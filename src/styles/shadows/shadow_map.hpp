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
//   ShadowMap shadows(setup);
//   shadows.addPass(frame);
//   // per frame: fill shadows.lightUniforms() with the frame uniforms seen from the light;
//   // in the geometry pass: shadows.bindForLookup();
#pragma once

#include <cstddef>
#include <functional>

#include <glm/glm.hpp>

#include "cutaway/geometry/mesh.hpp"
#include "cutaway/frame/frame.hpp"
#include "cutaway/scene/scene.hpp"
#include "frame/frame_setup.hpp"

namespace cutaway {

struct LightFrustum {
  glm::mat4 view, projection;
  bool orthographic;
  float near, far;  // along the light's axis, scene units
};

// The key light's frustum around `bounds` (world space). `lightVector` is the light as the
// renderer passes it: w = 0, the direction the light travels; w = 1, its position.
LightFrustum keyLightFrustum(const glm::vec4& lightVector, const Bounds& bounds);
// A point light beyond 1e4 radii of `bounds` as the directional light along its axis (it shines
// on the scene in parallel to within 1e-4 rad), worked out in double: at 1e19 and beyond, the
// float square of its distance overflowed, and shading and shadows went dark. Any other light
// as it is.
glm::vec4 farLightAsDirectional(const glm::vec4& lightVector, const Bounds& bounds);

// world → [0, 1]³ shadow-map coordinates (texture s, t and window depth).
glm::mat4 shadowMatrix(const LightFrustum& frustum);

// Whether `object` is drawn into the shadow map.
bool castsShadow(const SceneObject& object);

class ShadowMap {
 public:
  // Declares the targets "shadowMap" (AOV: linear depth from the light) and "shadowDepth" and
  // allocates the lookup's texture unit.
  explicit ShadowMap(FrameSetup& setup);
  // The "shadowMap" pass: the scene meshes that cast, then the other kinds' casters
  // (FrameSetup::drawShadowCasters), with the light's uniforms bound.
  void addPass(Frame& frame);
  // The depth map the geometry pass reads.
  Target depth() const { return depth_; }
  // The uniform buffer the pass binds at the frame's block instead of the frame's: the frame
  // uniforms with the light as the camera, filled by the composer every frame.
  GLuint lightUniforms() const { return lightUniforms_.id(); }
  // Whether this frame has a key light to cast shadows from (the pass draws nothing without).
  void setActive(bool active) { active_ = active; }
  // Binds the depth map, with hardware depth comparison, for the geometry pass.
  void bindForLookup() const;

 private:
  const ShadowStyle& style() const { return setup_.scene.style.shadows; }

  FrameSetup& setup_;
  gl::Program program_;
  gl::Buffer lightUniforms_;
  GLuint unit_;
  Target map_, depth_;
  bool active_ = false;
};

}  // namespace cutaway
