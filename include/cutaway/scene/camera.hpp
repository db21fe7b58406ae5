// cutaway/scene/camera.hpp — the scene's camera: projection, placement, an optional path of
// keys over time, and the view and projection matrices it makes.
//
//   cutaway::Camera c{.eye = {0, 2, 10}, .target = {0, 0, 0}, .near = 1, .far = 50};
//   glm::mat4 viewProjection = c.projectionMatrix(4.0f / 3.0f) * c.view();
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace cutaway {

enum class Projection { Perspective, Orthographic };

struct CameraKey {
  float time;
  glm::vec3 eye, target;
};

struct Camera {
  Projection projection = Projection::Perspective;
  glm::vec3 eye{0, 0, 5}, target{0, 0, 0}, up{0, 1, 0};
  float fovY = 40.0f;           // degrees, perspective
  float height = 2.0f;          // world units of the view's height, orthographic
  float near = 0, far = 0;      // 0: derived from the scene bounds
  bool fit = false;             // place eye/target so the scene fills the view
  std::vector<CameraKey> path;  // eye/target over time (overrides eye, target, fit)

  glm::mat4 view() const;
  glm::mat4 projectionMatrix(float aspect) const;
  // Why 32-bit floats cannot draw this resolved camera's view (near and far set), or "":
  // eye and target closer than a few of the floats' steps at their magnitude, a depth range
  // [near, far] as thin, a perspective one deeper than 1e6 (far / near: its depth buffer
  // cannot order surfaces), or matrices that are not finite (a scene 1e-30 across).
  // A perspective range deeper than `deepestRange` (far / near; 0: any) is one too.
  std::string unresolvable(float aspect, float deepestRange = 0.0f) const;
  // World units of the view's height at the target (orthographic: `height`).
  float viewHeightAtTarget() const;
  // Where the view ray through world point `x` starts: the eye, or for orthographic views
  // x's foot on the view plane through the eye (as the cutters' GLSL has it).
  glm::vec3 rayOrigin(const glm::vec3& x) const;
  // Switches the projection keeping the view's height at the target: the orthographic height
  // of the perspective frustum there, or a perspective eye backed off along its line of sight
  // until it sees the orthographic height.
  void setProjection(Projection to);
};

}  // namespace cutaway
