#include "cutters/box_cut/box_cut.hpp"

namespace cutaway {

CutterType boxCutCutterType() {
  return {.key = BoxCutOptions::kKey,
          .title = "Box cut (Li07, Konev18)",
          .glsl = "cutters/box_cut/box_cut.glsl",
          .name = "boxCut",
          .schema = &boxCutSchema(),
          .create = [](FrameSetup& setup) -> std::unique_ptr<Cutter> {
            return std::make_unique<BoxCut>(setup);
          }};
}

BoxCut::BoxCut(FrameSetup& setup)
    : setup_(setup),
      centerLocation_(setup.bindings.uniformLocation("BOX_CUT_CENTER")),
      axesLocation_(setup.bindings.uniformLocation("BOX_CUT_AXES", 3)),
      halfLocation_(setup.bindings.uniformLocation("BOX_CUT_HALF")) {}

void BoxCut::beginFrame(const FrameState& state) {
  // An object the box does not meet keeps every fragment: it draws without the box's code
  // (its back faces behind the box are no cut wall of its own).
  const Scene& scene = setup_.scene;
  reaches_.assign(scene.objects.size(), true);
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const Bounds& local = setup_.meshes.mesh(i).bounds();
    if (local.empty() || !cuts(i)) continue;
    reaches_[i] = boxCutMeetsBox(options(), shadedBox(scene, local, i, state.time, state.uniforms));
  }
}

bool BoxCut::cuts(std::size_t index) const {
  const SceneObject& o = setup_.scene.objects[index];
  return o.role != Role::Interest && o.mayBeCutBy(BoxCutOptions::kKey);
}

bool BoxCut::cutsVolume(std::size_t index) const {
  const SceneVolume& v = setup_.scene.volumes[index];
  return v.role != Role::Interest && v.mayBeCutBy(BoxCutOptions::kKey);
}

CutLook BoxCut::look(std::size_t index) const {
  // Diepstraten03 rule 5: a solid shows its cut wall; a hollow object its inside.
  const SceneObject& o = setup_.scene.objects[index];
  return {.cutSurface = o.solid(),
          .cutColor = options().cutSurfaceColor.value_or(o.material.color * 0.8f)};
}

void BoxCut::setProgramUniforms(GLuint program) const {
  const BoxCutOptions& o = options();
  const glm::mat3 axes = boxCutAxes(o);
  const glm::vec3 half = 0.5f * o.size;
  glProgramUniform3fv(program, centerLocation_, 1, &o.center[0]);
  glProgramUniform3fv(program, axesLocation_, 3, &axes[0][0]);
  glProgramUniform3fv(program, halfLocation_, 1, &half[0]);
}

std::optional<glm::vec3> BoxCut::cutOutlineColor() const {
  if (!options().outlines) return std::nullopt;
  return glm::vec3(0.0f);
}

}  // namespace cutaway
