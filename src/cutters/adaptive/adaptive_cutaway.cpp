#include "cutters/adaptive/adaptive_cutaway.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include "frame/fullscreen.hpp"

namespace cutaway {

CutterType adaptiveCutterType() {
  return {.key = "adaptive",
          .title = "Adaptive cutaway (Burns08/11)",
          .glsl = "cutters/adaptive/clip.glsl",
          .name = "adaptive",
          .schema = &adaptiveCutawaySchema(),
          .create = [](FrameSetup& setup) -> std::unique_ptr<Cutter> {
            return std::make_unique<AdaptiveCutaway>(setup);
          }};
}

struct AdaptiveCutaway::Programs {
  gl::Program seed, anchors, jfaInit, jumpFlooding, cutawayDepth, dilate, ghost;
  FullscreenTriangle fullscreen;
};

AdaptiveCutaway::AdaptiveCutaway(FrameSetup& setup)
    : setup_(setup),
      bufferSize_(options().bufferSize),
      variant_(options().variant),
      cpu_(cutawayOnCpu(options(), setup.context.software)),
      depthUnit_(setup.bindings.textureUnit("CUTAWAY_DEPTH")),
      dilatedUnit_(setup.bindings.textureUnit("CUTAWAY_DILATED")),
      programs_(std::make_unique<Programs>()) {
  Frame& frame = setup.frame;
  const int n = bufferSize_;
  const std::string size = " (" + std::to_string(n) + "x" + std::to_string(n) + " cutaway buffer)";
  seedDepth_ = frame.declare("seedDepth",
                             {.format = GL_R32F,
                              .width = n,
                              .height = n,
                              .meaning = "window depth in [0,1] of the region of interest's rear "
                                         "hull (greater-than depth test); 0 = near plane, no "
                                         "seed" +
                                         size});
  seedAngle_ = frame.declare(
      "seedAngle", {.format = GL_R32F,
                    .width = n,
                    .height = n,
                    .meaning = "local cutaway angle θ of the seeding object, radians" + size});
  seedDepthTest_ =
      frame.declare("seedDepthTest", {.format = GL_DEPTH_COMPONENT32F, .width = n, .height = n});
  cutawayDepth_ = frame.declare("cutawayDepth",
                                {.format = GL_R32F,
                                 .width = n,
                                 .height = n,
                                 .meaning = "cutaway surface C(p) as window depth in [0,1] (0 = "
                                            "near plane: nothing cut); fragments nearer than it "
                                            "are removed" +
                                            size});
  cutawayDilated_ = frame.declare("cutawayDilated",
                                  {.format = GL_R32F,
                                   .width = n,
                                   .height = n,
                                   .meaning = "1-pixel minimum of cutawayDepth, window depth, "
                                              "used for back faces" +
                                              size});
  for (const Target t : {cutawayDepth_, cutawayDilated_}) {
    const GLuint id = frame.texture(t).id();
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);  // Burns08 §6: interpolated
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  }
  if (!cpu_) {
    anchorCone_ = frame.declare("anchorCone", {.format = GL_RGBA32F, .width = n, .height = n});
    anchorFloor_ = frame.declare("anchorFloor", {.format = GL_RG32F, .width = n, .height = n});
    anchorsA_ = frame.declare("anchorsA", {.format = GL_R32I, .width = n, .height = n});
    anchorsB_ = frame.declare("anchorsB", {.format = GL_R32I, .width = n, .height = n});
  }
  if (options().ghostLines) {
    const int samples = setup.scene.samples;
    ghostNormal_ = frame.declare("ghostNormal", {.format = GL_RGBA16F, .samples = samples});
    ghostPosition_ = frame.declare("ghostPosition", {.format = GL_RGBA32F, .samples = samples});
    ghostObjectId_ = frame.declare("ghostObjectId", {.format = GL_R32I, .samples = samples});
    ghostDepth_ = frame.declare("ghostDepth", {.format = GL_DEPTH_COMPONENT32F, .samples = samples});
  }
  Programs& p = *programs_;
  p.seed = gl::buildProgram({.stages = {{GL_VERTEX_SHADER, "frame/mesh.vert"},
                                        {GL_FRAGMENT_SHADER, "cutters/adaptive/seed.frag"}}});
  p.dilate = buildFullscreenProgram("cutters/adaptive/dilate.frag");
  if (options().ghostLines)
    p.ghost = setup.bindings.build({.stages = {{GL_VERTEX_SHADER, "frame/mesh.vert"},
                                               {GL_FRAGMENT_SHADER, "cutters/adaptive/ghost.frag"}}});
  if (!cpu_) {
    p.anchors = buildFullscreenProgram("cutters/adaptive/anchors.frag");
    p.jfaInit = buildFullscreenProgram("cutters/adaptive/jfa_init.frag");
    p.jumpFlooding = buildFullscreenProgram("cutters/adaptive/jump_flooding.frag");
    p.cutawayDepth = buildFullscreenProgram("cutters/adaptive/cutaway_depth.frag");
  }
}

