#include "cutters/clip_surfaces/clip_surfaces.hpp"

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

#include "cutaway/core/error.hpp"
#include "cutaway/gl/shader.hpp"
#include "frame/depth_offsets.hpp"
#include "frame/fullscreen.hpp"
#include "frame/samples.hpp"

namespace cutaway {

namespace {

// std140 mirror of the ClipSurfaces block in clip_surfaces.glsl.
struct ClipSurfaceBlock {
  glm::vec4 origin[kMaxClipSurfaces], u[kMaxClipSurfaces], v[kMaxClipSurfaces],
      scale[kMaxClipSurfaces];
  glm::ivec4 count;
  glm::vec4 capStyle;
  glm::vec4 plane[kMaxClipSurfaces], toS[kMaxClipSurfaces], toT[kMaxClipSurfaces];
};

// A cap's grid is drawn as one prism per tile of up to kCapTileTexels² offset-map texels, the
// instances of a unit cube placed by its tile's (x, y) and stretched over the relief's range
// there (cap.vert).
constexpr float kCapTileTexels = 16.0f;
constexpr int kMostCapTiles = 256;  // along a side

struct CapPrism {
  gl::VertexArray vertexArray;
  gl::Buffer vertices, indices;
  GLsizei indexCount = 0;
};

// The unit cube, its faces wound counter-clockwise seen from outside. cap.vert maps (s, t,
// lift) onto U, V, N, a right-handed frame (N = Û × V̂), so the winding holds in the world.
CapPrism makeCapPrism() {
  std::vector<glm::vec3> corners;
  for (int c = 0; c < 8; ++c)
    corners.emplace_back(float(c & 1), float((c >> 1) & 1), float(c >> 2));
  // Per face: the axis it is normal to and its side; corners by their bits.
  std::vector<GLuint> idx;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int a = 1 << ((axis + 1) % 3), b = 1 << ((axis + 2) % 3), base = side << axis;
      // (a, b, normal) is a cyclic turn of (x, y, z): a → b is counter-clockwise seen from +axis.
      const GLuint q[4] = {GLuint(base), GLuint(base + a), GLuint(base + a + b), GLuint(base + b)};
      if (side == 1)
        idx.insert(idx.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
      else
        idx.insert(idx.end(), {q[0], q[2], q[1], q[0], q[3], q[2]});
    }
  CapPrism g;
  g.vertices = gl::Buffer::create(GLsizeiptr(corners.size() * sizeof(glm::vec3)), corners.data());
  g.indices = gl::Buffer::create(GLsizeiptr(idx.size() * sizeof(GLuint)), idx.data());
  g.indexCount = GLsizei(idx.size());
  g.vertexArray = gl::VertexArray::create();
  const GLuint vao = g.vertexArray.id();
  glVertexArrayVertexBuffer(vao, 0, g.vertices.id(), 0, sizeof(glm::vec3));
  glVertexArrayElementBuffer(vao, g.indices.id());
  glEnableVertexArrayAttrib(vao, 0);
  glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao, 0, 0);
  // Attribute 1: the instance's tile and the relief's range over it, from the frame's tile
  // list (binding 1).
  glEnableVertexArrayAttrib(vao, 1);
  glVertexArrayAttribFormat(vao, 1, 4, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao, 1, 1);
  glVertexArrayBindingDivisor(vao, 1, 1);
  return g;
}

}  // namespace

glm::mat4 depthSpriteFrame(const Bounds& box, const glm::mat3& basis, int resolution) {
  // One texel of margin around the box on every side keeps silhouettes off the border.
  const glm::vec3 size = glm::max(box.max - box.min, glm::vec3(1e-6f));
  const glm::vec3 pad = size / float(resolution - 2);
  const glm::vec3 lo = box.min - pad, extent = size + 2.0f * pad;
  // T = S · (Bᵀ x − lo): into the basis, then onto [0,1]³.
  glm::mat4 toBasis(glm::transpose(basis));
  return glm::scale(glm::mat4(1.0f), 1.0f / extent) * glm::translate(glm::mat4(1.0f), -lo) *
         toBasis;
}

gl::Program buildDepthPeelProgram() {
  return gl::buildProgram(
      {.stages = {{GL_VERTEX_SHADER, "cutters/clip_surfaces/depth_peel.vert"},
                  {GL_FRAGMENT_SHADER, "cutters/clip_surfaces/depth_peel.frag"}}});
}

