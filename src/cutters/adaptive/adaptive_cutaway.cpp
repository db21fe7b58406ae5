#include "cutters/adaptive/adaptive_cutaway.hpp"

#include "frame/fullscreen.hpp"

namespace cutaway {

CutterType adaptiveCutterType() {
  return {.key = "adaptive",
          .title = "Adaptive cutaway (Burns08/11)",
          .glsl = "cutters/adaptive/clip.glsl",
          .name = "adaptive",
          .schema = &adaptiveCutawaySchema(),
          // C(p) is a window depth (clip.glsl), whose float steps near 1 (2⁻²⁴) span about
          // 6e-8 · far / near of the far distance: deeper, the cut surface turns to rings
          // (measured: faint at 1e4, broken at 4e4). Derived planes stay below ~2100.
          .deepestDepthRange = 1e4f,
          .create = [](FrameSetup& setup) -> std::unique_ptr<Cutter> {
            return std::make_unique<AdaptiveCutaway>(setup);
          }};
}

struct AdaptiveCutaway::Programs {
  gl::Program seed, ghost, atPixel;
  FullscreenTriangle fullscreen;
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
  if (options().contextual) {
    transition_ = std::make_unique<CutawaySurfacePasses>(surface_, "C2", [this] {
      return glm::radians(options().contextual ? options().contextual->transitionAngle : 0.0f);
    });
    transitionDepthUnit_ = setup.bindings.textureUnit("CUTAWAY_DEPTH_C2");
    transitionDilatedUnit_ = setup.bindings.textureUnit("CUTAWAY_DILATED_C2");
    contextualLocation_ = setup.bindings.uniformLocation("ADAPTIVE_CONTEXTUAL");
    importanceLocation_ = setup.bindings.uniformLocation("ADAPTIVE_IMPORTANCE");
    graded_ = options().contextual->apply != ContextualCutawayOptions::Application::Cut;
    if (graded_) applyLocation_ = setup.bindings.uniformLocation("ADAPTIVE_APPLY");
    // Per pixel of the visible surface of a cut object (channels 0 and 1 of clip.glsl).
    setup.gbuffer.addChannel({.name = "occlusion",
                              .meaning = "Burns11 eq. 5.6's occlusion Ω of the visible surface "
                                         "in the contextual cutaway structure, in [0, 1] (0 "
                                         "base region, 1 clear); NaN where no object the "
                                         "adaptive cutter cuts is visible; sample 0"});
    setup.gbuffer.addChannel({.name = "reduction",
                              .meaning = "occlusion reduction R of the visible surface (Burns11 "
                                         "eqs. 7.1–7.3 from its importance, or R = Ω), in [0, 1]; "
                                         "visible surfaces have R < 0.5 (R ≥ 0.5 is removed); "
                                         "NaN as for occlusion; sample 0"});
  }
  // C and its dilation (x, y), then C₂'s (z, w) or the simple structure's cut-surface normal.
  atPixel_ = frame.declare("cutawayAtPixel", {.format = GL_RGBA32F});
  atPixelUnit_ = setup.bindings.textureUnit("CUTAWAY_AT_PIXEL");
  const int n = surface_.bufferSize();
  seedDepthTest_ =
      frame.declare("seedDepthTest", {.format = GL_DEPTH_COMPONENT32F, .width = n, .height = n});
  if (options().ghostLines) {
    const int samples = setup.scene.samples;
    ghostNormal_ = frame.declare("ghostNormal", {.format = GL_R32UI, .samples = samples});
    ghostObjectId_ = frame.declare("ghostObjectId", {.format = GL_RG32I, .samples = samples});
    ghostDepth_ = frame.declare("ghostDepth", {.format = GL_DEPTH_COMPONENT32F, .samples = samples});
    ghostCulling_ = std::make_unique<OcclusionCulling>(setup);
  }
  Programs& p = *programs_;
  p.seed = gl::buildProgram({.stages = {{GL_VERTEX_SHADER, "frame/mesh.vert"},
                                        {GL_FRAGMENT_SHADER, "cutters/adaptive/seed.frag"}}});
  p.atPixel =
      setup.bindings.build({.stages = {{GL_VERTEX_SHADER, "frame/fullscreen.vert"},
                                       {GL_FRAGMENT_SHADER, "cutters/adaptive/at_pixel.frag"}}});
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

bool AdaptiveCutaway::cutsVolume(std::size_t index) const {
  const SceneVolume& v = setup_.scene.volumes[index];
  return v.role != Role::Interest && v.mayBeCutBy(AdaptiveCutawayOptions::kKey);
}

CutLook AdaptiveCutaway::look(std::size_t index) const {
  const SceneObject& o = setup_.scene.objects[index];
  using CutSurfaces = AdaptiveCutawayOptions::CutSurfaces;
  const AdaptiveCutawayOptions& a = options();
  return {.cutSurface = a.cutSurfaces == CutSurfaces::All ||
                        a.cutSurfaces == CutSurfaces::Unmarked ||
                        (a.cutSurfaces == CutSurfaces::Watertight && o.mesh->report.watertight),
          .cutColor = a.cutSurfaceColor.value_or(o.material.color * 0.8f),
          .marksOpenMeshes = !graded_,  // graded: no cut surfaces (clip.glsl)
          .skipsMarks = a.cutSurfaces == CutSurfaces::Unmarked};
}

std::optional<glm::vec3> AdaptiveCutaway::cutOutlineColor() const {
  if (!options().outlines) return std::nullopt;
  return options().outlineColor;
}

std::optional<GhostBuffers> AdaptiveCutaway::ghosts() const {
  if (!ghostNormal_.valid()) return std::nullopt;
  return GhostBuffers{ghostNormal_, ghostObjectId_, [this] {
                        return options().ghostLines ? options().ghostLines->opacity : 0.0f;
                      }};
}

void AdaptiveCutaway::describeAovs(std::vector<Aov>& aovs) const {
  surface_.describeAovs(aovs);
  if (transition_) transition_->describeAovs(aovs);
}

std::vector<std::pair<std::string, std::string>> AdaptiveCutaway::facts() const {
  return {{"computePath", surface_.onCpu() ? "cpu" : "gpu"}};
}

void AdaptiveCutaway::beginFrame(const FrameState& state) {
  const CutawayProjection camera = cutawayProjection(state.camera, state.aspect);
  surface_.setCamera(camera);
  if (transition_) transition_->setCamera(camera);
  if (ghostCulling_) ghostCulling_->beginFrame(state);
  time_ = state.time, uniforms_ = state.uniforms;
  reaches_.clear();
}

// On the CPU path of the simple structure, where C is in memory: an object whose box C leaves
// as it is (cutawayKeepsBox) draws without the cutter's code.
void AdaptiveCutaway::findReaches() {
  const Scene& scene = setup_.scene;
  reaches_.assign(scene.objects.size(), true);
  if (surface_.greatest().empty()) return;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const Bounds& local = setup_.meshes.mesh(i).bounds();
    if (local.empty() || !cuts(i)) continue;
    reaches_[i] = !cutawayKeepsBox(shadedBox(scene, local, i, time_, uniforms_),
                                   uniforms_.viewProjection, surface_.greatest());
  }
}

std::vector<Target> AdaptiveCutaway::geometryInputs() const {
  std::vector<Target> inputs{surface_.cutawayDepth(), surface_.cutawayDilated(), atPixel_};
  if (transition_)
    inputs.insert(inputs.end(), {transition_->cutawayDepth(), transition_->cutawayDilated()});
  return inputs;
}

void AdaptiveCutaway::bindSurfaces() const {
  glBindTextureUnit(depthUnit_, setup_.frame.texture(surface_.cutawayDepth()).id());
  glBindTextureUnit(dilatedUnit_, setup_.frame.texture(surface_.cutawayDilated()).id());
  if (!transition_) return;
  glBindTextureUnit(transitionDepthUnit_, setup_.frame.texture(transition_->cutawayDepth()).id());
  glBindTextureUnit(transitionDilatedUnit_,
                    setup_.frame.texture(transition_->cutawayDilated()).id());
}

void AdaptiveCutaway::bindForGeometry() const {
  bindSurfaces();
  glBindTextureUnit(atPixelUnit_, setup_.frame.texture(atPixel_).id());
}

int AdaptiveCutaway::translucentLayers() const {
  if (!graded_) return 0;
  return options().contextual ? options().contextual->layers : 1;
}

bool AdaptiveCutaway::reductionIsOcclusion() const {
  using Reduction = ContextualCutawayOptions::Reduction;
  const Reduction r = options().contextual->reduction;
  if (r != Reduction::Auto) return r == Reduction::Occlusion;
  std::optional<float> first;
  for (std::size_t i = 0; i < setup_.scene.objects.size(); ++i) {
    if (setup_.scene.objects[i].proxy || !cuts(i)) continue;
    const float importance = setup_.scene.objects[i].importance;
    if (first && *first != importance) return false;
    first = importance;
  }
  // A volume's materials carry importances of their own (its transfer function's).
  for (std::size_t i = 0; i < setup_.scene.volumes.size(); ++i) {
    if (!cutsVolume(i)) continue;
    for (const TransferFunction::Row& row : setup_.scene.volumes[i].transfer.rows)
      for (const TransferPoint& p : row.points) {
        if (first && *first != p.importance) return false;
        first = p.importance;
      }
  }
  return true;
}

void AdaptiveCutaway::setProgramUniforms(GLuint program) const {
  if (!transition_ || !options().contextual) return;
  const ContextualCutawayOptions& c = *options().contextual;
  // d unset: 5% of the scene's radius, as the ghost lines' distance.
  const float d = c.overlay.value_or(0.05f * setup_.sceneBounds.radius());
  // θ₂ below θ₁ (possible only when set live) is taken as θ₁: no transition region.
  const bool transition = c.transitionAngle > options().angle;
  glProgramUniform3f(program, contextualLocation_, d, transitionOverlayOcclusion(transition, d > 0.0f),
                     reductionIsOcclusion() ? 1.0f : 0.0f);
  // clip.glsl's uApply.x: 0 translucency, 1 edge highlights, 2 lines.
  // Only where the program uses it (the ghost and cap programs do not): a write to an
  // inactive location is an error.
  using Application = ContextualCutawayOptions::Application;
  if (graded_ && glGetUniformLocation(program, "uApply") == applyLocation_)
    glProgramUniform2f(program, applyLocation_,
                       c.apply == Application::EdgeHighlights ? 1.0f
                       : c.apply == Application::Lines        ? 2.0f
                                                              : 0.0f,
                       c.edgeExponent);
}

void AdaptiveCutaway::setObjectUniforms(GLuint program, std::size_t index) const {
  if (transition_) glProgramUniform1f(program, importanceLocation_, setup_.scene.objects[index].importance);
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
  if (transition_) transition_->addPasses();
  if (surface_.onCpu() && !transition_)
    frame.addPass({.name = "cutawayReaches",
                   .reads = {surface_.cutawayDepth()},
                   .run = [this](const PassContext&) { findReaches(); }});
  std::vector<Target> reads{surface_.cutawayDepth(), surface_.cutawayDilated()};
  if (transition_)
    reads.insert(reads.end(), {transition_->cutawayDepth(), transition_->cutawayDilated()});
  frame.addPass({.name = "cutawayAtPixel",
                 .reads = reads,
                 .writes = {atPixel_},
                 .run = [this](const PassContext&) { drawAtPixel(); }});
}

void AdaptiveCutaway::drawAtPixel() const {
  glDisable(GL_DEPTH_TEST);
  glUseProgram(programs_->atPixel.id());
  bindSurfaces();
  programs_->fullscreen.draw();
}

void AdaptiveCutaway::addPassesAfterGeometry(Frame& frame) {
  if (!ghostNormal_.valid()) return;
  frame.addPass({.name = "ghostGeometry",
                 .reads = geometryInputs(),
                 .writes = {ghostNormal_, ghostObjectId_, ghostDepth_},
                 .run = [this](const PassContext& pass) { drawGhostGeometry(pass.framebuffer); }});
  ghostCulling_->addPass(frame, "visibleGhosts", ghostObjectId_);
}

void AdaptiveCutaway::drawGhostGeometry(GLuint framebuffer) const {
  const float one = 1.0f;
  const GLuint noWeight[4] = {0, 0, 0, 0};
  const GLint noObject[4] = {-1, 0, 0, 0};
  glClearNamedFramebufferuiv(framebuffer, GL_COLOR, 0, noWeight);
  glClearNamedFramebufferiv(framebuffer, GL_COLOR, 1, noObject);
  glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &one);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  // Only front faces take part (ghost.frag): culling the back faces spares llvmpipe their
  // rasterisation and shading.
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  bindForGeometry();
  const GLuint program = programs_->ghost.id();
  const AdaptiveCutawayOptions& o = options();
  // Burns08 §4.3: the fade's distance; 0 means 5% of the scene's radius.
  const float distance = o.ghostLines && o.ghostLines->distance > 0 ? o.ghostLines->distance
                                                                     : 0.05f * setup_.sceneBounds.radius();
  glProgramUniform1f(program, 17, distance);
  setProgramUniforms(program);
  // The objects the last frame showed, then those of the others whose boxes pass
  // (frame/occlusion_culling.hpp).
  const auto ghost = [](const SceneObject& o) { return !o.proxy && o.role != Role::Interest; };
  const auto drawBatch = [&](const OcclusionCulling::Batch& batch) {
    setup_.meshes.draw(
        program, [&](const SceneObject& o, std::size_t i) { return ghost(o) && batch(i); },
        [&](const SceneObject& o, std::size_t i) {
          glProgramUniform1i(program, 11, int(i));
          glProgramUniform1f(program, 12, o.takesLines() ? 1.0f : 0.0f);
          setObjectUniforms(program, i);
        });
  };
  ghostCulling_->draw([&](std::size_t i) { return ghost(setup_.scene.objects[i]); },
                      setup_.meshes.time(), drawBatch);
  glDisable(GL_CULL_FACE);
}

}  // namespace cutaway