AdaptiveCutaway::~AdaptiveCutaway() = default;

float AdaptiveCutaway::angleOf(const SceneObject* object) const {
  double degrees = options().angle;
  if (object)
    if (const auto it = object->params.find("cutawayAngle"); it != object->params.end())
      degrees = std::get<double>(it->second);
  return glm::radians(float(degrees));
}

bool AdaptiveCutaway::cuts(std::size_t index) const {
  const SceneObject& o = setup_.scene.objects[index];
  return o.role != Role::Interest && o.mayBeCutBy(AdaptiveCutawayOptions::kKey);
}

CutLook AdaptiveCutaway::look(std::size_t index) const {
  const SceneObject& o = setup_.scene.objects[index];
  using CutSurfaces = AdaptiveCutawayOptions::CutSurfaces;
  const AdaptiveCutawayOptions& a = options();
  return {.cutSurface = a.cutSurfaces == CutSurfaces::All ||
                        (a.cutSurfaces == CutSurfaces::Watertight && o.mesh->report.watertight),
          .cutColor = a.cutSurfaceColor.value_or(o.material.color * 0.8f)};
}

std::optional<glm::vec3> AdaptiveCutaway::cutOutlineColor() const {
  if (!options().outlines) return std::nullopt;
  return options().outlineColor;
}

std::optional<GhostBuffers> AdaptiveCutaway::ghosts() const {
  if (!ghostNormal_.valid()) return std::nullopt;
  return GhostBuffers{ghostNormal_, ghostPosition_, ghostObjectId_,
                      [this] { return options().ghostLines ? options().ghostLines->opacity : 0.0f; }};
}

std::vector<std::pair<std::string, std::string>> AdaptiveCutaway::facts() const {
  return {{"computePath", cpu_ ? "cpu" : "gpu"}};
}

void AdaptiveCutaway::beginFrame(const FrameState& state) {
  camera_ = cutawayProjection(state.camera, state.aspect);
}

void AdaptiveCutaway::bindForGeometry() const {
  glBindTextureUnit(depthUnit_, setup_.frame.texture(cutawayDepth_).id());
  glBindTextureUnit(dilatedUnit_, setup_.frame.texture(cutawayDilated_).id());
}

void AdaptiveCutaway::addPreparationPasses(Frame& frame) {
  frame.addPass({.name = "cutawaySeed",
                 .writes = {seedDepth_, seedAngle_, seedDepthTest_},
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
                   // Rear hulls of every object of interest and interest proxy (Burns11
                   // §4.2.2), then of the other kinds' geometry of interest.
                   setup_.meshes.draw(
                       program, [](const SceneObject& o, std::size_t) { return o.role == Role::Interest; },
                       [&](const SceneObject& o, std::size_t) {
                         glProgramUniform1f(program, 16, angleOf(&o));
                       });
                   if (setup_.drawInterestRearHulls)
                     setup_.drawInterestRearHulls({[this](const SceneObject* o) { return angleOf(o); }});
                   glDepthFunc(GL_LESS);
                 }});
  if (cpu_)
    frame.addPass({.name = "cutawayCpu",
                   .reads = {seedDepth_, seedAngle_},
                   .writes = {cutawayDepth_},
                   .run = [this](const PassContext&) { computeOnCpu(); }});
  else
    addGpuPasses(frame);
  frame.addPass({.name = "cutawayDilate",
                 .reads = {cutawayDepth_},
                 .writes = {cutawayDilated_},
                 .run = [this](const PassContext&) {
                   glDisable(GL_DEPTH_TEST);
                   glUseProgram(programs_->dilate.id());
                   glBindTextureUnit(0, setup_.frame.texture(cutawayDepth_).id());
                   programs_->fullscreen.draw();
                 }});
}

