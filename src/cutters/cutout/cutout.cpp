#include "cutters/cutout/cutout.hpp"

#include <map>

#include "cutaway/core/error.hpp"

namespace cutaway {

std::vector<ExteriorUnit> exteriorUnits(const Scene& scene) {
  std::vector<ExteriorUnit> units;
  std::map<std::string, std::size_t> unitOfGroup;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    if (o.proxy || o.role != Role::Exterior) continue;
    if (o.group.empty()) {
      units.push_back({o.name, {i}, {}});
      continue;
    }
    const auto [it, added] = unitOfGroup.emplace(o.group, units.size());
    if (added) units.push_back({o.group, {}, {}});
    units[it->second].objects.push_back(i);
  }
  for (auto& unit : units) {
    std::vector<glm::vec3> points;
    for (const std::size_t i : unit.objects) {
      const SceneObject& o = scene.objects[i];
      const glm::mat4 m = o.transformAt(0.0f);
      for (const auto& p : o.mesh->positions) points.push_back(glm::vec3(m * glm::vec4(p, 1.0f)));
    }
    try {
      unit.axes = principalAxes(points);
    } catch (const Error& e) {
      throw Error(scene.file.string(), "exterior \"" + unit.name + "\"",
                  "no main axis: " + e.reason() + " (a flat exterior has no inside to show)");
    }
  }
  return units;
}

Cutout::Cutout(const Scene& scene, const CutoutOptions& options)
    : options_(options), units_(exteriorUnits(scene)), unitOfObject_(scene.objects.size(), -1) {
  for (std::size_t u = 0; u < units_.size(); ++u)
    for (const std::size_t i : units_[u].objects) unitOfObject_[i] = int(u);
  wedges_.resize(units_.size());
  if (options.jitter.pattern == CutoutJitter::Pattern::Image) {
    const FloatImage& image = options.jitter.imageData;
    imageTexture_ = gl::Texture::create(GL_TEXTURE_2D);
    const GLuint id = imageTexture_.id();
    glTextureStorage2D(id, 1, GL_R32F, image.width, image.height);
    glTextureSubImage2D(id, 0, 0, 0, image.width, image.height, GL_RED, GL_FLOAT,
                        image.data.data());
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_REPEAT);
  }
}

void Cutout::setCamera(const Camera& camera) {
  for (std::size_t u = 0; u < units_.size(); ++u) {
    const PrincipalAxes& axes = units_[u].axes;
    const glm::vec3 towardsViewer = camera.projection == Projection::Orthographic
                                        ? camera.eye - camera.target
                                        : camera.eye - axes.center;
    wedges_[u] = cutoutWedge(axes, options_, towardsViewer);
  }
}

void Cutout::bind() const {
  if (imageTexture_.id()) glBindTextureUnit(10, imageTexture_.id());
}

const CutoutWedge* Cutout::wedgeOf(std::size_t index) const {
  const int u = unitOfObject_[index];
  return u < 0 ? nullptr : &wedges_[std::size_t(u)];
}

void Cutout::setUniforms(GLuint program, std::size_t index) const {
  // Locations of src/cutters/cutout/cutout.glsl.
  constexpr GLint kPlanes = 20, kPlaneCount = 24, kOrigin = 25, kAxis = 26, kJitter = 27;
  const CutoutWedge* w = wedgeOf(index);
  if (!w) {
    glProgramUniform1i(program, kPlaneCount, 0);
    return;
  }
  glProgramUniform4fv(program, kPlanes, GLsizei(w->planes.size()), &w->planes[0][0]);
  glProgramUniform1i(program, kPlaneCount, GLint(w->planes.size()));
  glProgramUniform4f(program, kOrigin, w->origin.x, w->origin.y, w->origin.z, w->axisLength);
  glProgramUniform3fv(program, kAxis, 1, &w->axis[0]);
  const CutoutJitter& j = options_.jitter;
  glProgramUniform4f(program, kJitter, float(int(j.pattern)), j.amplitude * w->axisLength,
                     j.frequency / w->axisLength, float(j.octaves));
}

}  // namespace cutaway
