#include "cutaway/render/renderer.hpp"

#include <algorithm>
#include <cmath>

#include "cutaway/core/error.hpp"
#include "cutaway/gl/shader.hpp"
#include "cutters/adaptive/adaptive_cutaway.hpp"
#include "cutters/breakaway/breakaway.hpp"
#include "cutters/clip_surfaces/clip_surfaces.hpp"
#include "cutters/cutout/cutout.hpp"
#include "cutters/terrain_opening/terrain_opening.hpp"
#include "render/fullscreen.hpp"
#include "render/pipes/pipe_renderer.hpp"
#include "render/scene_gpu.hpp"
#include "styles/hatching/tonal_art_map.hpp"
#include "styles/shadows/shadow_map.hpp"
#include "styles/toon/toon_ramp.hpp"

namespace cutaway {

namespace {

// std140 mirror of src/render/frame_uniforms.glsl.
struct FrameUniforms {
  glm::mat4 view, projection, viewProjection, inverseProjection, inverseView;
  glm::vec4 viewport;
  glm::vec4 eye, forward;
  glm::vec4 lightVector[8];
  glm::vec4 lightColor[8];
  glm::ivec4 counts;
  glm::vec4 backgroundTop, backgroundBottom;
  glm::vec4 goochCool, goochWarm;
  glm::vec4 styleParams;
  glm::mat4 shadowMatrix;
  glm::vec4 shadowParams;
  glm::vec4 toonParams, toonHighlight;
  glm::vec4 hatchPaper, hatchInk, hatchParams;
};

const char* styleFile(const std::string& style) {
  if (style == "gooch") return "styles/gooch/gooch.glsl";
  if (style == "blinn-phong") return "styles/blinn_phong/blinn_phong.glsl";
  if (style == "toon") return "styles/toon/toon.glsl";
  if (style == "hatching") return "styles/hatching/hatching.glsl";
  throw Error("style", "", "unknown style \"" + style + "\"");
}

// Mesh uniform locations of src/render/mesh.frag (and ghost.frag for the id).
constexpr GLint kColor = 8, kSpecular = 9, kShininess = 10, kObjectId = 11, kLines = 12,
                kCutBy = 13, kCutSurface = 14, kCutColor = 15, kBackColor = 16, kGhostDistance = 17,
                kClipPlane = 18, kShaftOpening = 52;
// Bits of src/cutters/fate.glsl.
constexpr int kCutByAdaptive = 1, kCutByCutout = 2, kCutByBreakaway = 4, kCutByClipSurfaces = 8,
              kCutByTerrain = 16, kCutByShaftOuter = 32, kCutByShaftInner = 64;

bool isShaft(const SceneObject& o) {
  return o.networkPart == NetworkPart::ShaftOuter || o.networkPart == NetworkPart::ShaftInner;
}

}  // namespace

struct Renderer::Impl {
  explicit Impl(const Scene& scene) : sceneGpu(scene), sceneBounds(scene.bounds()) {}
  SceneGpu sceneGpu;
  // Over the whole animation (SceneObject::worldBounds), so computed once, not per frame.
  Bounds sceneBounds;
  std::unique_ptr<AdaptiveCutaway> adaptive;
  std::unique_ptr<Cutout> cutout;
  std::unique_ptr<Breakaway> breakaway;
  std::unique_ptr<ClipSurfaceCutter> clipSurfaces;
  std::unique_ptr<TerrainOpening> terrain;
  std::unique_ptr<PipeRenderer> pipes;
  gl::Program capProgram, capMaskProgram;
  gl::Buffer frameUniforms;
  FullscreenTriangle fullscreen;
  gl::Program meshProgram, backgroundProgram, linesProgram, ghostProgram, ghostLinesProgram,
      compositeProgram;
  bool lines = false, outlines = false, ghosts = false;
  float ghostDistance = 0;
  gl::Texture toonRamp, tonalArtMap;  // the toon and hatching styles' textures
  std::unique_ptr<ShadowMap> shadowMap;
};

Renderer::Renderer(const Scene& scene, const gl::ContextInfo& info)
    : scene_(scene), impl_(std::make_unique<Impl>(scene)) {
  Impl& g = *impl_;
  frame_ = std::make_unique<Frame>(scene.width, scene.height, info.software);
  Frame& f = *frame_;
  const AdaptiveCutawayOptions* adaptive = scene.adaptive ? &*scene.adaptive : nullptr;
  if (adaptive) g.adaptive = std::make_unique<AdaptiveCutaway>(g.sceneGpu, *adaptive, info, f);
  if (scene.cutout) g.cutout = std::make_unique<Cutout>(scene, *scene.cutout);
  if (scene.breakaway) g.breakaway = std::make_unique<Breakaway>(scene, *scene.breakaway, f);
  if (scene.clipSurfaces)
    g.clipSurfaces = std::make_unique<ClipSurfaceCutter>(g.sceneGpu, *scene.clipSurfaces, f);
  if (scene.terrainOpening)
    g.terrain = std::make_unique<TerrainOpening>(scene, *scene.terrainOpening, f);
  g.lines = scene.style.lines.has_value();
  // Cut outlines: the adaptive cutter's option; the Diepstraten03 cutters outline their walls.
  g.outlines = (adaptive && adaptive->outlines) || g.cutout || g.breakaway;
  g.ghosts = adaptive && adaptive->ghostLines;
  if (g.ghosts)
    g.ghostDistance =
        adaptive->ghostDistance > 0 ? adaptive->ghostDistance : 0.05f * g.sceneBounds.radius();

  g.frameUniforms = gl::Buffer::create(sizeof(FrameUniforms), nullptr, GL_DYNAMIC_STORAGE_BIT);
  // The active cutters' #defines for cutters.glsl.
  std::map<std::string, std::string> cutters;
  for (const auto& [on, define] :
       {std::pair{adaptive != nullptr, "CUTTER_ADAPTIVE"},
        std::pair{bool(g.cutout), "CUTTER_CUTOUT"},
        std::pair{bool(g.breakaway), "CUTTER_BREAKAWAY"},
        std::pair{bool(g.clipSurfaces), "CUTTER_CLIP_SURFACES"},
        std::pair{bool(g.terrain), "CUTTER_TERRAIN"},
        std::pair{std::any_of(scene.objects.begin(), scene.objects.end(), isShaft),
                  "CUTTER_SHAFT_WEDGE"}})
    if (on) cutters.emplace(define, "1");
  g.meshProgram = gl::buildProgram(
      {.stages = {{GL_VERTEX_SHADER, "render/mesh.vert"}, {GL_FRAGMENT_SHADER, "render/mesh.frag"}},
       .defines = cutters,
       .aliases = {{"style.glsl", styleFile(scene.style.name)}}});
  g.backgroundProgram = buildFullscreenProgram("render/background.frag");
  g.compositeProgram = buildFullscreenProgram("render/composite.frag", cutters);
  if (g.clipSurfaces) {
    g.capProgram =
        gl::buildProgram({.stages = {{GL_VERTEX_SHADER, "cutters/clip_surfaces/cap.vert"},
                                     {GL_FRAGMENT_SHADER, "cutters/clip_surfaces/cap.frag"}},
                          .defines = cutters,
                          .aliases = {{"style.glsl", styleFile(scene.style.name)}}});
    g.capMaskProgram = buildFullscreenProgram("cutters/clip_surfaces/cap_mask.frag");
  }
  if (g.lines || g.outlines)
    g.linesProgram = buildFullscreenProgram(
        "styles/lines/lines.frag", g.outlines
                                       ? std::map<std::string, std::string>{{"CUT_OUTLINES", "1"}}
                                       : std::map<std::string, std::string>{});
  if (g.ghosts) {
    g.ghostProgram =
        gl::buildProgram({.stages = {{GL_VERTEX_SHADER, "render/mesh.vert"},
                                     {GL_FRAGMENT_SHADER, "cutters/adaptive/ghost.frag"}}});
    g.ghostLinesProgram = buildFullscreenProgram("styles/lines/lines.frag");
  }

  if (scene.style.name == "toon") g.toonRamp = createToonRampTexture(scene.style.toon);
  if (scene.style.name == "hatching")
    g.tonalArtMap = createTonalArtMapTexture(generateTonalArtMap(
        {.tones = scene.style.hatching.tones, .seed = scene.style.hatching.seed}));
  if (scene.style.shadows.enabled)
    g.shadowMap =
        std::make_unique<ShadowMap>(g.sceneGpu, scene.style.shadows, f, sizeof(FrameUniforms));

  const int samples = scene.samples;
  f.declare("sceneColor", {.format = GL_RGBA8, .samples = samples});
  f.declare("sceneNormal", {.format = GL_RGBA16F, .samples = samples});
  f.declare("scenePosition", {.format = GL_RGBA32F, .samples = samples});
  f.declare("sceneObjectId", {.format = GL_R32I, .samples = samples});
  f.declare("sceneCutMask", {.format = GL_R8, .samples = samples});
  // Konev18 §6's billboard pipes mark the stencil buffer.
  const bool billboards =
      std::any_of(scene.networks.begin(), scene.networks.end(),
                  [](const PipeNetwork& n) { return n.mode == PipeNetwork::Mode::Billboards; });
  f.declare("sceneDepth",
            {.format = billboards ? GLenum(GL_DEPTH32F_STENCIL8) : GLenum(GL_DEPTH_COMPONENT32F),
             .samples = samples});
  if (g.cutout) {
    f.declare("sceneCutoutDistance", {.format = GL_R32F, .samples = samples});
    f.declare("cutoutDistance",
              {.format = GL_R32F,
               .meaning = "signed distance of the visible exterior surface to the cutout wedge, "
                          "perturbed by the jitter (Diepstraten03 §4.5), scene units; > 0 would "
                          "be removed, so visible surfaces are <= 0; NaN where no exterior "
                          "object is visible; sample 0"});
  }
  if (g.lines || g.outlines)
    f.declare("lines", {.format = GL_R16F,
                        .meaning = "feature-line coverage in [0,1] (silhouettes and creases, "
                                   "fraction of MSAA samples on a line)"});
  if (g.outlines)
    f.declare("cutOutlines",
              {.format = GL_R16F,
               .meaning = "cut-outline coverage in [0,1]: boundary of the cut-surface "
                          "mask (Burns08 §4.2), fraction of MSAA samples"});
  if (g.ghosts) {
    f.declare("ghostNormal", {.format = GL_RGBA16F, .samples = samples});
    f.declare("ghostPosition", {.format = GL_RGBA32F, .samples = samples});
    f.declare("ghostObjectId", {.format = GL_R32I, .samples = samples});
    f.declare("ghostDepth", {.format = GL_DEPTH_COMPONENT32F, .samples = samples});
    f.declare("ghostLines", {.format = GL_R16F,
                             .meaning = "ghost-line coverage in [0,1]: feature lines of removed "
                                        "material, faded with distance in front of the cutaway "
                                        "surface (Burns08 §4.3)"});
  }
  f.declare("color", {.format = GL_RGBA8});
  f.declare("normal", {.format = GL_RGBA16F,
                       .meaning = "world-space unit normal of the visible surface, turned towards "
                                  "the viewer (the cutaway surface's on cut surfaces); (0,0,0) on "
                                  "background; sample 0",
                       .aovChannels = 3});
  f.declare("position", {.format = GL_RGBA32F,
                         .meaning = "world-space position of the visible surface, scene units; "
                                    "(0,0,0) on background; sample 0",
                         .aovChannels = 3});
  f.declare("viewDepth", {.format = GL_R32F,
                          .meaning = "linear eye-space depth: distance from the eye along the "
                                     "viewing direction, scene units; 0 on background; sample 0"});
  f.declare("objectId", {.format = GL_R32F,
                         .meaning = "index of the visible object in the scene's object list (as "
                                    "printed by `cutaway info`); -1 on background; sample 0"});
  f.declare("depth", {.format = GL_R32F,
                      .meaning = "window-space depth in [0,1] (OpenGL default depth range, "
                                 "0 = near plane, 1 = far plane and background); sample 0"});
  f.declare("cutMask", {.format = GL_R32F,
                        .meaning = "1 where a cut surface or cut wall is shown (a back face of a "
                                   "solid seen through the cut: Burns08 §4.1, Diepstraten03 "
                                   "rule 5), else 0; sample 0"});

  std::vector<std::string> cutawayInputs;
  if (adaptive) cutawayInputs = {"cutawayDepth", "cutawayDilated"};
  std::vector<std::string> geometryInputs = cutawayInputs;
  if (g.breakaway)
    for (const char* t : {"breakawayClipDepth", "breakawayInnerDepth", "breakawayHullNormal"})
      geometryInputs.push_back(t);
  if (g.shadowMap) geometryInputs.push_back("shadowDepth");
  std::vector<std::string> geometryOutputs{"sceneColor", "sceneNormal", "scenePosition",
                                           "sceneObjectId", "sceneCutMask"};
  if (g.cutout) geometryOutputs.push_back("sceneCutoutDistance");
  geometryOutputs.push_back("sceneDepth");
  f.addPass({.name = "geometry",
             .reads = geometryInputs,
             .writes = geometryOutputs,
             .run = [this](const PassContext& pass) { drawGeometry(pass.framebuffer); }});
  if (billboards) {
    geometryOutputs.pop_back();  // the depth target: the pipe passes add their own
    g.pipes = std::make_unique<PipeRenderer>(scene, f, cutters, styleFile(scene.style.name),
                                             geometryOutputs);
    if (g.shadowMap)
      g.shadowMap->setOtherCasters([pipes = g.pipes.get()] { pipes->drawShadowCasters(); });
  }
  if (g.clipSurfaces) {
    f.declare("capMask", {.format = GL_R32F,
                          .meaning = "1 where a cap surface covers a clip surface's cut (Trapp13 "
                                     "§5), else 0; sample 0"});
    f.addPass({.name = "capMask",
               .reads = {"sceneCutMask"},
               .writes = {"capMask"},
               .run = [this](const PassContext&) {
                 glDisable(GL_DEPTH_TEST);
                 glUseProgram(impl_->capMaskProgram.id());
                 glBindTextureUnit(0, frame_->texture("sceneCutMask").id());
                 impl_->fullscreen.draw();
               }});
  }
  if (g.ghosts) {
    f.addPass({.name = "ghostGeometry",
               .reads = cutawayInputs,
               .writes = {"ghostNormal", "ghostPosition", "ghostObjectId", "ghostDepth"},
               .run = [this](const PassContext& pass) {
                 const Impl& g = *impl_;
                 const float zero[4] = {0, 0, 0, 0}, one = 1.0f;
                 const GLint noObject[4] = {-1, 0, 0, 0};
                 glClearNamedFramebufferfv(pass.framebuffer, GL_COLOR, 0, zero);
                 glClearNamedFramebufferfv(pass.framebuffer, GL_COLOR, 1, zero);
                 glClearNamedFramebufferiv(pass.framebuffer, GL_COLOR, 2, noObject);
                 glClearNamedFramebufferfv(pass.framebuffer, GL_DEPTH, 0, &one);
                 glEnable(GL_DEPTH_TEST);
                 glDepthFunc(GL_LESS);
                 glDepthMask(GL_TRUE);
                 g.adaptive->bindForClipping();
                 const GLuint program = g.ghostProgram.id();
                 glProgramUniform1f(program, kGhostDistance, g.ghostDistance);
                 g.sceneGpu.draw(
                     program,
                     [](const SceneObject& o) { return !o.proxy && o.role != Role::Interest; },
                     [&](const SceneObject&, std::size_t i) {
                       glProgramUniform1i(program, kObjectId, int(i));
                     });
               }});
  }
  if (g.lines || g.outlines) {
    std::vector<std::string> reads{"sceneNormal", "scenePosition", "sceneObjectId"};
    std::vector<std::string> writes{"lines"};
    if (g.outlines) reads.push_back("sceneCutMask"), writes.push_back("cutOutlines");
    f.addPass(
        {.name = "lines", .reads = reads, .writes = writes, .run = [this](const PassContext&) {
           drawLines(impl_->linesProgram.id(), "scene", scene_.style.lines.has_value());
         }});
  }
  if (g.ghosts)
    f.addPass({.name = "ghostLines",
               .reads = {"ghostNormal", "ghostPosition", "ghostObjectId"},
               .writes = {"ghostLines"},
               .run = [this](const PassContext&) {
                 drawLines(impl_->ghostLinesProgram.id(), "ghost", true);
               }});
  std::vector<std::string> compositeReads{"sceneColor",    "sceneNormal", "scenePosition",
                                          "sceneObjectId", "sceneDepth",  "sceneCutMask"};
  for (const char* optional : {"lines", "cutOutlines", "ghostLines", "sceneCutoutDistance"})
    if (f.has(optional)) compositeReads.push_back(optional);
  std::vector<std::string> compositeWrites{"color",    "normal", "position", "viewDepth",
                                           "objectId", "depth",  "cutMask"};
  if (g.cutout) compositeWrites.push_back("cutoutDistance");
  f.addPass({.name = "composite",
             .reads = compositeReads,
             .writes = compositeWrites,
             .run = [this](const PassContext&) { composite(); }});
}

Renderer::~Renderer() = default;

const char* Renderer::cutawayComputePath() const {
  return impl_->adaptive ? impl_->adaptive->computePath() : nullptr;
}

void Renderer::drawGeometry(GLuint framebuffer) {
  const Impl& g = *impl_;
  const float zero[4] = {0, 0, 0, 0}, one = 1.0f;
  const GLint noObject[4] = {-1, 0, 0, 0};
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 1, zero);
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 2, zero);
  glClearNamedFramebufferiv(framebuffer, GL_COLOR, 3, noObject);
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 4, zero);
  if (g.cutout) {
    const float nan[4] = {std::nanf(""), 0, 0, 0};
    glClearNamedFramebufferfv(framebuffer, GL_COLOR, 5, nan);
  }
  glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &one);
  // Background gradient into the colour target only.
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  const GLuint attachments = g.cutout ? 6 : 5;
  for (GLuint i = 1; i < attachments; ++i) glColorMaski(i, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glUseProgram(g.backgroundProgram.id());
  g.fullscreen.draw();
  for (GLuint i = 1; i < attachments; ++i) glColorMaski(i, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);

  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  if (g.adaptive) g.adaptive->bindForClipping();
  if (g.cutout) g.cutout->bind();
  if (g.breakaway) g.breakaway->bind();
  if (g.clipSurfaces) g.clipSurfaces->clearMasks(), g.clipSurfaces->bind();
  if (g.terrain) g.terrain->prepare(g.meshProgram.id());
  if (g.shadowMap) g.shadowMap->bindForLookup();
  if (g.toonRamp) glBindTextureUnit(kToonRampUnit, g.toonRamp.id());
  if (g.tonalArtMap) glBindTextureUnit(kTonalArtMapUnit, g.tonalArtMap.id());
  const GLuint program = g.meshProgram.id();
  const AdaptiveCutawayOptions* adaptive = scene_.adaptive ? &*scene_.adaptive : nullptr;
  const bool clipPlanes = g.cutout && scene_.cutout->method == CutoutOptions::Method::ClipPlanes;
  // Diepstraten03's cutters cut only exterior objects (rule 1); their walls and insides take
  // the cutter's colours.
  const std::optional<glm::vec3> wallColor = g.cutout      ? scene_.cutout->wallColor
                                             : g.breakaway ? scene_.breakaway->wallColor
                                                           : std::nullopt;
  const std::optional<glm::vec3> insideColor = g.cutout      ? scene_.cutout->insideColor
                                               : g.breakaway ? scene_.breakaway->insideColor
                                                             : std::nullopt;
  auto setUniforms = [&](const SceneObject& o, std::size_t i) {
    glProgramUniform3fv(program, kColor, 1, &o.material.color[0]);
    glProgramUniform1f(program, kSpecular, o.material.specular);
    glProgramUniform1f(program, kShininess, o.material.shininess);
    glProgramUniform1i(program, kObjectId, int(i));
    const auto lines = o.params.find("lines");
    const bool objectLines = lines == o.params.end() || std::get<bool>(lines->second);
    glProgramUniform1f(program, kLines, objectLines ? 1.0f : 0.0f);
    // Objects of interest are never cut (Burns08 §4.1).
    const bool adaptiveCut = adaptive && o.role != Role::Interest;
    const bool exterior = o.role == Role::Exterior;
    const int cutBy = (adaptiveCut ? kCutByAdaptive : 0) |
                      (g.cutout && exterior && !clipPlanes ? kCutByCutout : 0) |
                      (g.breakaway && exterior ? kCutByBreakaway : 0) |
                      (g.clipSurfaces && o.role != Role::Interest ? kCutByClipSurfaces : 0) |
                      (g.terrain && g.terrain->cuts(i) ? kCutByTerrain : 0);
    glProgramUniform1i(program, kCutBy, cutBy);
    using CutSurfaces = AdaptiveCutawayOptions::CutSurfaces;
    const bool diepstraten = exterior && (g.cutout || g.breakaway);
    if (isShaft(o)) {
      // Konev18 §7: the wedge's cut surface in the network's colour, the inside in its own.
      const PipeNetwork& net = scene_.networks[std::size_t(o.network)];
      const bool inner = o.networkPart == NetworkPart::ShaftInner;
      glProgramUniform1i(program, kCutBy, cutBy | (inner ? kCutByShaftInner : kCutByShaftOuter));
      glProgramUniform1i(program, kCutSurface, 1);
      glProgramUniform3fv(program, kCutColor, 1, &net.cutColor[0]);
      glProgramUniform3fv(program, kBackColor, 1, &net.insideColor[0]);
      glProgramUniform1f(program, kShaftOpening, net.shaftOpening);
      return;
    }
    const bool cutSurface =
        (adaptiveCut &&
         (adaptive->cutSurfaces == CutSurfaces::All ||
          (adaptive->cutSurfaces == CutSurfaces::Watertight && o.mesh->report.watertight))) ||
        (diepstraten && o.solid()) || (g.terrain && g.terrain->cuts(i));
    glProgramUniform1i(program, kCutSurface, cutSurface);
    const glm::vec3 cutColor = g.terrain && g.terrain->cuts(i)
                                   ? scene_.terrainOpening->thicknessColor.value_or(kSoilColor)
                               : diepstraten ? wallColor.value_or(kDefaultWallColor)
                               : adaptive && adaptive->cutSurfaceColor ? *adaptive->cutSurfaceColor
                                                                       : o.material.color * 0.8f;
    glProgramUniform3fv(program, kCutColor, 1, &cutColor[0]);
    const glm::vec3 backColor =
        diepstraten ? insideColor.value_or(o.material.color * 0.55f) : o.material.color;
    glProgramUniform3fv(program, kBackColor, 1, &backColor[0]);
    if (g.cutout) g.cutout->setUniforms(program, i);
  };
  // Secondary objects first, clipped; then the objects of interest, whole (Burns08 §4.1).
  g.sceneGpu.draw(
      program,
      [&](const SceneObject& o) {
        return !o.proxy && o.role != Role::Interest && !(clipPlanes && o.role == Role::Exterior);
      },
      setUniforms);
  if (clipPlanes) {
    // Diepstraten03 §4.3: the exterior drawn once per plane, each time keeping the far side
    // of that plane (n·x + w <= 0); the union of the passes is everything outside the wedge.
    glEnable(GL_CLIP_DISTANCE0);
    for (int k = 0; k < kMaxCutoutPlanes; ++k)
      g.sceneGpu.draw(
          program, [&](const SceneObject& o) { return !o.proxy && o.role == Role::Exterior; },
          [&](const SceneObject& o, std::size_t i) {
            setUniforms(o, i);
            const CutoutWedge* w = g.cutout->wedgeOf(i);
            // A wedge with fewer planes clips this pass away entirely.
            const glm::vec4 keep = w && k < int(w->planes.size()) ? -w->planes[std::size_t(k)]
                                                                  : glm::vec4(0, 0, 0, -1);
            glProgramUniform4fv(program, kClipPlane, 1, &keep[0]);
          });
    glDisable(GL_CLIP_DISTANCE0);
  }
  g.sceneGpu.draw(
      program, [](const SceneObject& o) { return !o.proxy && o.role == Role::Interest; },
      setUniforms);
  // Trapp13 §5: the caps close the clipped solids.
  if (g.clipSurfaces) g.clipSurfaces->drawCaps(g.capProgram.id(), g.sceneGpu.time());
}