void AdaptiveCutaway::addGpuPasses(Frame& frame) {
  auto bindCone = [this](GLuint program) {
    glUseProgram(program);
    glBindTextureUnit(0, setup_.frame.texture(anchorCone_).id());
    glBindTextureUnit(1, setup_.frame.texture(anchorFloor_).id());
    // View-plane units per buffer pixel: Δndc / P00 horizontally, Δndc / P11 vertically.
    const float n = float(bufferSize_);
    glProgramUniform2f(program, 0, 2.0f / n / camera_.projection[0][0],
                       2.0f / n / camera_.projection[1][1]);
    glDisable(GL_DEPTH_TEST);
  };
  frame.addPass({.name = "cutawayAnchors",
                 .reads = {seedDepth_, seedAngle_},
                 .writes = {anchorCone_, anchorFloor_},
                 .run = [this](const PassContext&) {
                   const AdaptiveCutawayOptions& o = options();
                   const GLuint program = programs_->anchors.id();
                   glUseProgram(program);
                   glBindTextureUnit(0, setup_.frame.texture(seedDepth_).id());
                   glBindTextureUnit(1, setup_.frame.texture(seedAngle_).id());
                   const glm::vec3 floor = glm::normalize(camera_.viewRotation * o.floorNormal);
                   glProgramUniform1i(program, 0, o.edgeCompression);
                   glProgramUniform1f(program, 1, o.edgeRegion);
                   glProgramUniform1i(program, 2, o.directionalConstraint);
                   glProgramUniform3fv(program, 3, 1, &floor[0]);
                   glProgramUniform1i(program, 4, o.perspectiveCompensation);
                   glProgramUniform1i(program, 5, camera_.orthographic);
                   glDisable(GL_DEPTH_TEST);
                   programs_->fullscreen.draw();
                 }});
  frame.addPass({.name = "jumpFloodingInit",
                 .reads = {anchorCone_},
                 .writes = {anchorsA_},
                 .run = [this](const PassContext&) {
                   glUseProgram(programs_->jfaInit.id());
                   glBindTextureUnit(0, setup_.frame.texture(anchorCone_).id());
                   glDisable(GL_DEPTH_TEST);
                   programs_->fullscreen.draw();
                 }});
  // One pass per step, ping-ponging the anchor buffers.
  Target current = anchorsA_, next = anchorsB_;
  for (int step : fields::stepSizes(bufferSize_, bufferSize_, variant_)) {
    frame.addPass({.name = "jumpFlooding/" + std::to_string(step),
                   .reads = {anchorCone_, anchorFloor_, current},
                   .writes = {next},
                   .run = [this, bindCone, step, current](const PassContext&) {
                     const GLuint program = programs_->jumpFlooding.id();
                     bindCone(program);
                     glBindTextureUnit(2, setup_.frame.texture(current).id());
                     glProgramUniform1i(program, 1, step);
                     programs_->fullscreen.draw();
                   }});
    std::swap(current, next);
  }
  frame.addPass({.name = "cutawayDepth",
                 .reads = {anchorCone_, anchorFloor_, current},
                 .writes = {cutawayDepth_},
                 .run = [this, bindCone, current](const PassContext&) {
                   bindCone(programs_->cutawayDepth.id());
                   glBindTextureUnit(2, setup_.frame.texture(current).id());
                   programs_->fullscreen.draw();
                 }});
}

// The same computation as the GPU passes: the seed read back, cones from anchorCone()
// (cutaway_function.cpp mirrors anchors.frag), fields::jumpFlooding, and the result uploaded.
void AdaptiveCutaway::computeOnCpu() {
  const int n = bufferSize_;
  const Frame& frame = setup_.frame;
  fields::CutawayField field = fields::jumpFlooding(
      makeSeedImage(frame.read(seedDepth_, 1), frame.read(seedAngle_, 1), n, options(), camera_),
      -1.0f, variant_);
  for (float& z : field.depth) z = z * 0.5f + 0.5f;  // NDC → window depth
  glTextureSubImage2D(frame.texture(cutawayDepth_).id(), 0, 0, 0, n, n, GL_RED, GL_FLOAT,
                      field.depth.data());
}

void AdaptiveCutaway::addPassesAfterGeometry(Frame& frame) {
  if (!ghostNormal_.valid()) return;
  frame.addPass({.name = "ghostGeometry",
                 .reads = {cutawayDepth_, cutawayDilated_},
                 .writes = {ghostNormal_, ghostPosition_, ghostObjectId_, ghostDepth_},
                 .run = [this](const PassContext& pass) { drawGhostGeometry(pass.framebuffer); }});
}

void AdaptiveCutaway::drawGhostGeometry(GLuint framebuffer) const {
  const float zero[4] = {0, 0, 0, 0}, one = 1.0f;
  const GLint noObject[4] = {-1, 0, 0, 0};
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, zero);
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 1, zero);
  glClearNamedFramebufferiv(framebuffer, GL_COLOR, 2, noObject);
  glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &one);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  bindForGeometry();
  const GLuint program = programs_->ghost.id();
  const AdaptiveCutawayOptions& o = options();
  // Burns08 §4.3: the fade's distance; 0 means 5% of the scene's radius.
  const float distance = o.ghostLines && o.ghostLines->distance > 0 ? o.ghostLines->distance
                                                                     : 0.05f * setup_.sceneBounds.radius();
  glProgramUniform1f(program, 17, distance);
  setup_.meshes.draw(
      program,
      [](const SceneObject& o, std::size_t) { return !o.proxy && o.role != Role::Interest; },
      [&](const SceneObject&, std::size_t i) { glProgramUniform1i(program, 11, int(i)); });
}

}  // namespace cutaway
