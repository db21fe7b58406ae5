#include "kinds/pipes/pipe_kind.hpp"

#include <algorithm>
#include <cmath>

#include "cutaway/gl/shader.hpp"
#include "frame/samples.hpp"

namespace cutaway {

namespace {

// Mirrors of src/render/pipes: the node buffer, the proxy vertices and the shaft water.
struct Node {
  glm::vec3 position;
  float arc;
  GLint pipe;
};
struct ProxyVertex {
  glm::vec3 axis, offset;  // world = axis + offset · r_out
  glm::vec2 uv;
  GLint pipe, kind;  // kind 0: end triangle, 1: quad
  glm::vec3 normal;
};
struct PipeRecord {
  glm::vec4 radii, cut;
};
struct WaterDisc {
  glm::vec4 disc;
  float fill;
};

constexpr GLuint kPrimitiveRestart = 0xffffffffu;
constexpr GLint kPass = 37;
constexpr int kStencilInside = 1, kStencilCut = 2, kStencilBackEnd = 4;

glm::vec3 cutUp(const glm::vec3& d) {
  glm::vec3 u = glm::vec3(0, 1, 0) - d.y * d;
  return glm::dot(u, u) < 1e-8f ? glm::normalize(glm::cross(d, glm::vec3(1, 0, 0)))
                                : glm::normalize(u);
}

// §6.1–6.2: the proxies of one cut stretch: a quad per segment in the plane through the axis
// perpendicular to cutUp, v across the diameter; an isosceles right triangle at each end,
// its base on that plane and its apex h = √2 r_out above the axis, so the upper half of the
// pipe's cross-section (radius r_out) fits inside; its front faces the opened stretch.
void appendProxies(const Pipe& pipe, GLint index, std::vector<ProxyVertex>& out) {
  const std::vector<glm::vec3> q = cutStretch(pipe, *pipe.cut);
  if (q.size() < 2) return;
  std::vector<glm::vec3> dirs(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) {
    const glm::vec3 a = i > 0 ? glm::normalize(q[i] - q[i - 1]) : glm::vec3(0.0f);
    const glm::vec3 b = i + 1 < q.size() ? glm::normalize(q[i + 1] - q[i]) : glm::vec3(0.0f);
    const glm::vec3 m = a + b;
    dirs[i] = glm::dot(m, m) < 1e-12f ? (i > 0 ? a : b) : glm::normalize(m);
  }
  const auto vertex = [&](const glm::vec3& axis, const glm::vec3& offset, glm::vec2 uv, GLint kind,
                          const glm::vec3& normal) {
    out.push_back({axis, offset, uv, index, kind, normal});
  };
  for (std::size_t i = 0; i + 1 < q.size(); ++i) {
    const glm::vec3 s0 = glm::normalize(glm::cross(dirs[i], cutUp(dirs[i])));
    const glm::vec3 s1 = glm::normalize(glm::cross(dirs[i + 1], cutUp(dirs[i + 1])));
    const glm::vec3 n = cutUp(glm::normalize(q[i + 1] - q[i]));
    vertex(q[i], -s0, {0.5f, 0.0f}, 1, n);
    vertex(q[i], s0, {0.5f, 1.0f}, 1, n);
    vertex(q[i + 1], s1, {0.5f, 1.0f}, 1, n);
    vertex(q[i], -s0, {0.5f, 0.0f}, 1, n);
    vertex(q[i + 1], s1, {0.5f, 1.0f}, 1, n);
    vertex(q[i + 1], -s1, {0.5f, 0.0f}, 1, n);
  }
  const float h = std::sqrt(2.0f);
  for (const bool start : {true, false}) {
    const std::size_t i = start ? 0 : q.size() - 1;
    const glm::vec3 up = cutUp(dirs[i]);
    const glm::vec3 side = glm::normalize(glm::cross(dirs[i], up));
    const glm::vec3 front = start ? dirs[i] : -dirs[i];  // towards the opened stretch
    // uv = (0.5, 0.5) + offset / 2 in (side, up): d = 0.5 at r_out (eq. 12).
    const glm::vec3 a = -h * side, b = h * side, c = h * up;
    const glm::vec2 ua(0.5f - h / 2, 0.5f), ub(0.5f + h / 2, 0.5f), uc(0.5f, 0.5f + h / 2);
    // (a, b, c) winds about −dir; the start's front faces +dir.
    if (start) {
      vertex(q[i], a, ua, 0, front), vertex(q[i], c, uc, 0, front), vertex(q[i], b, ub, 0, front);
    } else {
      vertex(q[i], a, ua, 0, front), vertex(q[i], b, ub, 0, front), vertex(q[i], c, uc, 0, front);
    }
  }
}

template <typename T>
gl::Buffer upload(const std::vector<T>& data) {
  return gl::Buffer::create(GLsizeiptr(std::max<std::size_t>(data.size(), 1) * sizeof(T)),
                            data.empty() ? nullptr : data.data());
}

}  // namespace

bool PipeKind::present(const Scene& scene) {
  return std::any_of(scene.networks.begin(), scene.networks.end(),
                     [](const PipeNetwork& n) { return n.mode == PipeNetwork::Mode::Billboards; });
}

PipeKind::PipeKind(FrameSetup& setup)
    : setup_(setup),
      scene_(setup.scene),
      pipesBlock_(setup.bindings.storageBlock("PIPES")),
      ownerUnit_(setup.bindings.textureUnit("PIPE_OWNER")),
      ownerDepthUnit_(setup.bindings.textureUnit("PIPE_OWNER_DEPTH")),
      stencilMasksUnit_(setup.bindings.textureUnit("PIPE_STENCIL_MASKS")) {
  const Scene& scene = scene_;
  GLint pipeBase = 0;
  for (std::size_t k = 0; k < scene.networks.size(); ++k) {
    const PipeNetwork& net = scene.networks[k];
    if (net.mode != PipeNetwork::Mode::Billboards) continue;
    NetworkGpu g{k, int(scene.objects.size() + k), {}, {}, {}, {}, {}, {}, {}, {}, {}, 0, 0, 0, 0};
    std::vector<Node> nodes;
    std::vector<GLuint> indices;
    std::vector<PipeRecord> records;
    std::vector<ProxyVertex> proxies;
    for (std::size_t i = 0; i < net.pipes.size(); ++i) {
      const Pipe& p = net.pipes[i];
      records.push_back(
          {glm::vec4(p.radius, p.wallThickness, p.waterLevel, float(pipeBase + GLint(i))),
           p.cut ? glm::vec4(p.cut->x, p.cut->y, 1.0f, 0.0f) : glm::vec4(0.0f)});
      // A line strip with adjacency whose ends repeat: the geometry shader sees an end as an
      // adjacent node equal to the segment's own (eqs. 4 and 6).
      const auto first = GLuint(nodes.size());
      float arc = 0.0f;
      for (std::size_t j = 0; j < p.nodes.size(); ++j) {
        if (j > 0) arc += glm::length(p.nodes[j] - p.nodes[j - 1]);
        nodes.push_back({p.nodes[j], arc, GLint(i)});
      }
      indices.push_back(first);
      for (std::size_t j = 0; j < p.nodes.size(); ++j) indices.push_back(first + GLuint(j));
      indices.push_back(first + GLuint(p.nodes.size() - 1));
      indices.push_back(kPrimitiveRestart);
      if (p.cut) appendProxies(p, GLint(i), proxies);
    }
    pipeBase += GLint(net.pipes.size());
    std::vector<WaterDisc> water;
    for (const Shaft& s : net.shafts)
      if (s.waterLevel > 0.0f)
        water.push_back({glm::vec4(s.bottom + glm::vec3(0, s.waterLevel, 0), s.innerRadius()),
                         s.waterLevel / std::max(s.top - s.bottom.y, 1e-6f)});
    g.pipes = upload(records);
    g.nodes = upload(nodes);
    g.nodeIndices = upload(indices);
    g.nodeIndexCount = GLsizei(indices.size());
    g.nodeArray = gl::VertexArray::create();
    GLuint vao = g.nodeArray.id();
    glVertexArrayVertexBuffer(vao, 0, g.nodes.id(), 0, sizeof(Node));
    glVertexArrayElementBuffer(vao, g.nodeIndices.id());
    glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(Node, position));
    glVertexArrayAttribFormat(vao, 1, 1, GL_FLOAT, GL_FALSE, offsetof(Node, arc));
    glVertexArrayAttribIFormat(vao, 2, 1, GL_INT, offsetof(Node, pipe));
    for (GLuint a = 0; a < 3; ++a)
      glEnableVertexArrayAttrib(vao, a), glVertexArrayAttribBinding(vao, a, 0);

    g.proxy = upload(proxies);
    g.proxyVertexCount = GLsizei(proxies.size());
    std::vector<GLuint> ends;
    for (std::size_t v = 0; v < proxies.size(); ++v)
      if (proxies[v].kind == 0) ends.push_back(GLuint(v));
    g.endTriangles = upload(ends);
    g.endTriangleIndexCount = GLsizei(ends.size());
    g.proxyArray = gl::VertexArray::create();
    vao = g.proxyArray.id();
    glVertexArrayVertexBuffer(vao, 0, g.proxy.id(), 0, sizeof(ProxyVertex));
    glVertexArrayElementBuffer(vao, g.endTriangles.id());
    glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(ProxyVertex, axis));
    glVertexArrayAttribFormat(vao, 1, 3, GL_FLOAT, GL_FALSE, offsetof(ProxyVertex, offset));
    glVertexArrayAttribFormat(vao, 2, 2, GL_FLOAT, GL_FALSE, offsetof(ProxyVertex, uv));
    glVertexArrayAttribIFormat(vao, 3, 1, GL_INT, offsetof(ProxyVertex, pipe));
    glVertexArrayAttribIFormat(vao, 4, 1, GL_INT, offsetof(ProxyVertex, kind));
    glVertexArrayAttribFormat(vao, 5, 3, GL_FLOAT, GL_FALSE, offsetof(ProxyVertex, normal));
    for (GLuint a = 0; a < 6; ++a)
      glEnableVertexArrayAttrib(vao, a), glVertexArrayAttribBinding(vao, a, 0);