void Renderer::drawLines(GLuint program, const std::string& buffer, bool featureLines) {
  static const LineStyle kDefault;
  const LineStyle& l = scene_.style.lines ? *scene_.style.lines : kDefault;
  glDisable(GL_DEPTH_TEST);
  glUseProgram(program);
  glBindTextureUnit(0, frame_->texture(buffer + "Normal").id());
  glBindTextureUnit(1, frame_->texture(buffer + "Position").id());
  glBindTextureUnit(2, frame_->texture(buffer + "ObjectId").id());
  if (frame_->has(buffer + "CutMask"))
    glBindTextureUnit(3, frame_->texture(buffer + "CutMask").id());
  glProgramUniform1i(program, 0, scene_.samples);
  glProgramUniform1i(program, 1, std::max(1, int(std::lround(l.width))));
  glProgramUniform1f(program, 2, std::cos(glm::radians(l.creaseAngle)));
  glProgramUniform1f(program, 3, l.depthThreshold);
  glProgramUniform1i(program, 4, featureLines && l.silhouettes);
  glProgramUniform1i(program, 5, featureLines && l.creases);
  impl_->fullscreen.draw();
}

void Renderer::composite() {
  const Impl& g = *impl_;
  const GLuint program = g.compositeProgram.id();
  glDisable(GL_DEPTH_TEST);
  glUseProgram(program);
  const char* inputs[] = {
      "sceneColor", "sceneNormal", "scenePosition", "sceneObjectId", "sceneDepth",
      "lines",      "cutOutlines", "ghostLines",    "sceneCutMask",  "sceneCutoutDistance"};
  for (GLuint unit = 0; unit < 10; ++unit)
    if (frame_->has(inputs[unit])) glBindTextureUnit(unit, frame_->texture(inputs[unit]).id());
  glProgramUniform1i(program, 0, scene_.samples);
  glProgramUniform1i(program, 1, g.lines || g.outlines);
  const glm::vec3 lineColor = scene_.style.lines ? scene_.style.lines->color : glm::vec3(0.0f);
  glProgramUniform3fv(program, 2, 1, &lineColor[0]);
  glProgramUniform1i(program, 3, g.outlines);
  const glm::vec3 outlineColor = scene_.adaptive ? scene_.adaptive->outlineColor : glm::vec3(0.0f);
  glProgramUniform3fv(program, 4, 1, &outlineColor[0]);
  glProgramUniform1i(program, 5, g.ghosts);
  glProgramUniform1f(program, 6, scene_.adaptive ? scene_.adaptive->ghostOpacity : 0.0f);
  g.fullscreen.draw();
}

