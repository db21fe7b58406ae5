#include "cutters/breakaway/breakaway.hpp"

#include <algorithm>
#include <map>

#include "cutaway/core/error.hpp"
#include "cutaway/geometry/convex_hull.hpp"
#include "cutaway/cutters/cutout.hpp"  // the wall colour both Diepstraten03 cutters default to
#include "cutaway/gl/shader.hpp"

namespace cutaway {

namespace {

// The vertices of the convex hull of `points` (Qhull's), or where they span no volume, of
// their hull in the plane they lie in (a sheet: Andrew's monotone chain), or the two ends of
// the line they lie on.
std::vector<glm::vec3> hullVertices(const std::vector<glm::vec3>& points) {
  if (points.empty()) throw Error("a hull of no points");
  try {
    return convexHull(points).positions;
  } catch (const Error&) {
  }
  const glm::dvec3 p0(points.front());
  glm::dvec3 p1 = p0, p2 = p0;
  double far = -1.0;
  for (const glm::vec3& p : points)
    if (const double d = glm::length(glm::dvec3(p) - p0); d > far) far = d, p1 = p;
  const glm::dvec3 u = far > 0.0 ? (p1 - p0) / far : glm::dvec3(1, 0, 0);
  double off = -1.0;
  for (const glm::vec3& p : points)
    if (const double d = glm::length(glm::cross(u, glm::dvec3(p) - p0)); d > off) off = d, p2 = p;
  std::vector<std::pair<glm::dvec2, glm::vec3>> plane;
  if (!(off > 1e-6 * far)) {  // on one line (or one point): its two ends
    const auto along = [&](const glm::vec3& p) { return glm::dot(glm::dvec3(p) - p0, u); };
    const auto [lo, hi] = std::minmax_element(
        points.begin(), points.end(),
        [&](const glm::vec3& a, const glm::vec3& b) { return along(a) < along(b); });
    return {*lo, *hi};
  }
  const glm::dvec3 n = glm::normalize(glm::cross(u, p2 - p0)), v = glm::cross(n, u);
  for (const glm::vec3& p : points)
    plane.emplace_back(glm::dvec2(glm::dot(glm::dvec3(p) - p0, u), glm::dot(glm::dvec3(p) - p0, v)),
                       p);
  std::sort(plane.begin(), plane.end(), [](const auto& a, const auto& b) {
    return a.first.x < b.first.x || (a.first.x == b.first.x && a.first.y < b.first.y);
  });
  const auto turn = [](glm::dvec2 o, glm::dvec2 a, glm::dvec2 b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<std::pair<glm::dvec2, glm::vec3>> chain(2 * plane.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < plane.size(); ++i) {  // lower hull
    while (k >= 2 && turn(chain[k - 2].first, chain[k - 1].first, plane[i].first) <= 0.0) --k;
    chain[k++] = plane[i];
  }
  for (std::size_t i = plane.size() - 1, lower = k + 1; i-- > 0;) {  // upper hull
    while (k >= lower && turn(chain[k - 2].first, chain[k - 1].first, plane[i].first) <= 0.0) --k;
    chain[k++] = plane[i];
  }
  std::vector<glm::vec3> out;
  for (std::size_t i = 0; i + 1 < k; ++i) out.push_back(chain[i].second);
  return out;
}

}  // namespace

Mesh inflatedHull(const std::vector<glm::vec3>& points, float offset) {
  if (offset <= 0.0f) return convexHull(points);
  // The 12 vertices and 30 edge midpoints of an icosahedron, on the unit sphere: the hull of
  // p + offset·d over these 42 directions never reaches beyond the exact offset body and
  // contains every point within 0.9·offset of the points (tests/test_cutout.cpp measures it).
  const float phi = (1.0f + std::sqrt(5.0f)) * 0.5f;
  std::vector<glm::vec3> ico;
  for (const float a : {-1.0f, 1.0f})
    for (const float b : {-phi, phi}) {
      ico.push_back(glm::normalize(glm::vec3(0, a, b)));
      ico.push_back(glm::normalize(glm::vec3(a, b, 0)));
      ico.push_back(glm::normalize(glm::vec3(b, 0, a)));
    }
  std::vector<glm::vec3> directions = ico;
  for (std::size_t i = 0; i < ico.size(); ++i)
    for (std::size_t j = i + 1; j < ico.size(); ++j)
      if (glm::dot(ico[i], ico[j]) > 0.4f)  // neighbours: cos 63.4° = 0.447
        directions.push_back(glm::normalize(ico[i] + ico[j]));
  // Only the hull's own vertices matter; a flat cluster (a sheet, a wire) grows into a solid.
  const std::vector<glm::vec3> vertices = hullVertices(points);
  std::vector<glm::vec3> grown;
  grown.reserve(vertices.size() * directions.size());
  for (const auto& p : vertices)
    for (const auto& d : directions) grown.push_back(p + offset * d);
  return convexHull(grown);
}

BreakawayExtent breakawayExtent(const Scene& scene, const BreakawayOptions& options) {
  // At the rest pose: the hole keeps its rim as the objects move (their motion's sweep is
  // no part of their size).
  Bounds interior;
  for (const auto& o : scene.objects)
    if (!o.proxy && o.role == Role::Interior && o.mesh)
      interior.extend(o.mesh->bounds().transformed(o.transformAt(0.0f)));
  const float offset = options.offset ? *options.offset : 0.05f * interior.radius();
  const float thickness = options.wallThickness ? *options.wallThickness : 0.5f * offset;
  return {offset, std::min(thickness, offset)};
}

std::vector<BreakawayCluster> breakawayClusters(const Scene& scene, const BreakawayOptions& options,
                                                float time) {
  std::vector<BreakawayCluster> clusters;
  std::map<std::string, std::size_t> clusterOfGroup;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    if (o.proxy || o.role != Role::Interior) continue;
    const auto [it, added] = clusterOfGroup.emplace(o.group, clusters.size());
    if (added) clusters.push_back({o.group, {}, {}, {}});
    clusters[it->second].objects.push_back(i);
  }
  const BreakawayExtent extent = breakawayExtent(scene, options);
  for (auto& c : clusters) {
    std::vector<glm::vec3> points;
    for (const std::size_t i : c.objects) {
      const glm::mat4 m = scene.objects[i].transformAt(time);
      for (const auto& p : scene.objects[i].mesh->positions)
        points.push_back(glm::vec3(m * glm::vec4(p, 1.0f)));
    }
    const std::string name = c.group.empty() ? "the ungrouped interior objects" : c.group;
    try {
      c.outerHull = inflatedHull(points, extent.offset);
      c.innerHull = inflatedHull(points, extent.offset - extent.wallThickness);
    } catch (const Error&) {  // a hull of no volume
      throw Error(
          scene.file.string(),
          "/objects/" + std::to_string(c.objects.front()) + (c.group.empty() ? "" : "/group"),
          "interior cluster \"" + name +
              "\" is flat (its points lie in one plane or on one line) and its inner hull "
              "is not grown (wallThickness ≥ offset), so it has no inside; give the breakaway "
              "an offset > its wall thickness");
    }
  }
  return clusters;
}

CutterType breakawayCutterType() {
  return {.key = "breakaway",
          .title = "Breakaway (Diepstraten03)",
          .glsl = "cutters/breakaway/breakaway.glsl",
          .name = "breakaway",
          .schema = &breakawaySchema(),
          // Diepstraten03 rule 1: the cutters need the inside/outside classification.
          .complete =
              [](const json_reader::Context& ctx, const std::string& pointer, Scene& s) {
                requireExterior(ctx, pointer, s);
                requireRole(ctx, pointer, s, Role::Interior,
                            "the breakaway hull is built around them");
              },
          .create = [](FrameSetup& setup) -> std::unique_ptr<Cutter> {
            return std::make_unique<Breakaway>(setup);
          }};
}

Breakaway::Breakaway(FrameSetup& setup)
    : setup_(setup),
      clipUnit_(setup.bindings.textureUnit("BREAKAWAY_CLIP_DEPTH")),
      innerUnit_(setup.bindings.textureUnit("BREAKAWAY_INNER_DEPTH")),
      normalUnit_(setup.bindings.textureUnit("BREAKAWAY_HULL_NORMAL")) {
  buildHulls(0.0f);
  for (const SceneObject& o : setup.scene.objects)
    animated_ = animated_ || (o.role == Role::Interior && !o.proxy && !o.animation.empty());
  hullProgram_ =
      gl::buildProgram({.stages = {{GL_VERTEX_SHADER, "frame/mesh.vert"},
                                   {GL_FRAGMENT_SHADER, "cutters/breakaway/hull.frag"}}});
  const glm::mat4 identity(1.0f);
  glProgramUniformMatrix4fv(hullProgram_.id(), meshUniform::kModel, 1, GL_FALSE, &identity[0][0]);
  glProgramUniformMatrix4fv(hullProgram_.id(), meshUniform::kNormalMatrix, 1, GL_FALSE,
                            &identity[0][0]);
  Frame& frame = setup.frame;
  clipDepth_ = frame.declare(
      "breakawayClipDepth",
      {.format = GL_DEPTH_COMPONENT32F,
       .meaning = "window depth in [0,1] of the foremost surface of the interior objects' inflated "
                  "convex hulls (Diepstraten03 §5); exterior front faces at or in front of it are "
                  "removed; 0 where no hull covers the pixel"});
  innerDepth_ = frame.declare("breakawayInnerDepth",
                              {.format = GL_DEPTH_COMPONENT32F,
                               .meaning = "the same for the smaller hulls (offset minus wall "
                                          "thickness) that clip exterior back faces"});
  hullNormal_ = frame.declare("breakawayHullNormal", {.format = GL_RGBA16F});
}

void Breakaway::buildHulls(float time) {
  outer_.clear();
  inner_.clear();
  for (const auto& c : breakawayClusters(setup_.scene, options(), time)) {
    outer_.emplace_back(c.outerHull);
    inner_.emplace_back(c.innerHull);
  }
  hullsTime_ = time;
}

void Breakaway::beginFrame(const FrameState& state) {
  if (animated_ && state.time != hullsTime_) buildHulls(state.time);  // around this frame's pose
}

void Breakaway::addPreparationPasses(Frame& frame) {
  frame.addPass(
      {.name = "breakawayClip",
       .writes = {hullNormal_, clipDepth_},
       .run = [this](const PassContext& pass) { drawClipDepth(pass.framebuffer, outer_); }});
  frame.addPass(
      {.name = "breakawayInnerClip",
       .writes = {innerDepth_},  // back faces need no hull normal
       .run = [this](const PassContext& pass) { drawClipDepth(pass.framebuffer, inner_); }});
}

void Breakaway::drawClipDepth(GLuint framebuffer, const std::vector<GpuMesh>& hulls) const {
  const float zero[4] = {0, 0, 0, 0}, near = 0.0f;
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, zero);
  // Diepstraten03 §5: depth cleared to 0 (the near plane); the hulls drawn with a greater-than
  // test leave their rear depth, then with a less-than test their foremost depth; pixels no
  // hull covers keep 0 and clip nothing.
  glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &near);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  glUseProgram(hullProgram_.id());
  glColorMaski(0, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glDepthFunc(GL_GREATER);
  for (const auto& h : hulls) h.draw();
  glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthFunc(GL_LESS);
  for (const auto& h : hulls) h.draw();
}

void Breakaway::bindForGeometry() const {
  glBindTextureUnit(clipUnit_, setup_.frame.texture(clipDepth_).id());
  glBindTextureUnit(innerUnit_, setup_.frame.texture(innerDepth_).id());
  glBindTextureUnit(normalUnit_, setup_.frame.texture(hullNormal_).id());
}

bool Breakaway::cuts(std::size_t index) const {
  const SceneObject& o = setup_.scene.objects[index];
  return o.role == Role::Exterior && o.mayBeCutBy(BreakawayOptions::kKey);
}

bool Breakaway::cutsVolume(std::size_t index) const {
  const SceneVolume& v = setup_.scene.volumes[index];
  return v.role == Role::Exterior && v.mayBeCutBy(BreakawayOptions::kKey);
}

CutLook Breakaway::look(std::size_t index) const {
  const SceneObject& o = setup_.scene.objects[index];
  return {.cutSurface = o.solid(),
          .cutColor = options().wallColor.value_or(kDefaultWallColor),
          .backColor = options().insideColor.value_or(o.material.color * 0.55f)};
}

}  // namespace cutaway
