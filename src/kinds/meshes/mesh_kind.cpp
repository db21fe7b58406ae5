#include "kinds/meshes/mesh_kind.hpp"

#include <algorithm>

namespace cutaway {

namespace {
// Uniform locations of kinds/meshes/mesh.frag and frame/mesh.vert.
constexpr GLint kColor = 8, kSpecular = 9, kShininess = 10, kObjectId = 11, kLines = 12,
                kCutBy = 13, kCutSurfaces = 14, kBackColor = 15, kClipPlane = 18, kCutColor = 24;
}  // namespace

void MeshKind::prepare(const std::vector<ActiveCutter>&) {
  program_ = gl::buildProgram(setup_.geometryProgram(
      {{GL_VERTEX_SHADER, "frame/mesh.vert"}, {GL_FRAGMENT_SHADER, "kinds/meshes/mesh.frag"}}));
}

void MeshKind::drawGeometry(const std::vector<ActiveCutter>& cutters, const GeometryDraw&) const {
  const GLuint program = program_.id();
  for (const ActiveCutter& c : cutters) c.cutter->setProgramUniforms(program);
  int clipPasses = 0;  // the most any object needs
  auto setUniforms = [&](const SceneObject& o, std::size_t i) {
    glProgramUniform3fv(program, kColor, 1, &o.material.color[0]);
    glProgramUniform1f(program, kSpecular, o.material.specular);
    glProgramUniform1f(program, kShininess, o.material.shininess);
    glProgramUniform1i(program, kObjectId, int(i));
    const auto lines = o.params.find("lines");
    const bool objectLines = lines == o.params.end() || std::get<bool>(lines->second);
    glProgramUniform1f(program, kLines, objectLines ? 1.0f : 0.0f);
    int cutBy = 0, cutSurfaces = 0;
    std::optional<glm::vec3> backColor;
    for (const ActiveCutter& c : cutters) {
      const bool cuts = c.cutter->cuts(i);
      if (!cuts && c.cutter->clipPasses(i) == 0) continue;
      const CutLook look = c.cutter->look(i);
      if (cuts) cutBy |= 1 << c.slot;
      if (look.cutSurface) cutSurfaces |= 1 << c.slot;
      glProgramUniform3fv(program, kCutColor + c.slot, 1, &look.cutColor[0]);
      if (!backColor) backColor = look.backColor;
      c.cutter->setObjectUniforms(program, i);
    }
    glProgramUniform1i(program, kCutBy, cutBy);
    glProgramUniform1i(program, kCutSurfaces, cutSurfaces);
    const glm::vec3 back = backColor.value_or(o.material.color);
    glProgramUniform3fv(program, kBackColor, 1, &back[0]);
  };
  const auto clippedByPlanes = [&](std::size_t i) {
    int passes = 0;
    for (const ActiveCutter& c : cutters) passes = std::max(passes, c.cutter->clipPasses(i));
    return passes;
  };
  const Scene& scene = setup_.scene;
  std::vector<int> passesOf(scene.objects.size(), 0);
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    passesOf[i] = clippedByPlanes(i);
    clipPasses = std::max(clipPasses, passesOf[i]);
  }
  // Secondary objects first, cut; then the objects of interest, whole (Burns08 §4.1).
  setup_.meshes.draw(
      program,
      [&](const SceneObject& o, std::size_t i) {
        return !o.proxy && o.role != Role::Interest && passesOf[i] == 0;
      },
      setUniforms);
  if (clipPasses > 0) {
    // Diepstraten03 §4.3: each pass keeps the far side of one plane; their union is the object
    // outside the cut.
    glEnable(GL_CLIP_DISTANCE0);
    for (int k = 0; k < clipPasses; ++k)
      setup_.meshes.draw(
          program,
          [&](const SceneObject& o, std::size_t i) { return !o.proxy && passesOf[i] > k; },
          [&](const SceneObject& o, std::size_t i) {
            setUniforms(o, i);
            glm::vec4 keep(0, 0, 0, -1);
            for (const ActiveCutter& c : cutters)
              if (k < c.cutter->clipPasses(i)) keep = c.cutter->clipPlane(i, k);
            glProgramUniform4fv(program, kClipPlane, 1, &keep[0]);
          });
    glDisable(GL_CLIP_DISTANCE0);
  }
  setup_.meshes.draw(
      program,
      [&](const SceneObject& o, std::size_t i) {
        return !o.proxy && o.role == Role::Interest && passesOf[i] == 0;
      },
      setUniforms);
}

}  // namespace cutaway