    g.water = upload(water);
    g.waterCount = GLsizei(water.size());
    g.waterArray = gl::VertexArray::create();
    vao = g.waterArray.id();
    glVertexArrayVertexBuffer(vao, 0, g.water.id(), 0, sizeof(WaterDisc));
    glVertexArrayBindingDivisor(vao, 0, 1);
    glVertexArrayAttribFormat(vao, 0, 4, GL_FLOAT, GL_FALSE, offsetof(WaterDisc, disc));
    glVertexArrayAttribFormat(vao, 1, 1, GL_FLOAT, GL_FALSE, offsetof(WaterDisc, fill));
    for (GLuint a = 0; a < 2; ++a)
      glEnableVertexArrayAttrib(vao, a), glVertexArrayAttribBinding(vao, a, 0);
    cutOpen_ = cutOpen_ || g.proxyVertexCount > 0;
    networks_.push_back(std::move(g));
  }
}

void PipeKind::prepare(const std::vector<ActiveCutter>&) {
  const Scene& scene = scene_;
  Frame& frame = setup_.frame;
  const GBuffer& gbuffer = setup_.gbuffer;
  gbufferTargets_ = GLuint(gbuffer.colorAttachmentCount());
  const std::map<std::string, std::string> defines{
      {"PIPE_CLASS_LOCATION", std::to_string(gbufferTargets_)}};
  const auto build = [&](std::vector<std::pair<GLenum, std::string>> stages,
                         std::map<std::string, std::string> extra = {}) {
    extra.insert(defines.begin(), defines.end());
    return gl::buildProgram(setup_.geometryProgram(std::move(stages), std::move(extra)));
  };
  // The billboards' two passes as two programs, each with the other's code folded away.
  const auto billboards = [&](bool inside) {
    return build({{GL_VERTEX_SHADER, "kinds/pipes/billboard.vert"},
                  {GL_GEOMETRY_SHADER, "kinds/pipes/billboard.geom"},
                  {GL_FRAGMENT_SHADER, "kinds/pipes/billboard.frag"}},
                 {{"INSIDE_PASS", inside ? "1" : "0"}});
  };
  outsideProgram_ = billboards(false);
  insideProgram_ = billboards(true);
  if (scene.style.shadows.enabled)
    shadowProgram_ = setup_.bindings.build(
        {.stages = {{GL_VERTEX_SHADER, "kinds/pipes/billboard.vert"},
                    {GL_GEOMETRY_SHADER, "kinds/pipes/billboard.geom"},
                    {GL_FRAGMENT_SHADER, "kinds/pipes/billboard_shadow.frag"}}});
  rearHullProgram_ = setup_.bindings.build(
      {.stages = {{GL_VERTEX_SHADER, "kinds/pipes/billboard.vert"},
                  {GL_GEOMETRY_SHADER, "kinds/pipes/billboard.geom"},
                  {GL_FRAGMENT_SHADER, "kinds/pipes/billboard_rear_hull.frag"}}});
  proxyProgram_ = build(
      {{GL_VERTEX_SHADER, "kinds/pipes/proxy.vert"}, {GL_FRAGMENT_SHADER, "kinds/pipes/proxy.frag"}});
  ownerProgram_ = build(
      {{GL_VERTEX_SHADER, "kinds/pipes/proxy.vert"}, {GL_FRAGMENT_SHADER, "kinds/pipes/proxy.frag"}},
      {{"PROXY_OWNER", "1"}});
  waterProgram_ = build({{GL_VERTEX_SHADER, "kinds/pipes/water_disc.vert"},
                         {GL_FRAGMENT_SHADER, "kinds/pipes/water_disc.frag"}});
  aovProgram_ =
      buildFullscreenProgram("kinds/pipes/pipe_aovs.frag", sampleDefines(setup_.scene.samples));
  stencilMasksProgram_ = buildFullscreenProgram("kinds/pipes/pipe_stencil_masks.frag",
                                                sampleDefines(setup_.scene.samples));
  glProgramUniform1i(stencilMasksProgram_.id(), 0, setup_.scene.samples);

  owner_ = frame.declare("pipeOwner", {.format = GL_R32I});
  ownerDepth_ = frame.declare("pipeOwnerDepth", {.format = GL_DEPTH_COMPONENT32F});
  stencilMasks_ = frame.declare("pipeStencilMasks", {.format = GL_RG32I});
  pipeClass_ = frame.declare("scenePipeClass", {.format = GL_R8, .samples = scene.samples});
  stencilAov_ = frame.declare(
      "pipeStencil",
      {.format = GL_R32F,
       .meaning = "Konev18 §6: the stencil buffer after the proxy passes: 0 the pipes' outside, 1 "
                  "a cut pipe's inside (proxy pass 2: eqs. 14-15), 2 a cut surface (pass 1: eqs. "
                  "13, 16), 4 the outside over an end triangle seen from behind (Fig. 10's "
                  "reset); sample 0"});
  classAov_ = frame.declare(
      "pipeClass",
      {.format = GL_R32F,
       .meaning = "the visible pipe surface: 0 no pipe, 0.25 a pipe's outside, 0.5 its inside "
                  "(inverted normals), 0.75 a cut surface, 1 water (pipes and shafts); sample 0"});
  // The stencil of the depth-stencil target, readable as integers (GL_STENCIL_INDEX mode).
  GLuint view = 0;
  glGenTextures(1, &view);
  const TargetDesc& depth = frame.desc(gbuffer.depth());
  glTextureView(view, depth.textureTarget(), frame.texture(gbuffer.depth()).id(), depth.format, 0,
                1, 0, 1);
  glTextureParameteri(view, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_STENCIL_INDEX);
  // A 2-D one (one sample) samples stencil only with nearest filtering, else it is incomplete.
  glTextureParameteri(view, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(view, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  stencilView_ = gl::Texture(view);
}

void PipeKind::addPassesAfterGeometry(Frame& frame) {
  const GBuffer& gbuffer = setup_.gbuffer;
  std::vector<Target> writes = gbuffer.colorTargets();
  writes.push_back(pipeClass_);
  writes.push_back(gbuffer.depth());
  frame.addPass({.name = "pipeOwners",
                 .writes = {owner_, ownerDepth_},
                 .run = [this](const PassContext&) { drawOwners(); }});
  frame.addPass({.name = "pipeProxies", .writes = writes, .run = [this](const PassContext& pass) {
                   const GLint zero = 0;
                   const float none[4] = {0, 0, 0, 0};
                   glClearNamedFramebufferiv(pass.framebuffer, GL_STENCIL, 0, &zero);
                   glClearNamedFramebufferfv(pass.framebuffer, GL_COLOR, GLint(gbufferTargets_),
                                             none);
                   setup_.bindShading();
                   drawProxies();
                 }});
  frame.addPass({.name = "pipeStencilMasks",
                 .reads = {gbuffer.depth()},
                 .writes = {stencilMasks_},
                 .run = [this](const PassContext&) {
                   if (!cutOpen_) {  // no proxies: every sample at stencil 0
                     const GLint allOutside[2] = {0xffff, 0};
                     glClearTexImage(setup_.frame.texture(stencilMasks_).id(), 0, GL_RG_INTEGER,
                                     GL_INT, allOutside);
                     return;
                   }
                   glDisable(GL_DEPTH_TEST);
                   glUseProgram(stencilMasksProgram_.id());
                   glBindTextureUnit(0, stencilView_.id());
                   fullscreen_.draw();
                 }});
  frame.addPass({.name = "pipes",
                 .reads = {owner_, ownerDepth_, stencilMasks_},
                 .writes = writes,
                 .run = [this](const PassContext&) {
                   setup_.bindShading();
                   drawPipes();
                 }});
  // Only AOVs read these: a frame that shows its picture alone skips the pass.
  frame.addPass({.name = "pipeAovs",
                 .reads = {gbuffer.depth(), pipeClass_},
                 .writes = {stencilAov_, classAov_},
                 .run = [this](const PassContext&) { drawAovs(); },
                 .onRead = true});
}

void PipeKind::setNetworkUniforms(GLuint program, const NetworkGpu& n) const {
  const PipeNetwork& net = scene_.networks[n.network];
  glProgramUniform1f(program, 30, net.radiusScale);
  glProgramUniform3fv(program, 31, 1, &net.color[0]);
  glProgramUniform3fv(program, 32, 1, &net.insideColor[0]);
  glProgramUniform3fv(program, 33, 1, &net.cutColor[0]);
  glProgramUniform3fv(program, 34, 1, &net.waterLow[0]);
  glProgramUniform3fv(program, 35, 1, &net.waterHigh[0]);
  glProgramUniform1i(program, 36, n.objectId);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, pipesBlock_, n.pipes.id());
}

void PipeKind::drawTubes(GLuint program) const {
  glUseProgram(program);
  glEnable(GL_PRIMITIVE_RESTART);
  glPrimitiveRestartIndex(kPrimitiveRestart);
  for (const NetworkGpu& n : networks_) {
    // Only the radii: these programs have no colours.
    glProgramUniform1f(program, 30, scene_.networks[n.network].radiusScale);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, pipesBlock_, n.pipes.id());
    glBindVertexArray(n.nodeArray.id());
    glDrawElements(GL_LINE_STRIP_ADJACENCY, n.nodeIndexCount, GL_UNSIGNED_INT, nullptr);
  }
  glDisable(GL_PRIMITIVE_RESTART);
}

