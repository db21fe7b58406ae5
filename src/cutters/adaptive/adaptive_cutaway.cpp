#include "cutters/adaptive/adaptive_cutaway.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include "render/fullscreen.hpp"

namespace cutaway {

struct AdaptiveCutaway::Programs {
  gl::Program seed, anchors, jfaInit, jumpFlooding, cutawayDepth, dilate;
  FullscreenTriangle fullscreen;
};

AdaptiveCutaway::AdaptiveCutaway(const SceneGpu& sceneGpu, const AdaptiveCutawayOptions& options,
                                 const gl::ContextInfo& info, Frame& frame)
    : sceneGpu_(sceneGpu),
      options_(options),
      cpu_(cutawayOnCpu(options, info.software)),
      frame_(frame),
      programs_(std::make_unique<Programs>()) {
  Programs& p = *programs_;
  p.seed = gl::buildProgram({.stages = {{GL_VERTEX_SHADER, "render/mesh.vert"},
                                        {GL_FRAGMENT_SHADER, "cutters/adaptive/seed.frag"}}});
  p.dilate = buildFullscreenProgram("cutters/adaptive/dilate.frag");
  const int n = options.bufferSize;
  const std::string size = " (" + std::to_string(n) + "x" + std::to_string(n) + " cutaway buffer)";
  frame.declare("seedDepth",
                {.format = GL_R32F,
                 .width = n,
                 .height = n,
                 .meaning = "window depth in [0,1] of the region of interest's rear hull "
                            "(greater-than depth test); 0 = near plane, no seed" +
                            size});
  frame.declare("seedAngle",
                {.format = GL_R32F,
                 .width = n,
                 .height = n,
                 .meaning = "local cutaway angle θ of the seeding object, radians" + size});
  frame.declare("seedDepthTest", {.format = GL_DEPTH_COMPONENT32F, .width = n, .height = n});
  frame.declare("cutawayDepth",
                {.format = GL_R32F,
                 .width = n,
                 .height = n,
                 .meaning = "cutaway surface C(p) as window depth in [0,1] (0 = near "
                            "plane: nothing cut); fragments nearer than it are "
                            "removed" +
                            size});
  frame.declare("cutawayDilated", {.format = GL_R32F,
                                   .width = n,
                                   .height = n,
                                   .meaning = "1-pixel minimum of cutawayDepth, window depth, used "
                                              "for back faces" +
                                              size});
  for (const char* name : {"cutawayDepth", "cutawayDilated"}) {
    const GLuint id = frame.texture(name).id();
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);  // Burns08 §6: interpolated
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  }

  frame.addPass({.name = "cutawaySeed",
                 .writes = {"seedDepth", "seedAngle", "seedDepthTest"},
                 .run = [this](const PassContext& pass) {
                   const float zero[4] = {0, 0, 0, 0};
                   glClearNamedFramebufferfv(pass.framebuffer, GL_COLOR, 0, zero);
                   glClearNamedFramebufferfv(pass.framebuffer, GL_COLOR, 1, zero);
                   glClearNamedFramebufferfv(pass.framebuffer, GL_DEPTH, 0, zero);
                   glEnable(GL_DEPTH_TEST);
                   glDepthFunc(GL_GREATER);  // rear hulls (Burns08 §5.1)
                   glDepthMask(GL_TRUE);
                   glDisable(GL_CULL_FACE);
                   const GLuint program = programs_->seed.id();
                   sceneGpu_.draw(program, seedsCutaway, [&](const SceneObject& o, std::size_t) {
                     glProgramUniform1f(program, 16, angleOf(o));
                   });
                   glDepthFunc(GL_LESS);
                 }});
  if (cpu_)
    addCpuPass();
  else
    addGpuPasses();
  frame.addPass({.name = "cutawayDilate",
                 .reads = {"cutawayDepth"},
                 .writes = {"cutawayDilated"},
                 .run = [this](const PassContext&) {
                   glDisable(GL_DEPTH_TEST);
                   glUseProgram(programs_->dilate.id());
                   glBindTextureUnit(0, frame_.texture("cutawayDepth").id());
                   programs_->fullscreen.draw();
                 }});
}

AdaptiveCutaway::~AdaptiveCutaway() = default;

float AdaptiveCutaway::angleOf(const SceneObject& object) const {
  const auto it = object.params.find("cutawayAngle");
  const double degrees = it == object.params.end() ? options_.angle : std::get<double>(it->second);
  return glm::radians(float(degrees));
}

void AdaptiveCutaway::setCamera(const Camera& camera, float aspect) {
  camera_ = cutawayProjection(camera, aspect);
}

void AdaptiveCutaway::bindForClipping() const {
  glBindTextureUnit(8, frame_.texture("cutawayDepth").id());
  glBindTextureUnit(9, frame_.texture("cutawayDilated").id());
}