DepthSpriteGpu buildDepthSprite(GLuint peelProgram, const GpuMesh& mesh, const glm::mat4& toTexture,
                                int resolution, bool readBack, int maxLayers) {
  const int n = resolution;
  gl::Texture previous = gl::Texture::create2D(GL_R32F, n, n);
  gl::Texture depth = gl::Texture::create2D(GL_DEPTH_COMPONENT32F, n, n);
  gl::Framebuffer fbo = gl::Framebuffer::create();
  glNamedFramebufferTexture(fbo.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
  gl::Query query = gl::Query::create(GL_ANY_SAMPLES_PASSED);
  const float before = -1.0f, empty = 1.0f;
  glClearTexImage(previous.id(), 0, GL_RED, GL_FLOAT, &before);

  GLint viewport[4];
  glGetIntegerv(GL_VIEWPORT, viewport);
  glViewport(0, 0, n, n);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  glUseProgram(peelProgram);
  glProgramUniformMatrix4fv(peelProgram, 0, 1, GL_FALSE, &toTexture[0][0]);
  std::vector<gl::Texture> layers;
  for (int i = 0; i < maxLayers; ++i) {
    gl::Texture layer = gl::Texture::create2D(GL_R32F, n, n);
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, layer.id(), 0);
    glNamedFramebufferDrawBuffer(fbo.id(), GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, &empty);
    glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &empty);
    glBindTextureUnit(0, previous.id());
    glBeginQuery(GL_ANY_SAMPLES_PASSED, query.id());
    mesh.draw();
    glEndQuery(GL_ANY_SAMPLES_PASSED);
    GLuint any = 0;
    glGetQueryObjectuiv(query.id(), GL_QUERY_RESULT, &any);
    if (!any) break;  // nothing left behind the last layer: that is the depth complexity
    glCopyImageSubData(layer.id(), GL_TEXTURE_2D, 0, 0, 0, 0, previous.id(), GL_TEXTURE_2D, 0, 0, 0,
                       0, n, n, 1);
    layers.push_back(std::move(layer));
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);

  DepthSpriteGpu out;
  VolumetricDepthSprite& s = out.sprite;
  s.toTexture = toTexture;
  s.width = s.height = n;
  s.depthComplexity = int(layers.size());
  out.layers = gl::Texture::create(GL_TEXTURE_2D_ARRAY);
  glTextureStorage3D(out.layers.id(), 1, GL_R32F, n, n, std::max(1, s.depthComplexity));
  glTextureParameteri(out.layers.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(out.layers.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  // The parity test gathers 2×2 texels; at the border it takes the edge's (the CPU mirror's clamp).
  glTextureParameteri(out.layers.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(out.layers.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  if (layers.empty()) glClearTexImage(out.layers.id(), 0, GL_RED, GL_FLOAT, &empty);
  for (int i = 0; i < s.depthComplexity; ++i)
    glCopyImageSubData(layers[std::size_t(i)].id(), GL_TEXTURE_2D, 0, 0, 0, 0, out.layers.id(),
                       GL_TEXTURE_2D_ARRAY, 0, 0, 0, i, n, n, 1);
  if (readBack && s.depthComplexity > 0) {
    s.layers.resize(std::size_t(n) * std::size_t(n) * std::size_t(s.depthComplexity));
    glGetTextureImage(out.layers.id(), 0, GL_RED, GL_FLOAT,
                      GLsizei(s.layers.size() * sizeof(float)), s.layers.data());
  }
  return out;
}

CutterType clipSurfacesCutterType() {
  return {.key = "clipSurfaces",
          .title = "Clip surfaces (Trapp13)",
          .glsl = "cutters/clip_surfaces/clip_fragment.glsl",
          .name = "clipSurfaces",
          .schema = &clipSurfacesSchema(),
          .create = [](FrameSetup& setup) -> std::unique_ptr<Cutter> {
            return std::make_unique<ClipSurfaceCutter>(setup);
          }};
}

struct ClipSurfaceCutter::Gpu {
  gl::Program peel = buildDepthPeelProgram();
  gl::Program cap, capMask, clipMask;
  gl::Framebuffer clipMaskSamples;  // no attachments: the frame's size and samples
  FullscreenTriangle fullscreen;
  gl::Buffer block;
  std::vector<gl::Texture> relief, diffuse;  // diffuse: an empty texture id where none
  std::vector<glm::vec3> reliefScale;        // the S each relief map was derived with
  std::vector<glm::vec2> reliefRange;        // the offset map's least and greatest h
  CapPrism capPrism;
  // Per capped object and surface, the tiles its cap can cover, the relief's range over each
  // (h_min, h_max; where kept), and what they were found for.
  struct TileCache {
    glm::mat4 model;
    glm::vec4 rect;
    glm::ivec2 tiles;
    glm::vec3 origin, u, v, scale;
    std::vector<std::uint8_t> keep;
    std::vector<glm::vec2> range;
  };
  std::vector<TileCache> tileCache;
  gl::Buffer tileList;  // this frame's tiles of every cap, (x, y, h_min, h_max) per instance
  GLsizeiptr tileListBytes = 0;
  std::vector<DepthSpriteGpu> sprites;       // one per capped object
  std::vector<Bounds> capBounds;  // the capped objects' mesh bounds, object space
};

ClipSurfaceCutter::ClipSurfaceCutter(FrameSetup& setup)
    : setup_(setup),
      options_(*setup.scene.cutters.find<ClipSurfaceOptions>()),
      sceneRadius_(setup.scene.bounds().radius()),
      gpu_(std::make_unique<Gpu>()),
      blockBinding_(setup.bindings.uniformBlock("CLIP_SURFACES")),
      reliefUnit_(setup.bindings.textureUnit("CLIP_RELIEF", kMaxClipSurfaces)),
      capReliefUnit_(setup.bindings.textureUnit("CAP_RELIEF")),
      layersUnit_(setup.bindings.textureUnit("CAP_LAYERS")),
      diffuseUnit_(setup.bindings.textureUnit("CAP_DIFFUSE")),
      clipMaskImage_(setup.bindings.imageUnit("CLIP_MASK")),
      parityImage_(setup.bindings.imageUnit("CAP_PARITY")) {
  const ClipSurfaceOptions& options = options_;
  Gpu& g = *gpu_;
  for (std::size_t i = 0; i < options.surfaces.size(); ++i) {
    const ClipSurface& cs = options.surfaces[i];
    const std::string place = "/cutters/clipSurfaces/surfaces/" + std::to_string(i);
    setup.requireTextureFits(place + "/offsetMap", "an offset map", cs.offsetMap.width,
                             cs.offsetMap.height);
    setup.requireTextureFits(place + "/diffuseMap", "a diffuse map", cs.diffuseMap.width,
                             cs.diffuseMap.height);
    // §4.2: normal and occlusion maps derived from the offset map (again when S changes).
    gl::Texture t = gl::Texture::create(GL_TEXTURE_2D);
    glTextureStorage2D(t.id(), 1, GL_RGBA32F, cs.offsetMap.width, cs.offsetMap.height);
    uploadRelief(t.id(), cs);
    g.reliefScale.push_back(cs.scale);
    const auto [low, high] = std::minmax_element(cs.offsetMap.data.begin(), cs.offsetMap.data.end());
    g.reliefRange.push_back(cs.offsetMap.data.empty() ? glm::vec2(0.0f) : glm::vec2(*low, *high));
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GL_REPEAT);
    g.relief.push_back(std::move(t));
    gl::Texture d;
    if (cs.diffuseMap.width > 0) {
      d = gl::Texture::create(GL_TEXTURE_2D);
      glTextureStorage2D(d.id(), 1, GL_RGBA8, cs.diffuseMap.width, cs.diffuseMap.height);
      glTextureSubImage2D(d.id(), 0, 0, 0, cs.diffuseMap.width, cs.diffuseMap.height, GL_RGBA,
                          GL_UNSIGNED_BYTE, cs.diffuseMap.pixels.data());
      glTextureParameteri(d.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTextureParameteri(d.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTextureParameteri(d.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
      glTextureParameteri(d.id(), GL_TEXTURE_WRAP_T, GL_REPEAT);
    }
    g.diffuse.push_back(std::move(d));
  }
  g.capPrism = makeCapPrism();
  g.block = gl::Buffer::create(sizeof(ClipSurfaceBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
  const Scene& scene = setup.scene;

  if (options.caps)
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
      const SceneObject& o = scene.objects[i];
      if (o.proxy || !cuts(i)) continue;
      // Parity is undefined for open meshes (§5): never a wrong cap, no cap at all.
      if (!o.mesh->report.watertight) {
        uncappable_.push_back(i);
        continue;
      }
      capped_.push_back(i);
      g.capBounds.push_back(o.mesh->bounds());
      if (options.parity == ClipSurfaceOptions::Parity::Static)
        g.sprites.push_back(buildDepthSprite(
            g.peel.id(), setup.meshes.mesh(i),
            depthSpriteFrame(g.capBounds.back(), glm::mat3(1.0f), options.depthSpriteResolution),
            options.depthSpriteResolution, true));
    }
  if (options.parity == ClipSurfaceOptions::Parity::PerFrame) g.sprites.resize(capped_.size());

  Frame& frame = setup.frame;
  clipMask_ = frame.declare("clipMask",
                            {.format = GL_R32UI,
                             .meaning = "1 where the clip surfaces clip an object they reach, at "
                                        "any depth, hidden or removed by another cutter too (for a "
                                        "volume, where its ray crosses clipped space inside its "
                                        "box), else 0 (Trapp13 eq. 1)"});
  capParity_ = frame.declare(
      "capParity", {.format = GL_R32UI,
                    .meaning = "volumetric parity test of the cap fragments at this pixel (Trapp13 "
                               "§5.3): 0 none tested (also where no tile of a cap was drawn), 1 "
                               "only outside the solid (discarded), 2 at least one inside (kept)"});
  capMask_ = frame.declare("capMask", {.format = GL_R32F,
                                       .meaning = "1 where a cap surface covers a clip surface's "
                                                  "cut (Trapp13 §5), else 0; sample 0"});
  g.capMask = buildFullscreenProgram("cutters/clip_surfaces/cap_mask.frag",
                                     sampleDefines(setup_.scene.samples));
  g.clipMask = setup.bindings.build(
      {.stages = {{GL_VERTEX_SHADER, "frame/mesh.vert"},
                  {GL_FRAGMENT_SHADER, "cutters/clip_surfaces/clip_mask.frag"}}});
  g.clipMaskSamples = gl::Framebuffer::create();
  const GLuint fb = g.clipMaskSamples.id();
  glNamedFramebufferParameteri(fb, GL_FRAMEBUFFER_DEFAULT_WIDTH, frame.width());
  glNamedFramebufferParameteri(fb, GL_FRAMEBUFFER_DEFAULT_HEIGHT, frame.height());
  glNamedFramebufferParameteri(fb, GL_FRAMEBUFFER_DEFAULT_SAMPLES,
                               setup.scene.samples > 1 ? setup.scene.samples : 0);
}

ClipSurfaceCutter::~ClipSurfaceCutter() = default;

// A surface's relief maps (Trapp13 §4.2: height, its slopes, occlusion) into `texture`.
void ClipSurfaceCutter::uploadRelief(GLuint texture, const ClipSurface& cs) {
  const FloatImage relief = deriveReliefMaps(cs);
  glTextureSubImage2D(texture, 0, 0, 0, relief.width, relief.height, GL_RGBA, GL_FLOAT,
                      relief.data.data());
}

// The block of clip_surfaces.glsl from the options as they are now: the surfaces' placement,
// switches and the cap style are live.
void ClipSurfaceCutter::beginFrame(const FrameState& state) {
  const ClipSurfaceOptions& options = live();
  const Scene& scene = setup_.scene;
  reaches_.assign(scene.objects.size(), true);
  slabs_.assign(scene.objects.size(), std::nullopt);
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const Bounds& local = setup_.meshes.mesh(i).bounds();
    if (local.empty() || !cuts(i)) continue;
    const Bounds box = shadedBox(scene, local, i, state.time, state.uniforms);
    reaches_[i] = !clipSurfacesKeepBox(options, gpu_->reliefRange, box);
    if (!reaches_[i]) continue;
    if (const auto s = clipSurfacesSlab(options, gpu_->reliefRange, box))
      slabs_[i] = Slab{
          .kept = {s->kept}, .removed = s->removed, .overlap = worldPixel(box, state.uniforms)};
  }
  ClipSurfaceBlock block{};
  for (std::size_t i = 0; i < options.surfaces.size(); ++i) {
    const ClipSurface& cs = options.surfaces[i];
    // The height S_z is live: the relief's normals and occlusion follow it.
    if (cs.scale != gpu_->reliefScale[i]) {
      uploadRelief(gpu_->relief[i].id(), cs);
      gpu_->reliefScale[i] = cs.scale;
    }
    block.origin[i] = glm::vec4(cs.origin, cs.enabled ? 1.0f : 0.0f);
    block.u[i] = glm::vec4(cs.u, 0.0f);
    block.v[i] = glm::vec4(cs.v, 0.0f);
    // Eq. 1's plane, and eq. 2 as (P − O)·Û S_x / |U| (Û ⊥ N: P_N − O and P − O project alike).
    const glm::vec3 n = cs.normal();
    block.plane[i] = glm::vec4(n, glm::dot(n, cs.origin));
    const glm::dvec3 u(cs.u), v(cs.v);
    block.toS[i] = glm::vec4(glm::vec3(u / glm::dot(u, u) * double(cs.scale.x)), 0.0f);
    block.toT[i] = glm::vec4(glm::vec3(v / glm::dot(v, v) * double(cs.scale.y)), 0.0f);
    const glm::vec2 h = gpu_->reliefRange[i];
    block.scale[i] = glm::vec4(cs.scale, std::max(h.x * cs.scale.z, h.y * cs.scale.z));
  }
  const CapStyle& style = options.capStyle;
  block.count = glm::ivec4(int(options.surfaces.size()),
                           options.combine == ClipSurfaceOptions::Combine::Intersection,
                           style.normalMap, 0);
  block.capStyle = glm::vec4(style.occlusion, style.solidTexture,
                             style.solidTextureScale / std::max(sceneRadius_, 1e-6f), 0.0f);
  glNamedBufferSubData(gpu_->block.id(), 0, sizeof block, &block);
}

void ClipSurfaceCutter::prepareGeometryPrograms() {
  gpu_->cap = gl::buildProgram(
      setup_.geometryProgram({{GL_VERTEX_SHADER, "cutters/clip_surfaces/cap.vert"},
                              {GL_FRAGMENT_SHADER, "cutters/clip_surfaces/cap.frag"}}));
}

void ClipSurfaceCutter::addPreparationPasses(Frame& frame) {
  if (options_.parity == ClipSurfaceOptions::Parity::PerFrame && !capped_.empty())
    frame.addPass({.name = "clipSurfaceSprites", .writes = {}, .run = [this](const PassContext&) {
                     buildPerFrameSprites(setup_.meshes.time());
                   }});
}

bool ClipSurfaceCutter::cuts(std::size_t index) const {
  const SceneObject& o = setup_.scene.objects[index];
  return o.role != Role::Interest && o.mayBeCutBy(ClipSurfaceOptions::kKey);
}

bool ClipSurfaceCutter::cutsVolume(std::size_t index) const {
  const SceneVolume& v = setup_.scene.volumes[index];
  return v.role != Role::Interest && v.mayBeCutBy(ClipSurfaceOptions::kKey);
}

CutLook ClipSurfaceCutter::look(std::size_t index) const {
  // Its cuts are covered by caps, never shown as cut surfaces.
  return {.cutSurface = false, .cutColor = setup_.scene.objects[index].material.color};
}

void ClipSurfaceCutter::buildPerFrameSprites(float time) {
  // Trapp13 §6.3: peeled along the first clip surface's normal, in world space, every frame,
  // so moving and deforming solids keep exact caps.
  const ClipSurface& cs = options_.surfaces.front();
  const glm::mat3 basis(glm::normalize(cs.u), glm::normalize(cs.v), cs.normal());
  const Scene& scene = setup_.scene;
  for (std::size_t k = 0; k < capped_.size(); ++k) {
    const SceneObject& o = scene.objects[capped_[k]];
    const glm::mat4 model = o.transformAt(time);
    Bounds inBasis;
    const Bounds& b = gpu_->capBounds[k];
    for (int c = 0; c < 8; ++c) {
      const glm::vec3 corner((c & 1) ? b.max.x : b.min.x, (c & 2) ? b.max.y : b.min.y,
                             (c & 4) ? b.max.z : b.min.z);
      inBasis.extend(glm::transpose(basis) * glm::vec3(model * glm::vec4(corner, 1.0f)));
    }
    const glm::mat4 worldToTexture =
        depthSpriteFrame(inBasis, basis, options_.depthSpriteResolution);
    gpu_->sprites[k] =
        buildDepthSprite(gpu_->peel.id(), setup_.meshes.mesh(capped_[k]), worldToTexture * model,
                         options_.depthSpriteResolution, false);
    gpu_->sprites[k].sprite.toTexture = worldToTexture * model;
  }
}

void ClipSurfaceCutter::bindForMask() const {
  glBindBufferBase(GL_UNIFORM_BUFFER, blockBinding_, gpu_->block.id());
  for (std::size_t i = 0; i < gpu_->relief.size(); ++i)
    glBindTextureUnit(GLuint(reliefUnit_ + i), gpu_->relief[i].id());
  glBindImageTexture(clipMaskImage_, setup_.frame.texture(clipMask_).id(), 0, GL_FALSE, 0,
                     GL_READ_WRITE, GL_R32UI);
}

void ClipSurfaceCutter::bindForGeometry() const {
  const GLuint zero = 0;
  const Frame& frame = setup_.frame;
  glClearTexImage(frame.texture(clipMask_).id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  glClearTexImage(frame.texture(capParity_).id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  bindForMask();
  glBindImageTexture(parityImage_, frame.texture(capParity_).id(), 0, GL_FALSE, 0, GL_READ_WRITE,
                     GL_R32UI);
}

void ClipSurfaceCutter::drawGeometry(const GeometryDraw& draw) const {
  // Locations of cap.vert / cap.frag.
  constexpr GLint kObjectId = 11, kCutBy = 13, kImportance = 16, kCapSurface = 40,
                  kCapToTexture = 41, kDepthComplexity = 45, kCapColor = 46, kCapRect = 48,
                  kHasDiffuse = 49, kCapTiles = 50, kDepthUnits = 51;
  const Scene& scene = setup_.scene;
  const ClipSurfaceOptions& options = live();
  const float time = draw.time;
  // Each cap's grid: the part of the surface its object's box spans, in tiles, and the tiles
  // that can hold its cap (capTiles, worked out again only when the object, the surface or
  // the grid moved), gathered into one instance buffer.
  struct CapDraw {
    std::size_t k, surface;
    glm::vec4 rect;
    glm::ivec2 tiles;
    GLuint first = 0, count = 0;
  };
  std::vector<CapDraw> draws;
  std::vector<glm::vec4> tileList;
  Gpu& g = *gpu_;
  g.tileCache.resize(capped_.size() * std::size_t(kMaxClipSurfaces));
  for (std::size_t k = 0; k < capped_.size(); ++k) {
    const SceneObject& o = scene.objects[capped_[k]];
    const glm::mat4 model = o.transformAt(time);
    const Bounds& b = g.capBounds[k];
    for (std::size_t i = 0; i < options.surfaces.size(); ++i) {
      const ClipSurface& cs = options.surfaces[i];
      if (!cs.enabled) continue;
      // Only the part of the surface the object's box spans, and only if the box straddles
      // the displaced surface (which lies within S_z behind the plane).
      const glm::vec3 n = cs.normal(), u = glm::normalize(cs.u), v = glm::normalize(cs.v);
      glm::vec2 lo(1e30f), hi(-1e30f);
      float nearest = 1e30f, farthest = -1e30f;
      for (int c = 0; c < 8; ++c) {
        const glm::vec3 corner((c & 1) ? b.max.x : b.min.x, (c & 2) ? b.max.y : b.min.y,
                               (c & 4) ? b.max.z : b.min.z);
        const glm::vec3 d = glm::vec3(model * glm::vec4(corner, 1.0f)) - cs.origin;
        const glm::vec2 st(glm::dot(d, u) / glm::length(cs.u), glm::dot(d, v) / glm::length(cs.v));
        lo = glm::min(lo, st), hi = glm::max(hi, st);
        nearest = std::min(nearest, glm::dot(d, n)), farthest = std::max(farthest, glm::dot(d, n));
      }
      if (nearest > 0.0f || farthest < -cs.scale.z) continue;
      lo = glm::clamp(lo, 0.0f, 1.0f), hi = glm::clamp(hi, 0.0f, 1.0f);
      if (hi.x <= lo.x || hi.y <= lo.y) continue;
      // §5.1's grid, refined to the offset map's texels: tiles of up to kCapTileTexels texels
      // along each side (at most kMostCapTiles), a long thin rectangle in long thin tiles.
      const auto tilesAlong = [](float texels) {
        return std::clamp(int(std::ceil(texels / kCapTileTexels)), 1, kMostCapTiles);
      };
      CapDraw d{k, i, glm::vec4(lo, hi),
                glm::ivec2(tilesAlong((hi.x - lo.x) * float(cs.offsetMap.width) * cs.scale.x),
                           tilesAlong((hi.y - lo.y) * float(cs.offsetMap.height) * cs.scale.y))};
      Gpu::TileCache& cache = g.tileCache[k * std::size_t(kMaxClipSurfaces) + i];
      if (cache.keep.empty() || cache.model != model || cache.rect != d.rect ||
          cache.tiles != d.tiles || cache.origin != cs.origin || cache.u != cs.u ||
          cache.v != cs.v || cache.scale != cs.scale) {
        // A root the GPU finds in a tile next to the one a triangle's rectangle ends in, by
        // rounding, still has its prism.
        const float margin = 1e-4f * (glm::length(cs.u) + glm::length(cs.v));
        cache = {model,    d.rect,
                 d.tiles,  cs.origin,
                 cs.u,     cs.v,
                 cs.scale, capTiles(*o.mesh, model, cs, g.reliefRange[i], d.rect, d.tiles, margin),
                 {}};
        cache.range.resize(cache.keep.size());
        const glm::vec2 texture(cs.scale.x, cs.scale.y), size = hi - lo;
        for (int y = 0; y < d.tiles.y; ++y)
          for (int x = 0; x < d.tiles.x; ++x) {
            const std::size_t t = std::size_t(y) * std::size_t(d.tiles.x) + std::size_t(x);
            const glm::vec2 from = lo + size * glm::vec2(x, y) / glm::vec2(d.tiles),
                            to = lo + size * glm::vec2(x + 1, y + 1) / glm::vec2(d.tiles);
            if (cache.keep[t])
              cache.range[t] = reliefRangeOver(cs.offsetMap, from * texture, to * texture);
          }
      }
      d.first = GLuint(tileList.size());
      for (int y = 0; y < d.tiles.y; ++y)
        for (int x = 0; x < d.tiles.x; ++x) {
          const std::size_t t = std::size_t(y) * std::size_t(d.tiles.x) + std::size_t(x);
          if (cache.keep[t]) tileList.emplace_back(float(x), float(y), cache.range[t]);
        }
      d.count = GLuint(tileList.size()) - d.first;
      if (d.count > 0) draws.push_back(d);
    }
  }
  if (draws.empty()) return;
  const GLsizeiptr bytes = GLsizeiptr(tileList.size() * sizeof(glm::vec4));
  if (g.tileListBytes < bytes) {
    g.tileList = gl::Buffer::create(bytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
    g.tileListBytes = bytes;
    glVertexArrayVertexBuffer(g.capPrism.vertexArray.id(), 1, g.tileList.id(), 0,
                              sizeof(glm::vec4));
  }
  glNamedBufferSubData(g.tileList.id(), 0, bytes, tileList.data());

  const GLuint program = g.cap.id();
  const std::vector<ActiveCutter>& cutters = *draw.cutters;
  int ownSlot = -1;
  for (const ActiveCutter& c : cutters) {
    if (c.cutter.get() == this) ownSlot = c.slot;
    c.cutter->setProgramUniforms(program);
  }
  glUseProgram(program);
  // A solid modelled inside another without a cavity (a part in a housing, an organ in a
  // body) has its cap in the plane of the outer one's, which covers it too: the inner cap
  // wins that tie, nearer by kNestedCapUnits of depth resolution per box it lies in (of equal
  // boxes, the one listed later counts as inside), at most kMostNestedCaps boxes deep.
  std::vector<Bounds> boxes;
  for (const std::size_t index : capped_)
    boxes.push_back(g.capBounds[boxes.size()].transformed(scene.objects[index].transformAt(time)));
  const auto nesting = [&](std::size_t k) {
    int depth = 0;
    for (std::size_t j = 0; j < boxes.size(); ++j)
      if (j != k && glm::all(glm::lessThanEqual(boxes[j].min, boxes[k].min)) &&
          glm::all(glm::greaterThanEqual(boxes[j].max, boxes[k].max)) &&
          (j < k || boxes[j].min != boxes[k].min || boxes[j].max != boxes[k].max))
        ++depth;
    return std::min(depth, kMostNestedCaps);
  };
  // Each view ray through a prism crosses one of its back faces, where the cap's fragment
  // looks for the relief along the ray (cap.frag); the eye may be inside the prism.
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT);
  // Nor may the far plane clip a back face whose prism holds a cap point in front of it (the
  // fragment writes that point's depth).
  glEnable(GL_DEPTH_CLAMP);
  glBindVertexArray(g.capPrism.vertexArray.id());
  std::size_t object = capped_.size();
  for (const CapDraw& d : draws) {
    const std::size_t k = d.k;
    const SceneObject& o = scene.objects[capped_[k]];
    if (k != object) {
      object = k;
      glProgramUniform1f(program, kDepthUnits, -kNestedCapUnits * float(nesting(k)));
      setCutUniforms(program, {kCutBy}, cutters, objectCut(cutters, capped_[k], ownSlot),
                     capped_[k], glm::vec3(0.0f));
      const DepthSpriteGpu& sprite = g.sprites[k];
      // Sprites map the object's own space to LDI space: world → object → LDI.
      const glm::mat4 toTexture = sprite.sprite.toTexture * glm::inverse(o.transformAt(time));
      glProgramUniform1i(program, kObjectId, int(capped_[k]));
      glProgramUniformMatrix4fv(program, kCapToTexture, 1, GL_FALSE, &toTexture[0][0]);
      glProgramUniform1i(program, kDepthComplexity, sprite.sprite.depthComplexity);
      glBindTextureUnit(layersUnit_, sprite.layers.id());
      glProgramUniform1f(program, kImportance,
                         emphasisImportance(o.role == Role::Interest, o.importance));
    }
    const ClipSurface& cs = options.surfaces[d.surface];
    glProgramUniform1i(program, kCapSurface, GLint(d.surface));
    glBindTextureUnit(capReliefUnit_, g.relief[d.surface].id());
    glProgramUniform2i(program, kCapTiles, d.tiles.x, d.tiles.y);
    const glm::vec3 capColor = cs.capColor.value_or(o.material.color * 0.7f);
    glProgramUniform3fv(program, kCapColor, 1, &capColor[0]);
    glProgramUniform4fv(program, kCapRect, 1, &d.rect[0]);
    const GLuint diffuse = g.diffuse[d.surface].id();
    glProgramUniform1i(program, kHasDiffuse, diffuse != 0);
    if (diffuse) glBindTextureUnit(diffuseUnit_, diffuse);
    glDrawElementsInstancedBaseInstance(GL_TRIANGLES, g.capPrism.indexCount, GL_UNSIGNED_INT,
                                        nullptr, GLsizei(d.count), d.first);
  }
  glCullFace(GL_BACK);
  glDisable(GL_CULL_FACE);
  glDisable(GL_DEPTH_CLAMP);
}

void ClipSurfaceCutter::addPassesAfterGeometry(Frame& frame) {
  // Rasterised as the geometry pass is (its samples, a fragment at each pixel's centre), so
  // that the mask marks the pixels whose clipped fragments that pass would have discarded.
  frame.addPass({.name = "clipMask",
                 .writes = {clipMask_},
                 .run =
                     [this](const PassContext& pass) {
                       glBindFramebuffer(GL_FRAMEBUFFER, gpu_->clipMaskSamples.id());
                       glViewport(0, 0, pass.width, pass.height);
                       glDisable(GL_DEPTH_TEST);
                       glDisable(GL_CULL_FACE);
                       bindForMask();
                       setup_.meshes.draw(
                           gpu_->clipMask.id(),
                           [this](const SceneObject& o, std::size_t i) {
                             return !o.proxy && cuts(i) && reaches(i);
                           },
                           [](const SceneObject&, std::size_t) {});
                       glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                                       GL_TEXTURE_FETCH_BARRIER_BIT |
                                       GL_TEXTURE_UPDATE_BARRIER_BIT);
                     },
                 .onRead = true});
  frame.addPass({.name = "capMask",
                 .reads = {setup_.gbuffer.cutMask()},
                 .writes = {capMask_},
                 .run = [this](const PassContext&) {
                   glDisable(GL_DEPTH_TEST);
                   glUseProgram(gpu_->capMask.id());
                   glBindTextureUnit(0, setup_.frame.texture(setup_.gbuffer.cutMask()).id());
                   gpu_->fullscreen.draw();
                 }});
}

std::vector<Aov> ClipSurfaceCutter::extraAovs() const {
  std::vector<Aov> aovs;
  const Scene& scene = setup_.scene;
  const ClipSurfaceOptions& options = live();
  for (std::size_t k = 0; k < options.surfaces.size(); ++k) {
    const ClipSurface& cs = options.surfaces[k];
    FloatImage map = cs.offsetMap;
    map.flipVertically();  // held with t = 0 first; AOVs run top to bottom
    aovs.push_back(
        {"offsetMap_" + std::to_string(k),
         "offset map OM of clip surface " + std::to_string(k) +
             " (Trapp13 §4.1) as sampled: heights in [0, 1]; the image's bottom row is t = 0 (the "
             "PFM's first stored row; a PNG's last row), its left column s = 0, texel centres "
             "at ((i + ½)/width, (j + ½)/height), bilinear and repeating; T = (s, t) by eq. 2: s "
             "= (P_N − O)·Û/|U|·S_x, t = (P_N − O)·V̂/|V|·S_y (values: O, U, V, S_x, S_y; "
             "height S_z); eq. 1: f(P) = P·N − N·O + OM(T)·S_z, N = Û × V̂, clipped where f < 0",
         std::move(map),
         {{"originX", cs.origin.x},
          {"originY", cs.origin.y},
          {"originZ", cs.origin.z},
          {"uX", cs.u.x},
          {"uY", cs.u.y},
          {"uZ", cs.u.z},
          {"vX", cs.v.x},
          {"vY", cs.v.y},
          {"vZ", cs.v.z},
          {"scaleX", cs.scale.x},
          {"scaleY", cs.scale.y},
          {"height", cs.scale.z}}});
  }
  for (std::size_t k = 0; k < capped_.size(); ++k) {
    const DepthSpriteGpu& s = gpu_->sprites[k];
    const int n = s.sprite.width, d = s.sprite.depthComplexity;
    std::vector<float> texels(std::size_t(n) * std::size_t(n) * std::size_t(std::max(d, 1)));
    glGetTextureImage(s.layers.id(), 0, GL_RED, GL_FLOAT, GLsizei(texels.size() * sizeof(float)),
                      texels.data());
    for (int i = 0; i < d; ++i) {
      FloatImage image(n, n, 1);
      std::copy_n(texels.begin() + std::ptrdiff_t(std::size_t(i) * std::size_t(n) * std::size_t(n)),
                  std::size_t(n) * std::size_t(n), image.data.begin());
      image.flipVertically();
      aovs.push_back({"ldi_" + std::to_string(capped_[k]) + "_" + std::to_string(i),
                      "layer " + std::to_string(i) + " of " + std::to_string(d) +
                          " of the volumetric depth sprite of object " +
                          std::to_string(capped_[k]) + " (\"" + scene.objects[capped_[k]].name +
                          "\", Trapp13 §5.2): depth in [0,1] along the sprite's rays, 1 = empty",
                      std::move(image)});
    }
  }
  return aovs;
}

}  // namespace cutaway
