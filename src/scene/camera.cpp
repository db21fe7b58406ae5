#include "cutaway/scene/camera.hpp"

#include <cmath>
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