void Renderer::render(const Camera& camera, float time) {
  impl_->sceneGpu.setTime(time);
  const float aspect = float(scene_.width) / float(scene_.height);
  FrameUniforms u{};
  u.view = camera.view();
  u.projection = camera.projectionMatrix(aspect);
  u.viewProjection = u.projection * u.view;
  u.inverseProjection = glm::inverse(u.projection);
  u.inverseView = glm::inverse(u.view);
  u.viewport = glm::vec4(scene_.width, scene_.height, 1.0f / scene_.width, 1.0f / scene_.height);
  u.eye = glm::vec4(camera.eye, 1.0f);
  u.forward = glm::vec4(glm::normalize(camera.target - camera.eye), 0.0f);
  int count = 0;
  for (const auto& light : scene_.lights) {
    const bool point = light.type == Light::Type::Point;
    glm::vec4 v = point ? glm::vec4(light.position, 1.0f) : glm::vec4(light.direction, 0.0f);
    if (light.cameraSpace) v = u.inverseView * v;
    u.lightVector[count] = v;
    u.lightColor[count] = glm::vec4(light.color * light.intensity, 1.0f);
    ++count;
  }
  u.counts = glm::ivec4(count, camera.projection == Projection::Orthographic ? 1 : 0, 0, 0);
  u.backgroundTop = glm::vec4(scene_.backgroundTop, 1.0f);
  u.backgroundBottom = glm::vec4(scene_.backgroundBottom, 1.0f);
  u.goochCool = glm::vec4(scene_.style.gooch.cool, scene_.style.gooch.alpha);
  u.goochWarm = glm::vec4(scene_.style.gooch.warm, scene_.style.gooch.beta);
  u.styleParams = glm::vec4(scene_.style.blinnPhong.ambient, 0, 0, 0);
  const float sceneRadius = std::max(impl_->sceneBounds.radius(), 1e-6f);
  const ToonStyle& toon = scene_.style.toon;
  u.toonParams = glm::vec4(float(toon.ramp.size()), toon.highlightThreshold,
                           toon.highlight ? 1.0f : 0.0f, 0.0f);
  u.toonHighlight = glm::vec4(toon.highlightColor, 1.0f);
  const HatchingStyle& hatching = scene_.style.hatching;
  u.hatchPaper = glm::vec4(hatching.paper, hatching.tint);
  u.hatchInk = glm::vec4(hatching.ink, float(hatching.tones));
  u.hatchParams =
      glm::vec4(1.0f / (hatching.scale * sceneRadius),
                hatching.lightness == HatchingStyle::Lightness::Gooch ? 1.0f : 0.0f, 0, 0);
  if (impl_->shadowMap) {
    // The light sees the scene's bounds over the whole animation, so the map does not
    // change resolution from frame to frame.
    const bool keyLight = count > 0;
    impl_->shadowMap->setActive(keyLight);
    if (keyLight) {
      const ShadowStyle& shadows = scene_.style.shadows;
      const LightFrustum light = keyLightFrustum(u.lightVector[0], impl_->sceneBounds);
      u.shadowMatrix = shadowMatrix(light);
      u.shadowParams = glm::vec4(1.0f, shadows.bias * sceneRadius, float(shadows.pcfRadius),
                                 1.0f / float(shadows.size));
      FrameUniforms fromLight = u;
      fromLight.view = light.view;
      fromLight.projection = light.projection;
      fromLight.viewProjection = light.projection * light.view;
      fromLight.inverseProjection = glm::inverse(light.projection);
      fromLight.inverseView = glm::inverse(light.view);
      fromLight.counts.y = light.orthographic ? 1 : 0;
      // The light as the eye, for casters that face it (billboard pipes).
      fromLight.eye = glm::vec4(glm::vec3(fromLight.inverseView[3]), 1.0f);
      fromLight.forward = glm::vec4(-glm::vec3(fromLight.inverseView[2]), 0.0f);
      glNamedBufferSubData(impl_->shadowMap->lightUniforms(), 0, sizeof fromLight, &fromLight);
    }
  }
  glNamedBufferSubData(impl_->frameUniforms.id(), 0, sizeof u, &u);
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, impl_->frameUniforms.id());
  if (impl_->adaptive) impl_->adaptive->setCamera(camera, aspect);
  if (impl_->cutout) impl_->cutout->setCamera(camera);
  frame_->execute();
}