void PipeKind::drawShadowCasters() const {
  drawTubes(shadowProgram_.id());
}

void PipeKind::drawInterestRearHulls(const RearHullRequest& request) const {
  glProgramUniform1f(rearHullProgram_.id(), 16, request.theta(nullptr));
  drawTubes(rearHullProgram_.id());
}

void PipeKind::drawOwners() {
  const GLint none = 0;
  const float far = 1.0f;
  glClearTexImage(setup_.frame.texture(owner_).id(), 0, GL_RED_INTEGER, GL_INT, &none);
  glClearTexImage(setup_.frame.texture(ownerDepth_).id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &far);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  const GLuint program = ownerProgram_.id();
  glUseProgram(program);
  for (const NetworkGpu& n : networks_) {
    if (n.proxyVertexCount == 0) continue;
    setNetworkUniforms(program, n);
    glBindVertexArray(n.proxyArray.id());
    glDrawArrays(GL_TRIANGLES, 0, n.proxyVertexCount);
  }
}

void PipeKind::drawProxies() {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  glEnable(GL_STENCIL_TEST);
  glStencilMask(0xff);
  const GLuint proxy = proxyProgram_.id();
  const auto colorWrites = [&](bool on) {
    for (GLuint i = 0; i <= gbufferTargets_; ++i) glColorMaski(i, on, on, on, on);
  };
  const auto proxies = [&](int pass) {
    glUseProgram(proxy);
    glProgramUniform1i(proxy, kPass, pass);
    for (const NetworkGpu& n : networks_) {
      if (n.proxyVertexCount == 0) continue;
      setNetworkUniforms(proxy, n);
      glBindVertexArray(n.proxyArray.id());
      if (pass == 3)
        glDrawElements(GL_TRIANGLES, n.endTriangleIndexCount, GL_UNSIGNED_INT, nullptr);
      else
        glDrawArrays(GL_TRIANGLES, 0, n.proxyVertexCount);
    }
  };
  // Pass 1: the cut surface (eqs. 13, 16), drawn and marked 2.
  glDepthMask(GL_TRUE);
  glStencilFunc(GL_ALWAYS, kStencilCut, 0xff);
  glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
  proxies(1);
  // Pass 2: the inside (eqs. 14–15) marked 1, never over a cut surface; stencil only.
  // The test sees only the cut bit (mask 2): it passes where the value is 0 or 1, and
  // REPLACE writes the reference.
  glDepthMask(GL_FALSE);
  colorWrites(false);
  glStencilFunc(GL_EQUAL, kStencilInside, kStencilCut);
  glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
  proxies(2);
  // Fig. 10: an end triangle seen from behind resets its area to the pipe's outside, marked
  // apart (4): there the closed tube's end covers the disc beyond the flat end of its quad,
  // so the cut stretch's quad keeps its upper half. Only the end triangles, their front
  // faces culled: llvmpipe would rasterise and shade the rest for proxy.frag to discard.
  glStencilFunc(GL_EQUAL, kStencilBackEnd, kStencilCut);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT);
  proxies(3);
  glCullFace(GL_BACK);
  glDisable(GL_CULL_FACE);
  colorWrites(true);
  glDisable(GL_STENCIL_TEST);
}

