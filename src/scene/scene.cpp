#include "cutaway/scene/scene.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace cutaway {

const char* roleName(Role role) {
  switch (role) {
    case Role::Context: return "context";
    case Role::Interest: return "interest";
    case Role::Exterior: return "exterior";
    case Role::Interior: return "interior";
  }
  return "?";
}

const std::vector<ObjectParamSpec>& objectParameterSpecs() {
  static const std::vector<ObjectParamSpec> specs{
      {"lines", ObjectParamSpec::Type::Bool, 0, 0,
       "draw silhouette and crease lines on this object (styles/lines)"},
  };
  return specs;
}

const std::vector<std::string>& styleNames() {
  static const std::vector<std::string> names{"gooch", "blinn-phong"};
  return names;
}

glm::mat4 Camera::view() const { return glm::lookAt(eye, target, up); }

glm::mat4 Camera::projectionMatrix(float aspect) const {
  if (projection == Projection::Orthographic) {
    const float h = height * 0.5f, w = h * aspect;
    return glm::ortho(-w, w, -h, h, near, far);
  }
  return glm::perspective(glm::radians(fovY), aspect, near, far);
}

Bounds Scene::bounds() const {
  Bounds b;
  for (const auto& o : objects)
    if (!o.proxy) b.extend(o.worldBounds());
  return b;
}

const SceneObject* Scene::find(const std::string& name) const {
  for (const auto& o : objects)
    if (o.name == name) return &o;
  return nullptr;
}

Camera Scene::resolvedCamera() const {
  Camera c = camera;
  const Bounds b = bounds();
  const glm::vec3 center = b.empty() ? glm::vec3(0.0f) : b.center();
  const float radius = std::max(b.radius(), 1e-3f);
  const float aspect = float(width) / float(height);
  if (c.fit) {
    // Keep the viewing direction (eye − target), aim at the bounds' centre and back off until
    // the bounding sphere fits the narrower field of view.
    glm::vec3 direction = c.eye - c.target;
    if (glm::length(direction) < 1e-6f) direction = glm::vec3(1.0f, 0.8f, 1.4f);
    direction = glm::normalize(direction);
    c.target = center;
    if (c.projection == Projection::Perspective) {
      const float halfY = glm::radians(c.fovY) * 0.5f;
      const float halfX = std::atan(std::tan(halfY) * aspect);
      const float distance = radius / std::sin(std::min(halfX, halfY));
      c.eye = center + direction * distance;
    } else {
      c.height = 2.0f * radius * std::max(1.0f, 1.0f / aspect);
      c.eye = center + direction * (radius * 3.0f);
    }
  }
  // Depth range hugging the scene: better depth precision than a fixed range.
  const float distance = glm::length(center - c.eye);
  if (c.near <= 0.0f) {
    const float n = distance - radius * 1.05f;
    c.near = c.projection == Projection::Perspective ? std::max(n, radius * 1e-3f)
                                                     : n;
  }
  if (c.far <= 0.0f) c.far = distance + radius * 1.05f;
  if (c.far <= c.near) c.far = c.near + radius * 2.0f;
  return c;
}

}  // namespace cutaway
