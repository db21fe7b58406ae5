#include "camera_controller.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>

namespace cutaway::view {

namespace {

// `offset` turned by yaw about `up` and pitch about the axis perpendicular to both, with
// the polar angle to `up` kept in [kMinPolarDegrees, 180° − kMinPolarDegrees].
glm::vec3 turn(const glm::vec3& offset, const glm::vec3& upAxis, float yawDegrees,
               float pitchDegrees) {
  const glm::vec3 up = glm::normalize(upAxis);
  const float length = glm::length(offset);
  glm::vec3 d = glm::angleAxis(glm::radians(yawDegrees), up) * (offset / length);
  const float polar = glm::degrees(std::acos(std::clamp(glm::dot(d, up), -1.0f, 1.0f)));
  const float newPolar =
      std::clamp(polar - pitchDegrees, kMinPolarDegrees, 180.0f - kMinPolarDegrees);
  glm::vec3 axis = glm::cross(up, d);
  if (glm::length(axis) < 1e-6f) axis = glm::cross(up, glm::vec3(1, 0, 0));
  if (glm::length(axis) < 1e-6f) axis = glm::cross(up, glm::vec3(0, 0, 1));
  axis = glm::normalize(axis);
  // A rotation about up × d by +α increases the polar angle by α.
  d = glm::angleAxis(glm::radians(newPolar - polar), axis) * d;
  return d * length;
}

// The view's right and true up axes.
void viewAxes(const Camera& camera, glm::vec3& right, glm::vec3& up, glm::vec3& forward) {
  forward = glm::normalize(camera.target - camera.eye);
  right = glm::cross(forward, camera.up);
  right = glm::length(right) < 1e-6f ? glm::vec3(1, 0, 0) : glm::normalize(right);
  up = glm::cross(right, forward);
}

}  // namespace

void orbit(Camera& camera, float yawDegrees, float pitchDegrees) {
  // A positive yaw carries the eye towards the view's right (about up, counter-clockwise
  // seen from above); a positive pitch raises it.
  camera.eye =
      camera.target + turn(camera.eye - camera.target, camera.up, yawDegrees, pitchDegrees);
}

void look(Camera& camera, float yawDegrees, float pitchDegrees) {
  // The gaze is the opposite of the eye's offset: turning it right is a clockwise turn seen
  // from above (−yaw), and raising it lowers its polar angle like raising an orbiting eye.
  camera.target =
      camera.eye + turn(camera.target - camera.eye, camera.up, -yawDegrees, pitchDegrees);
}

void pan(Camera& camera, float dx, float dy) {
  glm::vec3 right, up, forward;
  viewAxes(camera, right, up, forward);
  const float h = camera.viewHeightAtTarget();
  const glm::vec3 move = (right * dx + up * dy) * h;
  camera.eye += move;
  camera.target += move;
}

void zoom(Camera& camera, float factor) {
  if (!(factor > 0.0f)) return;
  if (camera.projection == Projection::Orthographic) {
    camera.height /= factor;
    return;
  }
  camera.eye = camera.target + (camera.eye - camera.target) / factor;
}

void fly(Camera& camera, const glm::vec3& move) {
  glm::vec3 right, up, forward;
  viewAxes(camera, right, up, forward);
  const glm::vec3 world = right * move.x + up * move.y + forward * move.z;
  camera.eye += world;
  camera.target += world;
}

void frameBounds(Camera& camera, const Bounds& bounds, float aspect) {
  if (bounds.empty()) return;
  const glm::vec3 direction = glm::normalize(camera.eye - camera.target);
  const float radius = std::max(bounds.radius(), 1e-4f) * 1.05f;
  camera.target = bounds.center();
  const float tanHalfY = std::tan(glm::radians(camera.fovY) * 0.5f);
  const float tanHalf = std::min(tanHalfY, tanHalfY * aspect);
  if (camera.projection == Projection::Orthographic) {
    camera.height = 2.0f * radius * std::max(1.0f, 1.0f / aspect);
    camera.eye = camera.target + direction * (radius * 3.0f);
  } else {
    // The bounding sphere touches the narrower of the view's half-angles.
    const float distance = radius / std::sin(std::atan(tanHalf));
    camera.eye = camera.target + direction * distance;
  }
}

}  // namespace cutaway::view