void PipeKind::drawPipes() {
  // The billboards: the outside over stencil 0, 2 and 4 (billboard.frag leaves out the samples
  // each removes, from pipeStencilMasks), then the inside over 1.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  glEnable(GL_STENCIL_TEST);
  glDepthMask(GL_TRUE);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  glBindTextureUnit(ownerUnit_, setup_.frame.texture(owner_).id());
  glBindTextureUnit(ownerDepthUnit_, setup_.frame.texture(ownerDepth_).id());
  glBindTextureUnit(stencilMasksUnit_, setup_.frame.texture(stencilMasks_).id());
  glEnable(GL_PRIMITIVE_RESTART);
  glPrimitiveRestartIndex(kPrimitiveRestart);
  for (const bool inside : {false, true}) {
    if (inside && !cutOpen_) break;  // no proxies: no sample at stencil 1
    glStencilFunc(inside ? GL_EQUAL : GL_NOTEQUAL, kStencilInside, 0xff);
    const GLuint billboard = (inside ? insideProgram_ : outsideProgram_).id();
    glUseProgram(billboard);
    for (const NetworkGpu& n : networks_) {
      setNetworkUniforms(billboard, n);
      glBindVertexArray(n.nodeArray.id());
      glDrawElements(GL_LINE_STRIP_ADJACENCY, n.nodeIndexCount, GL_UNSIGNED_INT, nullptr);
    }
  }
  glDisable(GL_PRIMITIVE_RESTART);
  glDisable(GL_STENCIL_TEST);

  // §7 with §6.4: the water inside the shafts.
  glUseProgram(waterProgram_.id());
  for (const NetworkGpu& n : networks_) {
    if (n.waterCount == 0) continue;
    setNetworkUniforms(waterProgram_.id(), n);
    glBindVertexArray(n.waterArray.id());
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, n.waterCount);
  }
}

void PipeKind::drawAovs() {
  glDisable(GL_DEPTH_TEST);
  glUseProgram(aovProgram_.id());
  glBindTextureUnit(0, stencilView_.id());
  glBindTextureUnit(1, setup_.frame.texture(pipeClass_).id());
  fullscreen_.draw();
}

}  // namespace cutaway
