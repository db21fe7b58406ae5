#include "cutters/adaptive/adaptive_cutaway.hpp"

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
  gl::Program seed, ghost;
};

AdaptiveCutaway::AdaptiveCutaway(FrameSetup& setup)
    : setup_(setup),
      surface_(setup.frame, options().bufferSize, options().variant,
               cutawayOnCpu(options(), setup.context.software),
               [this]() -> const AdaptiveCutawayOptions& { return options(); }),
      depthUnit_(setup.bindings.textureUnit("CUTAWAY_DEPTH")),
      dilatedUnit_(setup.bindings.textureUnit("CUTAWAY_DILATED")),
      programs_(std::make_unique<Programs>()) {
  Frame& frame = setup.frame;
  const int n = surface_.bufferSize();
  seedDepthTest_ =
      frame.declare("seedDepthTest", {.format = GL_DEPTH_COMPONENT32F, .width = n, .height = n});
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
  if (options().ghostLines)
    p.ghost = setup.bindings.build({.stages = {{GL_VERTEX_SHADER, "frame/mesh.vert"},
                                               {GL_FRAGMENT_SHADER, "cutters/adaptive/ghost.frag"}}});
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
  return {{"computePath", surface_.onCpu() ? "cpu" : "gpu"}};
}

void AdaptiveCutaway::beginFrame(const FrameState& state) {
  surface_.setCamera(cutawayProjection(state.camera, state.aspect));
}

void AdaptiveCutaway::bindForGeometry() const {
  glBindTextureUnit(depthUnit_, setup_.frame.texture(surface_.cutawayDepth()).id());
  glBindTextureUnit(dilatedUnit_, setup_.frame.texture(surface_.cutawayDilated()).id());
}

void AdaptiveCutaway::addPreparationPasses(Frame& frame) {
  frame.addPass({.name = "cutawaySeed",
                 .writes = {surface_.seedDepth(), surface_.seedAngle(), seedDepthTest_},
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
  surface_.addPasses();
}

void AdaptiveCutaway::addPassesAfterGeometry(Frame& frame) {
  if (!ghostNormal_.valid()) return;
  frame.addPass({.name = "ghostGeometry",
                 .reads = {surface_.cutawayDepth(), surface_.cutawayDilated()},
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
