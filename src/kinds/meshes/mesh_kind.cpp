#include "kinds/meshes/mesh_kind.hpp"

#include <algorithm>

namespace cutaway {

namespace {
// Uniform locations of kinds/meshes/mesh.frag and frame/mesh.vert.
constexpr GLint kColor = 8, kSpecular = 9, kShininess = 10, kObjectId = 11, kLines = 12,
                kCutBy = 13, kCutSurfaces = 14, kBackColor = 15, kImportance = 16, kFirstLayer = 17,
                kClipPlane = 18, kSlabClip = 19, kCutColor = 24, kChannelsBy = 31;
constexpr int kSlabClipPlanes = Cutter::Slab::kMostKept + 1;  // mesh.vert's uSlabClip
// A cut object's front faces by `front`, then its back faces by `back` (mesh.frag's
// FRONT_FACES, BACK_FACES), `prepare` setting each program's uniforms before it draws.
void drawSides(GLuint front, GLuint back, const SceneMeshes::DrawWith& drawWith,
               const std::function<void(GLuint)>& prepare) {
  glEnable(GL_CULL_FACE);
  for (const auto& [culled, program] : {std::pair{GL_BACK, front}, std::pair{GL_FRONT, back}}) {
    prepare(program);
    glCullFace(culled);
    drawWith(program);
  }
}

}  // namespace

bool MeshKind::needsStencil(const std::vector<ActiveCutter>& cutters) const {
  const Scene& scene = setup_.scene;
  for (std::size_t i = 0; i < scene.objects.size(); ++i)
    if (!scene.objects[i].proxy && !scene.objects[i].mesh->report.watertight)
      for (const ActiveCutter& c : cutters)
        if (c.cutter->cuts(i) && c.cutter->look(i).marksOpenMeshes) return true;
  return false;
}

void MeshKind::prepare(const std::vector<ActiveCutter>& cutters) {
  const std::vector<std::pair<GLenum, std::string>> stages{
      {GL_VERTEX_SHADER, "frame/mesh.vert"}, {GL_FRAGMENT_SHADER, "kinds/meshes/mesh.frag"}};
  uncutProgram_ = gl::buildProgram(setup_.geometryProgram(stages, {{"UNCUT", "1"}}));
  if (!cutters.empty()) {
    frontProgram_ = gl::buildProgram(setup_.geometryProgram(stages, {{"FRONT_FACES", "1"}}));
    backProgram_ = gl::buildProgram(setup_.geometryProgram(stages, {{"BACK_FACES", "1"}}));
    if (needsStencil(cutters))
      markProgram_ = gl::buildProgram(
          setup_.geometryProgram(stages, {{"FRONT_FACES", "1"}, {"MARK_REMOVED", "1"}}));
    if (!setup_.gbuffer.channels().empty())
      slabKeptProgram_ =
          gl::buildProgram(setup_.geometryProgram(stages, {{"UNCUT", "1"}, {"SLAB_KEPT", "1"}}));
  }
  culling_ = std::make_unique<OcclusionCulling>(setup_, setup_.translucentLayers);
  if (setup_.translucentLayers)
    for (const auto& [program, side] : {std::pair{&layerFrontProgram_, "FRONT_FACES"},
                                        std::pair{&layerBackProgram_, "BACK_FACES"}})
      *program = gl::buildProgram(
          setup_.geometryProgram(stages, {{"TRANSLUCENT_LAYER", "1"}, {side, "1"}}));
}

void MeshKind::addPassesAfterGeometry(Frame& frame) {
  culling_->addPass(frame, "visibleObjects", setup_.gbuffer.objectId());
}

void MeshKind::beginFrame(const FrameState& state) {
  culling_->beginFrame(state);
}

std::vector<ObjectCut> MeshKind::objectCuts(const std::vector<ActiveCutter>& cutters) const {
  std::vector<ObjectCut> cuts;
  for (std::size_t i = 0; i < setup_.scene.objects.size(); ++i)
    cuts.push_back(objectCut(cutters, i));
  return cuts;
}

void MeshKind::setObjectUniforms(GLuint program, const std::vector<ActiveCutter>& cutters,
                                 const ObjectCut& cut, const SceneObject& o, std::size_t i) const {
  glProgramUniform3fv(program, kColor, 1, &o.material.color[0]);
  glProgramUniform1f(program, kSpecular, o.material.specular);
  glProgramUniform1f(program, kShininess, o.material.shininess);
  glProgramUniform1i(program, kObjectId, int(i));
  glProgramUniform1f(program, kImportance,
                     emphasisImportance(o.role == Role::Interest, o.importance));
  glProgramUniform1f(program, kLines, o.takesLines() ? 1.0f : 0.0f);
  setCutUniforms(program, {kCutBy, kCutSurfaces, kBackColor, kCutColor}, cutters, cut, i,
                 o.material.color);
  glProgramUniform1i(program, kChannelsBy, cut.cutBy);
}

bool MeshKind::marksRemoval(const ObjectCut& cut, std::size_t i) const {
  return markProgram_.id() != 0 && (cut.cutBy & cut.cutSurfaces & cut.marksBy) != 0 &&
         cut.clipPasses == 0 && !setup_.scene.objects[i].mesh->report.watertight;
}

void MeshKind::drawBackFaces(GLuint back, bool marks, bool unmarked,
                             const std::function<void(GLuint, bool)>& draw) const {
  if (!marks) {
    glCullFace(GL_FRONT);
    draw(back, true);
    return;
  }
  // A value per object, 255 to a clear of the stencil (the geometry pass's first mark clears
  // it too: the pipes' proxy passes leave theirs).
  if (marked_ % 255 == 0) {
    GLint framebuffer = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
    const GLint zero = 0;
    glStencilMask(0xff);
    glClearNamedFramebufferiv(GLuint(framebuffer), GL_STENCIL, 0, &zero);
  }
  const int value = int(marked_++ % 255) + 1;
  glEnable(GL_STENCIL_TEST);
  glStencilMask(0xff);
  glStencilFunc(GL_ALWAYS, value, 0xff);
  glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glDepthMask(GL_FALSE);
  glCullFace(GL_BACK);
  draw(markProgram_.id(), true);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  // No stencil writes: llvmpipe then tests depth and stencil before the shader (with a
  // writable stencil and a `discard` it shades every fragment, failing or not).
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  glStencilMask(0);
  glCullFace(GL_FRONT);
  glStencilFunc(GL_EQUAL, value, 0xff);
  draw(back, true);
  if (unmarked) {
    glStencilFunc(GL_NOTEQUAL, value, 0xff);
    draw(back, false);
  }
  glStencilMask(0xff);
  glDisable(GL_STENCIL_TEST);
}

void MeshKind::drawGeometry(const std::vector<ActiveCutter>& cutters,
                            const GeometryDraw& draw) const {
  marked_ = 0;
  for (const GLuint program : {frontProgram_.id(), backProgram_.id(), markProgram_.id()})
    if (program != 0)
      for (const ActiveCutter& c : cutters) c.cutter->setProgramUniforms(program);
  const std::vector<ObjectCut> cuts = objectCuts(cutters);
  int clipPasses = 0;  // the most any object needs
  for (const ObjectCut& cut : cuts) clipPasses = std::max(clipPasses, cut.clipPasses);
  // Draws object i. One no cutter cuts or clips takes the program without the cutters' code. A
  // cut opens the inside, whose back faces show (Burns08 §4.1): a cut object is drawn twice, its
  // front faces and then its back faces, each by a program with the other side's code folded
  // away (llvmpipe runs both sides of a branch); drawn first, its front faces hide from the
  // depth test the back faces behind them.
  const auto drawObject = [&](const SceneObject& o, std::size_t i,
                              const SceneMeshes::DrawWith& drawWith,
                              const std::function<void(GLuint)>& perProgram) {
    if (cuts[i].cutBy == 0 && cuts[i].clipPasses == 0) {
      setObjectUniforms(uncutProgram_.id(), cutters, cuts[i], o, i);
      perProgram(uncutProgram_.id());
      if (o.doubleSided())
        glDisable(GL_CULL_FACE);
      else
        glEnable(GL_CULL_FACE);
      glCullFace(GL_BACK);
      drawWith(uncutProgram_.id());
      return;
    }
    const ActiveCutter* slabCutter = nullptr;
    std::optional<Cutter::Slab> slab;
    for (const ActiveCutter& c : cutters)
      if (!slab && cuts[i].clipPasses == 0 && (cuts[i].cutBy & (1 << c.slot)) != 0)
        if ((slab = c.cutter->slab(i))) slabCutter = &c;
    const bool marks = marksRemoval(cuts[i], i);
    // Off its marks an open mesh's back faces show without the marking cutters' cut surfaces:
    // where it is double-sided, or where another cutter may make them its cut surface.
    const int unmarkedCutSurfaces = cuts[i].cutSurfaces & ~cuts[i].marksBy;
    const bool unmarked = o.doubleSided() || (cuts[i].cutBy & unmarkedCutSurfaces) != 0;
    if (!slab) {
      const auto drawBy = [&](GLuint program, bool cutSurfaces) {
        setObjectUniforms(program, cutters, cuts[i], o, i);
        if (program == markProgram_.id())
          glProgramUniform1i(program, kCutBy, cuts[i].cutBy & cuts[i].marksBy);
        if (!cutSurfaces) glProgramUniform1i(program, kCutSurfaces, unmarkedCutSurfaces);
        perProgram(program);
        drawWith(program);
      };
      glEnable(GL_CULL_FACE);
      glCullFace(GL_BACK);
      drawBy(frontProgram_.id(), true);
      drawBackFaces(backProgram_.id(), marks, unmarked, drawBy);
      return;
    }
    // Each side split by hardware clip distances: each half-space the cutter keeps whole by
    // the program of the other cutters (none: the slab-kept one), clipped off those before it;
    // then the rest by the cutter's program, reaching `overlap` into each kept half-space so
    // that their common edges leave no crack; the part it removes whole is drawn by neither.
    // The cutters' channels keep the whole cut's values throughout.
    const int rest = cuts[i].cutBy & ~(1 << slabCutter->slot);
    const auto drawPart = [&](GLuint program, int cutBy, const std::vector<glm::vec4>& planes,
                              bool cutSurfaces = true) {
      setObjectUniforms(program, cutters, cuts[i], o, i);
      glProgramUniform1i(program, kCutBy, cutBy);
      if (!cutSurfaces) glProgramUniform1i(program, kCutSurfaces, unmarkedCutSurfaces);
      glm::vec4 clip[kSlabClipPlanes];
      for (int k = 0; k < kSlabClipPlanes; ++k)
        clip[k] = k < int(planes.size()) ? planes[std::size_t(k)] : glm::vec4(0, 0, 0, 1);
      glProgramUniform4fv(program, kSlabClip, kSlabClipPlanes, &clip[0][0]);
      drawWith(program);
    };
    const GLuint kept = rest != 0               ? 0
                        : slabKeptProgram_.id() ? slabKeptProgram_.id()
                                                : uncutProgram_.id();
    for (int k = 1; k <= kSlabClipPlanes; ++k) glEnable(GLenum(GL_CLIP_DISTANCE0 + k));
    glEnable(GL_CULL_FACE);
    for (const auto& [culled, program] :
         {std::pair{GL_BACK, frontProgram_.id()}, std::pair{GL_FRONT, backProgram_.id()}}) {
      glCullFace(culled);
      if (culled == GL_FRONT && (marks || !slab->backFaces)) {
        drawBackFaces(program, marks, unmarked, [&](GLuint p, bool cutSurfaces) {
          const int marking = cuts[i].cutBy & cuts[i].marksBy;
          drawPart(p, p == markProgram_.id() ? marking : cuts[i].cutBy, {}, cutSurfaces);
        });
        continue;
      }
      std::vector<glm::vec4> outside;  // the kept half-spaces drawn so far, turned and grown
      for (const glm::vec4& k : slab->kept) {
        std::vector<glm::vec4> part = outside;
        part.push_back(k);
        drawPart(kept ? kept : program, rest, part);
        outside.push_back(-k + glm::vec4(0, 0, 0, slab->overlap));
      }
      outside.push_back(slab->removed);
      drawPart(program, cuts[i].cutBy, outside);
    }
    // Mesa 22.3's llvmpipe clips by stale distances with clipping disabled (below).
    glm::vec4 none[kSlabClipPlanes];
    std::fill(std::begin(none), std::end(none), glm::vec4(0, 0, 0, 1));
    for (const GLuint program : {uncutProgram_.id(), slabKeptProgram_.id(), frontProgram_.id(),
                                 backProgram_.id(), markProgram_.id()})
      if (program != 0) glProgramUniform4fv(program, kSlabClip, kSlabClipPlanes, &none[0][0]);
    for (int k = 1; k <= kSlabClipPlanes; ++k) glDisable(GLenum(GL_CLIP_DISTANCE0 + k));
  };
  const auto noMore = [](GLuint) {};
  // The objects of `batch` (frame/occlusion_culling.hpp), in the order below.
  auto drawBatch = [&](const OcclusionCulling::Batch& batch) {
    // Secondary objects first, cut; then the objects of interest, whole (Burns08 §4.1).
    setup_.meshes.forEach(
        [&](const SceneObject& o, std::size_t i) {
          return !o.proxy && o.role != Role::Interest && cuts[i].clipPasses == 0 && batch(i);
        },
        [&](const SceneObject& o, std::size_t i, const SceneMeshes::DrawWith& drawWith) {
          drawObject(o, i, drawWith, noMore);
        });
    if (clipPasses > 0) {
      // Diepstraten03 §4.3: each pass keeps the far side of one plane; their union is the
      // object outside the cut.
      glEnable(GL_CLIP_DISTANCE0);
      for (int k = 0; k < clipPasses; ++k)
        setup_.meshes.forEach(
            [&](const SceneObject& o, std::size_t i) {
              return !o.proxy && cuts[i].clipPasses > k && batch(i);
            },
            [&](const SceneObject& o, std::size_t i, const SceneMeshes::DrawWith& drawWith) {
              glm::vec4 keep(0, 0, 0, -1);
              for (const ActiveCutter& c : cutters)
                if (k < c.cutter->clipPasses(i)) keep = c.cutter->clipPlane(i, k);
              drawObject(o, i, drawWith, [&](GLuint program) {
                glProgramUniform4fv(program, kClipPlane, 1, &keep[0]);
              });
            });
      glDisable(GL_CLIP_DISTANCE0);
      // A plane that keeps everything: Mesa 22.3's llvmpipe went on clipping the next frame's
      // objects of interest with the last object's plane, clipping disabled or not.
      const glm::vec4 keepAll(0, 0, 0, 1);
      for (const GLuint program : {frontProgram_.id(), backProgram_.id(), markProgram_.id()})
        if (program != 0) glProgramUniform4fv(program, kClipPlane, 1, &keepAll[0]);
    }
    setup_.meshes.forEach(
        [&](const SceneObject& o, std::size_t i) {
          return !o.proxy && o.role == Role::Interest && cuts[i].clipPasses == 0 && batch(i);
        },
        [&](const SceneObject& o, std::size_t i, const SceneMeshes::DrawWith& drawWith) {
          drawObject(o, i, drawWith, noMore);
        });
  };
  culling_->draw([this](std::size_t i) { return !setup_.scene.objects[i].proxy; }, draw.time,
                 drawBatch);
  glCullFace(GL_BACK);
  glDisable(GL_CULL_FACE);
}

void MeshKind::drawTranslucentLayer(const std::vector<ActiveCutter>& cutters, const GeometryDraw&,
                                    bool first) const {
  const GLuint front = layerFrontProgram_.id(), back = layerBackProgram_.id();
  // The cuts and the cutters' program uniforms are the frame's: set once, at the first layer.
  if (first) {
    for (const GLuint program : {front, back})
      for (const ActiveCutter& c : cutters) c.cutter->setProgramUniforms(program);
    layerCuts_ = objectCuts(cutters);
    layerGrading_ = 0;
    for (const ActiveCutter& c : cutters)
      if (c.cutter->translucentLayers() > 0) layerGrading_ |= 1 << c.slot;
    peeled_.assign(setup_.scene.objects.size(), false);
    peeledDraws_ = 0;
  } else {
    peeledDraws_ += std::size_t(std::count(peeled_.begin(), peeled_.end(), true));
  }
  for (const GLuint program : {front, back})
    glProgramUniform1i(program, kFirstLayer, first ? 1 : 0);
  // As the geometry pass's cut objects: front faces, then back faces.
  setup_.meshes.forEach(
      [&](const SceneObject&, std::size_t i) { return inLayers(i); },
      [&](const SceneObject& o, std::size_t i, const SceneMeshes::DrawWith& drawWith) {
        drawSides(front, back, drawWith, [&](GLuint program) {
          setObjectUniforms(program, cutters, layerCuts_[i], o, i);
        });
      });
  glCullFace(GL_BACK);
  glDisable(GL_CULL_FACE);
}

bool MeshKind::inLayers(std::size_t i) const {
  // One the geometry pass culled lies wholly behind the opaque depth the layers test.
  return !setup_.scene.objects[i].proxy && (layerCuts_[i].cutBy & layerGrading_) != 0 &&
         layerCuts_[i].clipPasses == 0 && !culling_->hidden(i) && !peeled_[i];
}

void MeshKind::skipPeeled(const std::vector<ActiveCutter>& cutters, const GeometryDraw& draw,
                          Target ids) const {
  // Every fragment of an object whose box's far side lies at or in front of the previous
  // layer's depth wherever that layer found a surface is peeled (mesh.frag's test), in this
  // layer and the later ones: where it found none, no layer after it finds one. Not so for the
  // objects a cutter moves back (CUT_WRITES_DEPTH): their depth may leave the box.
  int movesBack = 0;
  for (const ActiveCutter& c : cutters)
    if (c.cutter->cutSurfaceBehind()) movesBack |= 1 << c.slot;
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < setup_.scene.objects.size(); ++i)
    if (inLayers(i) && (layerCuts_[i].cutBy & movesBack) == 0) candidates.push_back(i);
  const std::vector<bool> behind =
      culling_->mayReachBehind(candidates, draw.time, setup_.frame.texture(ids));
  for (const std::size_t i : candidates) peeled_[i] = !behind[i];
}

}  // namespace cutaway