GLuint Renderer::colorTexture() const {
  return frame_->texture("color").id();
}

Rgba8Image Renderer::readColor() const {
  Rgba8Image image(frame_->width(), frame_->height());
  glGetTextureImage(colorTexture(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(image.pixels.size()),
                    image.pixels.data());
  image.flipVertically();
  return image;
}

std::vector<Aov> Renderer::readAovs() const {
  std::vector<Aov> aovs;
  // Image stores (clip mask, cap parity) must land before the read-back.
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  for (const auto& name : frame_->aovNames()) {
    const TargetDesc& d = frame_->desc(name);
    const int channels = d.aovChannels ? d.aovChannels : 1;
    FloatImage image(d.width, d.height, channels);
    image.data = frame_->read(name, channels);
    image.flipVertically();
    aovs.push_back({name, d.meaning, std::move(image)});
  }
  for (auto& aov : extraAovs()) aovs.push_back(std::move(aov));
  return aovs;
}

std::vector<Aov> Renderer::extraAovs() const {
  std::vector<Aov> aovs;
  if (impl_->clipSurfaces) aovs = impl_->clipSurfaces->spriteAovs();
  if (impl_->terrain) aovs.push_back(impl_->terrain->fieldAov());
  return aovs;
}

}  // namespace cutaway
