// The composer: a frame from the registered techniques (geometry kinds, cutters, styles), in
// the order buildFrame() lists.
#include "cutaway/render/renderer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cutaway/core/error.hpp"
#include "cutaway/gl/shader.hpp"
#include "cutters/registry.hpp"
#include "frame/bindings.hpp"
#include "frame/frame_setup.hpp"
#include "frame/frame_uniforms.hpp"
#include "frame/gbuffer.hpp"
#include "frame/scene_meshes.hpp"
#include "frame/translucent_layers.hpp"
#include "kinds/meshes/mesh_kind.hpp"
#include "kinds/pipes/pipe_kind.hpp"
#include "kinds/volumes/volume_kind.hpp"
#include "styles/emphasis/emphasis.hpp"
#include "styles/lines/line_pass.hpp"
#include "styles/registry.hpp"
#include "styles/shadows/shadow_map.hpp"

namespace cutaway {

namespace {

// The scene's file, or what stands for it in messages (a scene built in code).
std::string sceneName(const Scene& scene) {
  return scene.file.empty() ? "scene" : scene.file.string();
}

// The device's limits on the frame, said at the scene's keys before any target is made (the
// frame's own checks, the backstop, name only its targets).
const Scene& withinDeviceLimits(const Scene& scene, const gl::ContextInfo& info) {
  int most = 0;  // samples every kind of render target takes
  for (const int m : {info.maxColorSamples, info.maxDepthSamples, info.maxIntegerSamples})
    if (m > 0) most = most == 0 ? m : std::min(most, m);
  if (scene.samples > 1 && most > 0 && scene.samples > most)
    throw Error(sceneName(scene), "/samples",
                std::to_string(scene.samples) + " samples exceed the device's " +
                    std::to_string(most) + " (" + info.renderer + ")");
  if (info.maxTextureSize > 0 && std::max(scene.width, scene.height) > info.maxTextureSize)
    throw Error(sceneName(scene), "/resolution",
                std::to_string(scene.width) + "×" + std::to_string(scene.height) +
                    " exceeds the device's largest image, " + std::to_string(info.maxTextureSize) +
                    " on a side (" + info.renderer + ")");
  return scene;
}

}  // namespace

struct Renderer::Impl {
  Impl(const Scene& scene, const gl::ContextInfo& info)
      : frame(scene.width, scene.height, info), meshes(scene), setup{scene,         info,   frame,
                                                                     bindings,      meshes, gbuffer,
                                                                     scene.bounds()} {}
  void buildFrame();
  void drawGeometry(GLuint framebuffer) const;

