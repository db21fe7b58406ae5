#include "frame/occlusion_culling.hpp"

#include "frame/depth_offsets.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cutaway {

namespace {

// Depth units (glPolygonOffset) the boxes come nearer by: more than the rounding of the
// depths interpolated over the object's triangles and over the box's faces, and than the
// offsets that draw surfaces nearer than they lie (frame/depth_offsets.hpp).
constexpr float kDepthUnits = 4.0f + kMostUnitsNearer;

}  // namespace

OcclusionCulling::OcclusionCulling(FrameSetup& setup, bool layers) : setup_(setup) {
  setup_.bindings.storageBlock("VISIBLE_OBJECTS");
  boxProgram_ =
      setup_.bindings.build({.stages = {{GL_VERTEX_SHADER, "frame/occlusion_box.vert"},
                                        {GL_FRAGMENT_SHADER, "frame/occlusion_box.frag"}}});
  if (layers)
    surfaceBoxProgram_ = setup_.bindings.build(
        {.stages = {{GL_VERTEX_SHADER, "frame/occlusion_box.vert"},
                    {GL_FRAGMENT_SHADER, "frame/occlusion_box.frag"}},
         .defines = sampleDefines(setup_.scene.samples, {{"SURFACES_ONLY", "1"}})});
  markProgram_ =
      setup_.bindings.build({.stages = {{GL_COMPUTE_SHADER, "frame/visible_objects.comp"}},
                             .defines = sampleDefines(setup_.scene.samples)});
  glGetProgramiv(markProgram_.id(), GL_COMPUTE_WORK_GROUP_SIZE, markGroup_.data());
  noAttributes_ = gl::VertexArray::create();
  const std::size_t objects = std::max<std::size_t>(setup_.scene.objects.size(), 1);
  visible_ = gl::Buffer::create(GLsizeiptr(objects * sizeof(GLuint)), nullptr, 0);
}

void OcclusionCulling::beginFrame(const FrameState& state) {
  culled_ = 0;
  hidden_.assign(setup_.scene.objects.size(), false);
  if (marked_) {
    shown_.resize(setup_.scene.objects.size());
    glGetNamedBufferSubData(visible_.id(), 0, GLsizeiptr(shown_.size() * sizeof(GLuint)),
                            shown_.data());
  }
  uniforms_ = state.uniforms;
  near_ = state.camera.near;
}

void OcclusionCulling::draw(const Batch& drawn, float time,
                            const std::function<void(const Batch&)>& drawBatch) const {
  drawBatch([this](std::size_t i) { return shown(i); });
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < setup_.scene.objects.size(); ++i)
    if (drawn(i) && !shown(i)) candidates.push_back(i);
  if (candidates.empty()) return;
  const std::vector<bool> passed = mayBeVisible(candidates, time);
  drawBatch([&](std::size_t i) { return passed[i]; });
}

std::vector<bool> OcclusionCulling::mayBeVisible(const std::vector<std::size_t>& candidates,
                                                 float time) const {
  const std::vector<bool> passed = boxesPass(candidates, time, Side::nearSide, boxProgram_.id());
  for (const std::size_t i : candidates) {
    hidden_[i] = !passed[i];
    culled_ += passed[i] ? 0 : 1;
  }
  return passed;
}

std::vector<bool> OcclusionCulling::mayReachBehind(const std::vector<std::size_t>& candidates,
                                                   float time, const gl::Texture& surfaces) const {
  if (!enabled_) return std::vector<bool>(setup_.scene.objects.size(), true);
  const GLuint program = surfaceBoxProgram_.id();
  glBindTextureUnit(0, surfaces.id());
  glProgramUniform1i(program, 2, setup_.scene.samples);
  glDepthFunc(GL_GREATER);
  std::vector<bool> passed = boxesPass(candidates, time, Side::farSide, program);
  glDepthFunc(GL_LESS);
  return passed;
}