void AdaptiveCutaway::addGpuPasses() {
  Frame& frame = frame_;
  Programs& p = *programs_;
  p.anchors = buildFullscreenProgram("cutters/adaptive/anchors.frag");
  p.jfaInit = buildFullscreenProgram("cutters/adaptive/jfa_init.frag");
  p.jumpFlooding = buildFullscreenProgram("cutters/adaptive/jump_flooding.frag");
  p.cutawayDepth = buildFullscreenProgram("cutters/adaptive/cutaway_depth.frag");
  const int n = options_.bufferSize;
  frame.declare("anchorCone", {.format = GL_RGBA32F, .width = n, .height = n});
  frame.declare("anchorFloor", {.format = GL_RG32F, .width = n, .height = n});
  frame.declare("anchorsA", {.format = GL_R32I, .width = n, .height = n});
  frame.declare("anchorsB", {.format = GL_R32I, .width = n, .height = n});

  auto bindCone = [this](GLuint program) {
    glUseProgram(program);
    glBindTextureUnit(0, frame_.texture("anchorCone").id());
    glBindTextureUnit(1, frame_.texture("anchorFloor").id());
    // View-plane units per buffer pixel: Δndc / P00 horizontally, Δndc / P11 vertically.
    const float n = float(options_.bufferSize);
    glProgramUniform2f(program, 0, 2.0f / n / camera_.projection[0][0],
                       2.0f / n / camera_.projection[1][1]);
    glDisable(GL_DEPTH_TEST);
  };
  frame.addPass({.name = "cutawayAnchors",
                 .reads = {"seedDepth", "seedAngle"},
                 .writes = {"anchorCone", "anchorFloor"},
                 .run = [this](const PassContext&) {
                   const GLuint program = programs_->anchors.id();
                   glUseProgram(program);
                   glBindTextureUnit(0, frame_.texture("seedDepth").id());
                   glBindTextureUnit(1, frame_.texture("seedAngle").id());
                   const glm::vec3 floor =
                       glm::normalize(camera_.viewRotation * options_.floorNormal);
                   glProgramUniform1i(program, 0, options_.edgeCompression);
                   glProgramUniform1f(program, 1, options_.edgeRegion);
                   glProgramUniform1i(program, 2, options_.directionalConstraint);
                   glProgramUniform3fv(program, 3, 1, &floor[0]);
                   glProgramUniform1i(program, 4, options_.perspectiveCompensation);
                   glProgramUniform1i(program, 5, camera_.orthographic);
                   glDisable(GL_DEPTH_TEST);
                   programs_->fullscreen.draw();
                 }});
  frame.addPass({.name = "jumpFloodingInit",
                 .reads = {"anchorCone"},
                 .writes = {"anchorsA"},
                 .run = [this](const PassContext&) {
                   glUseProgram(programs_->jfaInit.id());
                   glBindTextureUnit(0, frame_.texture("anchorCone").id());
                   glDisable(GL_DEPTH_TEST);
                   programs_->fullscreen.draw();
                 }});
  // One pass per step, ping-ponging the anchor buffers.
  std::string current = "anchorsA", next = "anchorsB";
  for (int step : fields::stepSizes(n, n, options_.variant)) {
    frame.addPass({.name = "jumpFlooding/" + std::to_string(step),
                   .reads = {"anchorCone", "anchorFloor", current},
                   .writes = {next},
                   .run = [this, bindCone, step, current](const PassContext&) {
                     const GLuint program = programs_->jumpFlooding.id();
                     bindCone(program);
                     glBindTextureUnit(2, frame_.texture(current).id());
                     glProgramUniform1i(program, 1, step);
                     programs_->fullscreen.draw();
                   }});
    std::swap(current, next);
  }
  frame.addPass({.name = "cutawayDepth",
                 .reads = {"anchorCone", "anchorFloor", current},
                 .writes = {"cutawayDepth"},
                 .run = [this, bindCone, current](const PassContext&) {
                   bindCone(programs_->cutawayDepth.id());
                   glBindTextureUnit(2, frame_.texture(current).id());
                   programs_->fullscreen.draw();
                 }});
}

void AdaptiveCutaway::addCpuPass() {
  frame_.addPass({.name = "cutawayCpu",
                  .reads = {"seedDepth", "seedAngle"},
                  .writes = {"cutawayDepth"},
                  .run = [this](const PassContext&) { computeOnCpu(); }});
}

// The same computation as the GPU passes: the seed read back, cones from anchorCone()
// (cutaway_function.cpp mirrors anchors.frag), fields::jumpFlooding, and the result uploaded.
void AdaptiveCutaway::computeOnCpu() {
  const int n = options_.bufferSize;
  fields::CutawayField field = fields::jumpFlooding(
      makeSeedImage(frame_.read("seedDepth", 1), frame_.read("seedAngle", 1), n, options_, camera_),
      -1.0f, options_.variant);
  for (float& z : field.depth) z = z * 0.5f + 0.5f;  // NDC → window depth
  glTextureSubImage2D(frame_.texture("cutawayDepth").id(), 0, 0, 0, n, n, GL_RED, GL_FLOAT,
                      field.depth.data());
}

}  // namespace cutaway