  Frame frame;
  Bindings bindings;
  SceneMeshes meshes;
  GBuffer gbuffer;
  FrameSetup setup;
  gl::Buffer frameUniforms;
  std::vector<ActiveCutter> cutters;
  std::vector<std::unique_ptr<GeometryKind>> kinds;
  MeshKind* meshKind = nullptr;         // among the kinds, for its occlusion culling
  const VolumeKind* volumes = nullptr;  // among the kinds, for its line drawing
  std::unique_ptr<ShadingStyle> style;
  std::unique_ptr<ShadowMap> shadowMap;
  std::unique_ptr<Emphasis> emphasis;
  std::unique_ptr<TranslucentLayers> layers;  // when a cutter leaves translucent fragments
  std::unique_ptr<LinePass> lines, ghostLines, layerLines;
  Target linesTarget, outlinesTarget, ghostLinesTarget;
};

Renderer::Renderer(const Scene& scene, const gl::ContextInfo& info) try
    : scene_(scene), impl_(std::make_unique<Impl>(withinDeviceLimits(scene, info), info)) {
  Impl& g = *impl_;
  FrameSetup& setup = g.setup;
  g.frameUniforms = gl::Buffer::create(sizeof(FrameUniforms), nullptr, GL_DYNAMIC_STORAGE_BIT);
  // The techniques, in the order their bindings are allocated: the style, shadows, the
  // cutters (registry order), the kinds.
  const Style& style = scene.style;
  const StyleType* shading = findStyle(style.name);
  if (!shading) throw Error("style", "", "unknown style " + quote(style.name));
  g.style = shading->create(setup);
  // Every geometry program includes the shadow lookup (styles/shadows/shadow_lookup.glsl);
  // its unit's define is there only while shadows are on, and without it the lookup compiles
  // to 1 (a software rasteriser runs branches on uniforms both ways, loops included).
  if (style.shadows.enabled) g.shadowMap = std::make_unique<ShadowMap>(setup);
  g.emphasis = std::make_unique<Emphasis>(setup);
  const auto& types = cutterTypes();
  for (std::size_t slot = 0; slot < types.size(); ++slot) {
    if (!cutterActive(types[slot], scene)) continue;
    const std::size_t channels = g.gbuffer.channels().size();
    ActiveCutter c{int(slot), &types[slot], types[slot].create(setup), {}};
    for (std::size_t k = channels; k < g.gbuffer.channels().size(); ++k)
      c.channels.push_back(int(k));
    g.cutters.push_back(std::move(c));
  }
  auto meshKind = std::make_unique<MeshKind>(setup);
  g.meshKind = meshKind.get();
  g.kinds.push_back(std::move(meshKind));
  if (PipeKind::present(scene)) g.kinds.push_back(std::make_unique<PipeKind>(setup));
  if (VolumeKind::present(scene)) {
    auto volumes = std::make_unique<VolumeKind>(setup);
    g.volumes = volumes.get();
    g.kinds.push_back(std::move(volumes));
  }

  // The G-buffer with the channels the cutters added, then every geometry program's shading.
  const bool stencil = std::any_of(g.kinds.begin(), g.kinds.end(),
                                   [&g](const auto& k) { return k->needsStencil(g.cutters); });
  g.gbuffer.declare(g.frame, scene.samples, stencil);
  // Burns11 ch. 2: material a cutter reduces only partly is peeled into translucent layers.
  setup.translucentLayers =
      std::any_of(g.cutters.begin(), g.cutters.end(),
                  [](const ActiveCutter& c) { return c.cutter->translucentLayers() > 0; });
  if (setup.translucentLayers)
    g.layers = std::make_unique<TranslucentLayers>(g.frame, g.bindings, g.gbuffer, [&g] {
      int most = 0;
      for (const ActiveCutter& c : g.cutters) most = std::max(most, c.cutter->translucentLayers());
      return most;
    });
  setup.shadingAliases = {{"style.glsl", shading->glsl}};
  setup.shadingSources = {{"cutters/composition.glsl", cutterComposition(g.cutters)},
                          {"frame/gbuffer_channels.glsl", g.gbuffer.channelsGlsl()}};
  setup.drawShadowCasters = [&g] {
    for (const auto& k : g.kinds) k->drawShadowCasters();
  };
  setup.drawInterestRearHulls = [&g](const RearHullRequest& request) {
    for (const auto& k : g.kinds) k->drawInterestRearHulls(request);
  };
  setup.bindShading = [&g] {
    g.style->bindForGeometry();
    g.emphasis->bindForGeometry();
    if (g.shadowMap) g.shadowMap->bindForLookup();
  };
  for (ActiveCutter& c : g.cutters) c.cutter->prepareGeometryPrograms();
  for (const auto& k : g.kinds) k->prepare(g.cutters);
  g.buildFrame();
} catch (const Error& e) {
  // The frame's targets outgrow the device (its memory): a matter of the scene's resolution and
  // samples, named at its resolution (so that a --size that set it is blamed).
  if (e.file() != "frame") throw;
  throw Error(sceneName(scene), "/resolution",
              std::to_string(scene.width) + "×" + std::to_string(scene.height) +
                  (scene.samples > 1 ? " at " + std::to_string(scene.samples) + " samples" : "") +
                  ": render target " + e.place() + ": " + e.reason());
}

// One frame's passes, in order. The pass graph of renderer.hpp's header comment.
void Renderer::Impl::buildFrame() {
  const Scene& scene = setup.scene;
  // 1. The cutters' preparation: Burns08 §5's seed, jump flooding and dilation,
  //    Diepstraten03 §5's hull clip depths, Trapp13 §6.3's per-frame depth sprites.
  for (ActiveCutter& c : cutters) c.cutter->addPreparationPasses(frame);
  // 2. The key light's shadow map (styles/shadows).
  if (shadowMap) shadowMap->addPass(frame);
  // 3. Geometry: the background, every kind's geometry with the cutters composed, the cutters'
  //    own geometry (Trapp13's caps), into the multisampled G-buffer.
  std::vector<Target> geometryReads;
  for (const ActiveCutter& c : cutters)
    for (const Target t : c.cutter->geometryInputs()) geometryReads.push_back(t);
  if (shadowMap) geometryReads.push_back(shadowMap->depth());
  frame.addPass({.name = "geometry",
                 .reads = geometryReads,
                 .writes = gbuffer.targets(),
                 .run = [this](const PassContext& pass) { drawGeometry(pass.framebuffer); }});
  // 4. The kinds' passes after it (Konev18 §6's billboard pipes into the same G-buffer), then
  //    the cutters' (Trapp13's cap mask, Burns08 §4.3's ghost geometry).
  for (const auto& k : kinds) k->addPassesAfterGeometry(frame);
  for (ActiveCutter& c : cutters) c.cutter->addPassesAfterGeometry(frame);
  // Burns11 ch. 2: the partly reduced material, peeled front to back, each layer with its
  // feature lines (faded by their opacity, the line weight stored with the normal).
  if (layers) {
    layerLines = std::make_unique<LinePass>(false, scene.samples);
    TranslucentLayers::Lines layersLines{
        .color = [this]() -> std::optional<glm::vec3> {
          if (!setup.scene.style.lines) return std::nullopt;
          return setup.scene.style.lines->color;
        },
        .draw =
            [this](const TranslucentLayers::Layer& layer) {
              layerLines->draw(frame, layer.normal, layer.objectId, std::nullopt,
                               *setup.scene.style.lines, true, true);
            }};
    layers->addLayersPass(frame,
                          {.draw =
                               [this](bool first) {
                                 for (const ActiveCutter& c : cutters) c.cutter->bindForGeometry();
                                 setup.bindShading();
                                 const GeometryDraw draw{meshes.time(), &cutters};
                                 for (const auto& k : kinds)
                                   k->drawTranslucentLayer(cutters, draw, first);
                               },
                           .skipPeeled =
                               [this](Target ids) {
                                 const GeometryDraw draw{meshes.time(), &cutters};
                                 for (const auto& k : kinds) k->skipPeeled(cutters, draw, ids);
                               }},
                          std::move(layersLines));
  }
  // 5. Feature lines and cut outlines over the G-buffer; ghost lines over a cutter's ghosts.
  std::vector<GBuffer::Overlay> overlays;
  std::optional<glm::vec3> outlineColor;
  std::optional<GhostBuffers> ghosts;
  for (const ActiveCutter& c : cutters) {
    if (!outlineColor) outlineColor = c.cutter->cutOutlineColor();
    if (!ghosts) ghosts = c.cutter->ghosts();
  }
  const bool featureLines = scene.style.lines.has_value();
  const auto lineColor = [this] {
    return glm::vec4(setup.scene.style.lines ? setup.scene.style.lines->color : glm::vec3(0.0f),
                     1.0f);
  };
  // Where LinePass skips the pixels with no line (its `skipEmpty`).
  Target linePixels;
  if (ghosts || featureLines || outlineColor)
    linePixels = frame.declare("linePixels", {.format = GL_DEPTH_COMPONENT16});
  if (ghosts) {
    ghostLinesTarget = frame.declare(
        "ghostLines", {.format = GL_R16F,
                       .meaning = "ghost-line coverage in [0,1]: feature lines of removed "
                                  "material, faded with distance in front of the cutaway "
                                  "surface (Burns08 §4.3)"});
    overlays.push_back({ghostLinesTarget, [lineColor, opacity = ghosts->opacity] {
                          return glm::vec4(glm::vec3(lineColor()), opacity());
                        }});
  }
  if (featureLines || outlineColor) {
    lines = std::make_unique<LinePass>(outlineColor.has_value(), scene.samples);
    linesTarget = frame.declare("lines", {.format = GL_R16F,
                                          .meaning = "feature-line coverage in [0,1] (silhouettes "
                                                     "and creases, fraction of MSAA samples on a "
                                                     "line)"});
    std::vector<Target> reads{gbuffer.normal(), gbuffer.objectId()};
    std::vector<Target> writes{linesTarget, linePixels};
    if (outlineColor) {
      outlinesTarget = frame.declare(
          "cutOutlines", {.format = GL_R16F,
                          .meaning = "cut-outline coverage in [0,1]: boundary of the cut-surface "
                                     "mask (Burns08 §4.2), fraction of MSAA samples"});
      reads.push_back(gbuffer.cutMask());
      writes.insert(writes.begin() + 1, outlinesTarget);
    }
    frame.addPass({.name = "lines",
                   .reads = reads,
                   .writes = writes,
                   .run = [this, featureLines, outlines = outlineColor.has_value()](
                              const PassContext&) {
                     static const LineStyle kDefault;
                     const LineStyle& l =
                         setup.scene.style.lines ? *setup.scene.style.lines : kDefault;
                     lines->draw(frame, gbuffer.normal(), gbuffer.objectId(),
                                 outlines ? std::optional(gbuffer.cutMask()) : std::nullopt, l,
                                 featureLines, true);
                   }});
    overlays.push_back({linesTarget, lineColor});
    if (outlineColor)
      overlays.push_back({outlinesTarget, [this] {
                            std::optional<glm::vec3> c;
                            for (const ActiveCutter& a : cutters)
                              if (!c) c = a.cutter->cutOutlineColor();
                            return glm::vec4(c.value_or(glm::vec3(0.0f)), 1.0f);
                          }});
  }
  if (ghosts) {
    ghostLines = std::make_unique<LinePass>(false, scene.samples);
    frame.addPass({.name = "ghostLines",
                   .reads = {ghosts->normal, ghosts->objectId},
                   .writes = {ghostLinesTarget, linePixels},
                   .run = [this, g = *ghosts](const PassContext&) {
                     static const LineStyle kDefault;
                     const LineStyle& l =
                         setup.scene.style.lines ? *setup.scene.style.lines : kDefault;
                     ghostLines->draw(frame, g.normal, g.objectId, std::nullopt, l, true, true);
                   }});
  }
  // 6. The composite: the colour samples resolved, the overlays blended (the AOVs are copied
  //    when read).
  gbuffer.addCompositePass(frame, std::move(overlays), frameUniforms.id());
  // 7. The kinds' passes over the final colour (volumes ray cast up to the opaque depth), then
  //    the translucent layers, lines of what lies behind them included.
  for (const auto& k : kinds) k->addPassesAfterComposite(frame);
  if (layers) layers->addCompositePass(frame, gbuffer.finalColor());
}

void Renderer::Impl::drawGeometry(GLuint framebuffer) const {
  gbuffer.clearWithBackground(framebuffer);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  for (const ActiveCutter& c : cutters) c.cutter->bindForGeometry();
  setup.bindShading();
  const GeometryDraw draw{meshes.time(), &cutters};
  for (const auto& k : kinds) k->drawGeometry(cutters, draw);
  // Trapp13 §5: the caps close the clipped solids.
  for (const ActiveCutter& c : cutters) c.cutter->drawGeometry(draw);
}

Renderer::~Renderer() = default;

const Frame& Renderer::frame() const {
  return impl_->frame;
}

std::vector<PassTiming> Renderer::timings() {
  return impl_->frame.timings();
}

void Renderer::setOcclusionCulling(bool on) {
  impl_->meshKind->culling().setEnabled(on);
  for (ActiveCutter& c : impl_->cutters) c.cutter->setOcclusionCulling(on);
}

std::size_t Renderer::peeledLayerDraws() const {
  return impl_->meshKind->peeledDraws();
}

std::size_t Renderer::culledObjects() const {
  return impl_->meshKind->culling().culled();
}

const char* Renderer::cutawayComputePath() const {
  for (const ActiveCutter& c : impl_->cutters)
    for (const auto& [key, value] : c.cutter->facts())
      if (key == "computePath") return value == "cpu" ? "cpu" : "gpu";
  return nullptr;
}

std::size_t Renderer::meshTriangles() const {
  return impl_->meshes.triangles();
}

float deepestDepthRange(const Scene& scene) {
  float deepest = 0.0f;
  for (const CutterType& type : cutterTypes())
    if (type.deepestDepthRange > 0.0f && cutterActive(type, scene))
      deepest = deepest > 0.0f ? std::min(deepest, type.deepestDepthRange) : type.deepestDepthRange;
  return deepest;
}

void Renderer::render(const Camera& camera, float time) {
  Impl& g = *impl_;
  const float aspect = float(scene_.width) / float(scene_.height);
  if (const std::string why = camera.unresolvable(aspect, deepestDepthRange(scene_)); !why.empty())
    throw Error("", "camera", why);
  g.meshes.setTime(time);
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
    u.lightVector[count] = farLightAsDirectional(v, g.setup.sceneBounds);
    u.lightColor[count] = glm::vec4(light.color * light.intensity, 1.0f);
    ++count;
  }
  u.counts = glm::ivec4(count, camera.projection == Projection::Orthographic ? 1 : 0, 0, 0);
  u.backgroundTop = glm::vec4(scene_.backgroundTop, 1.0f);
  u.backgroundBottom = glm::vec4(scene_.backgroundBottom, 1.0f);
  const float sceneRadius = std::max(g.setup.sceneBounds.radius(), 1e-6f);
  if (g.shadowMap) {
    // The light sees the scene's bounds over the whole animation, so the map does not
    // change resolution from frame to frame.
    const bool keyLight = count > 0;
    g.shadowMap->setActive(keyLight);
    if (keyLight) {
      const ShadowStyle& shadows = scene_.style.shadows;
      const LightFrustum light = keyLightFrustum(u.lightVector[0], g.setup.sceneBounds);
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
      glNamedBufferSubData(g.shadowMap->lightUniforms(), 0, sizeof fromLight, &fromLight);
    }
  }
  g.meshes.selectDetail(u.viewProjection, u.projection, camera.eye, float(scene_.height),
                        scene_.pixelError);
  glNamedBufferSubData(g.frameUniforms.id(), 0, sizeof u, &u);
  glBindBufferBase(GL_UNIFORM_BUFFER, Bindings::kFrameUniformBlock, g.frameUniforms.id());
  const FrameState state{camera, aspect, time, u};
  g.style->beginFrame(state);
  g.emphasis->beginFrame();
  for (ActiveCutter& c : g.cutters) c.cutter->beginFrame(state);
  for (const auto& k : g.kinds) k->beginFrame(state);
  g.frame.execute();
}

