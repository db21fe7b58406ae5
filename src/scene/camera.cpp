#include "cutaway/scene/camera.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>

namespace cutaway {

glm::mat4 Camera::view() const {
  return glm::lookAt(eye, target, up);
}

glm::mat4 Camera::projectionMatrix(float aspect) const {
  if (projection == Projection::Orthographic) {
    const float h = height * 0.5f, w = h * aspect;
    return glm::ortho(-w, w, -h, h, near, far);
  }
  return glm::perspective(glm::radians(fovY), aspect, near, far);
}

std::string Camera::unresolvable(float aspect, float deepestRange) const {
  const auto text = [](double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.3g", v);
    return std::string(buffer);
  };
  // Eight float steps (2⁻²³ relative each) apart at least: fewer leave the view's direction,
  // or its depth, to the rounding. (Lengths in double: a float's squares underflow at 1e-20.)
  constexpr double kSteps = 8.0 / double(1 << 23);
  for (const auto& [name, point] : {std::pair{"eye", eye}, std::pair{"target", target}})
    if (!std::isfinite(point.x) || !std::isfinite(point.y) || !std::isfinite(point.z))
      return std::string(name) + " (" + text(point.x) + ", " + text(point.y) + ", " +
             text(point.z) + ") is not finite in 32-bit floats";
  const double distance = glm::length(glm::dvec3(eye) - glm::dvec3(target));
  const double magnitude = std::max(glm::length(glm::dvec3(eye)), glm::length(glm::dvec3(target)));
  if (!(distance > kSteps * magnitude))
    return "eye and target are " + text(distance) + " apart at " + text(magnitude) +
           " from the origin, too close for 32-bit floats to give the view's direction";
  if (!(double(far) - double(near) > kSteps * std::max(std::abs(near), std::abs(far))))
    return "the depth range from near " + text(near) + " to far " + text(far) +
           " is too thin for 32-bit floats (the eye is " + text(distance) + " from the target)";
  // A window depth's float steps near 1 (2⁻²⁴) span ~6e-8 · far / near of the far distance: at
  // far / near = 1e6 the far half of the view keeps ~17 of them; at 1e8 every surface past a
  // few near distances rounds to the cleared 1 and the picture is blank.
  constexpr double kDeepestDepthBuffer = 1e6;
  const bool cut = deepestRange > 0.0f && double(deepestRange) < kDeepestDepthBuffer;
  const double deepest = cut ? double(deepestRange) : kDeepestDepthBuffer;
  if (projection == Projection::Perspective && double(far) > deepest * double(near))
    return "the depth range from near " + text(near) + " to far " + text(far) + " (far / near " +
           text(double(far) / double(near)) + ") is deeper than " +
           (cut ? "the adaptive cutaway" : "a 32-bit depth buffer") + " resolves (" +
           text(deepest) + "): give a larger near";
  const glm::mat4 m = projectionMatrix(aspect) * view();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) {
        const glm::dvec3 along = (glm::dvec3(target) - glm::dvec3(eye)) / distance;
        if (!(glm::length(glm::cross(along, glm::dvec3(up))) > 1e-6 * glm::length(glm::dvec3(up))))
          return "the up vector (" + text(up.x) + ", " + text(up.y) + ", " + text(up.z) +
                 ") is zero or parallel to the view direction";
        return "its view and projection are not finite in 32-bit floats (eye and target " +
               text(distance) + " apart, near " + text(near) + ", far " + text(far) + ")";
      }
  return "";
}

float Camera::viewHeightAtTarget() const {
  if (projection == Projection::Orthographic) return height;
  return 2.0f * glm::length(target - eye) * std::tan(glm::radians(fovY) * 0.5f);
}

glm::vec3 Camera::rayOrigin(const glm::vec3& x) const {
  if (projection != Projection::Orthographic) return eye;
  const glm::vec3 forward = glm::normalize(target - eye);
  return x - forward * glm::dot(x - eye, forward);
}

void Camera::setProjection(Projection to) {
  if (projection == to) return;
  const float distance = glm::length(target - eye);
  const float tanHalf = std::tan(glm::radians(fovY) * 0.5f);
  if (to == Projection::Orthographic)
    height = 2.0f * distance * tanHalf;
  else
    eye = target + (eye - target) / distance * (height * 0.5f / tanHalf);
  projection = to;
}

}  // namespace cutaway