std::vector<bool> OcclusionCulling::boxesPass(const std::vector<std::size_t>& candidates,
                                              float time, Side side, GLuint program) const {
  std::vector<bool> passed(setup_.scene.objects.size(), false);
  if (candidates.empty()) return passed;
  glUseProgram(program);
  glBindVertexArray(noAttributes_.id());
  const GLboolean cullFace = glIsEnabled(GL_CULL_FACE);
  GLboolean depthWrites = GL_TRUE;
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depthWrites);
  GLint cullFaceMode = GL_BACK, frontFace = GL_CCW;
  glGetIntegerv(GL_CULL_FACE_MODE, &cullFaceMode);
  glGetIntegerv(GL_FRONT_FACE, &frontFace);
  glDepthMask(GL_FALSE);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  // The eye is outside every box tested: the front faces, and the back faces, each cover
  // every sample the box does.
  glEnable(GL_CULL_FACE);
  glCullFace(side == Side::nearSide ? GL_BACK : GL_FRONT);
  glFrontFace(GL_CCW);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(0.0f, side == Side::nearSide ? -kDepthUnits : kDepthUnits);
  std::vector<std::size_t> tested;
  for (const std::size_t i : candidates) {
    const Bounds local = setup_.meshes.mesh(i).bounds();
    if (local.empty()) continue;  // nothing to draw
    Bounds box = local.transformed(setup_.scene.objects[i].transformAt(time));
    // Half a pixel where the box is farthest (its margin is more pixels everywhere nearer), so
    // rasterisation's snapping cannot put one of the object's samples outside the box.
    const float grow =
        std::max(1e-4f * glm::length(box.max - box.min), 0.5f * worldPixel(box, uniforms_));
    box.min -= glm::vec3(grow);
    box.max += glm::vec3(grow);
    if (viewDepthRange(box, uniforms_.view).first <= near_ + 1e-3f * std::abs(near_)) {
      passed[i] = true;  // cut by the near plane, or around the eye
      continue;
    }
    if (tested.size() == queries_.size())
      queries_.push_back(gl::Query::create(GL_ANY_SAMPLES_PASSED));
    glBeginQuery(GL_ANY_SAMPLES_PASSED, queries_[tested.size()].id());
    glProgramUniform3fv(program, 0, 1, &box.min[0]);
    glProgramUniform3fv(program, 1, 1, &box.max[0]);
    glDrawArrays(GL_TRIANGLES, 0, 36);
    glEndQuery(GL_ANY_SAMPLES_PASSED);
    tested.push_back(i);
  }
  for (std::size_t k = 0; k < tested.size(); ++k) {
    GLuint samples = 0;
    glGetQueryObjectuiv(queries_[k].id(), GL_QUERY_RESULT, &samples);
    passed[tested[k]] = samples != 0;
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
  if (!cullFace) glDisable(GL_CULL_FACE);
  glCullFace(GLenum(cullFaceMode));
  glFrontFace(GLenum(frontFace));
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(depthWrites);
  return passed;
}

void OcclusionCulling::addPass(Frame& frame, const std::string& name, Target objectIds) {
  frame.addPass(
      {.name = name,
       .reads = {objectIds},
       .run =
           [this, &frame, objectIds](const PassContext& pass) {
             const GLuint none = 0, program = markProgram_.id();
             glClearNamedBufferData(visible_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT,
                                    &none);
             glUseProgram(program);
             glBindTextureUnit(0, frame.texture(objectIds).id());
             glProgramUniform1i(program, 0, setup_.scene.samples);
             glBindBufferBase(GL_SHADER_STORAGE_BUFFER,
                              setup_.bindings.storageBlock("VISIBLE_OBJECTS"), visible_.id());
             glDispatchCompute(GLuint((pass.width + markGroup_[0] - 1) / markGroup_[0]),
                               GLuint((pass.height + markGroup_[1] - 1) / markGroup_[1]), 1);
             marked_ = true;
           },
       .compute = true});
}

}  // namespace cutaway