VolumeLineDrawing Renderer::volumeLineDrawing() const {
  return impl_->volumes ? impl_->volumes->lineDrawing()
                        : VolumeLineDrawing{scene_.width, scene_.height, {}};
}

GLuint Renderer::colorTexture() const {
  return impl_->frame.texture(impl_->gbuffer.finalColor()).id();
}

Rgba8Image Renderer::readColor() const {
  Rgba8Image image(impl_->frame.width(), impl_->frame.height());
  glGetTextureImage(colorTexture(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(image.pixels.size()),
                    image.pixels.data());
  image.flipVertically();
  return image;
}

std::vector<Aov> Renderer::readAovs() const {
  std::vector<Aov> aovs = readFrameAovs(impl_->frame);
  // Burns11 §3.2: the importance of the object each pixel shows, from the objectId AOV.
  const auto id = std::find_if(aovs.begin(), aovs.end(), [](const Aov& a) { return a.name == "objectId"; });
  if (id != aovs.end()) {
    Aov importance{"importance",
                   "importance I in [0, 1] of the visible object (Burns11 §3.1; objects of "
                   "interest are also of binary high importance, their role); NaN on "
                   "background; sample 0",
                   FloatImage(id->image.width, id->image.height, 1)};
    const auto& objects = impl_->setup.scene.objects;
    for (std::size_t i = 0; i < id->image.data.size(); ++i) {
      const float k = id->image.data[i];
      importance.image.data[i] = k >= 0 && std::size_t(k) < objects.size()
                                     ? objects[std::size_t(k)].importance
                                     : std::numeric_limits<float>::quiet_NaN();
    }
    aovs.push_back(std::move(importance));
  }
  for (auto& aov : extraAovs()) aovs.push_back(std::move(aov));
  for (const ActiveCutter& c : impl_->cutters) c.cutter->describeAovs(aovs);
  return aovs;
}

std::vector<Aov> Renderer::extraAovs() const {
  std::vector<Aov> aovs;
  for (const ActiveCutter& c : impl_->cutters)
    for (Aov& a : c.cutter->extraAovs()) aovs.push_back(std::move(a));
  for (const auto& k : impl_->kinds)
    for (Aov& a : k->extraAovs()) aovs.push_back(std::move(a));
  return aovs;
}

}  // namespace cutaway
