#include "kinds/volumes/volume_lines_pass.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>

#include "cutaway/kinds/volume_ray_cast.hpp"
#include "kinds/volumes/volume_blocks.hpp"

namespace cutaway {

namespace {
// Uniform locations of volume_line_surfaces.frag, volume_line.* and volume_line_segment_fate.*.
constexpr GLint kStep = 2, kCutBy = 9, kInterest = 10, kIsoCount = 20, kIsoValues = 21,
                kTolerance = 22, kHalo = 23, kHaloColor = 24, kHidden = 25, kDimmedOpacity = 26,
                kExtra = 30, kDepthPush = 31, kFateWidth = 32, kFateSize = 33, kFirstSegment = 34;
constexpr int kFateTexels = 1024;  // the fate target's width

// The families of a style: per isovalue its contours and suggestive contours, then per plane.
bool sameFamilies(const VolumeLineStyle& a, const VolumeLineStyle& b) {
  return a.isoValues.size() == b.isoValues.size() && a.contours == b.contours &&
         a.suggestive == b.suggestive && a.planes.size() == b.planes.size();
}
}  // namespace

VolumeLinesPass::VolumeLinesPass(FrameSetup& setup,
                                 std::function<void(GLuint, std::size_t)> bindVolume)
    : setup_(setup), bindVolume_(std::move(bindVolume)) {
  for (std::size_t i = 0; i < setup.scene.volumes.size(); ++i) {
    if (!setup.scene.volumes[i].lines) continue;
    lines_.push_back({.volume = i});
    const BlockRanges blocks = blockRanges(*setup.scene.volumes[i].volume);
    gl::Texture& t = lines_.back().blocks = gl::Texture::create(GL_TEXTURE_3D);
    glTextureStorage3D(t.id(), 1, GL_RG32F, blocks.grid.x, blocks.grid.y, blocks.grid.z);
    glTextureSubImage3D(t.id(), 0, 0, 0, 0, blocks.grid.x, blocks.grid.y, blocks.grid.z, GL_RG,
                        GL_FLOAT, blocks.range.data());
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  surfaces_ = setup.frame.declare(
      "volumeLineSurfaceDepth",
      {.format = GL_R32F,
       .meaning = "linear view depth (world units) of the nearest crossing of a volume's line "
                  "isovalues that the cutters keep, or of the opaque surfaces; 1e30 where none. "
                  "A line point deeper than it by more than two voxels is hidden"});
  coverage_ = setup.frame.declare(
      "volumeLineCoverage",
      {.format = GL_R32F, .meaning = "coverage in [0, 1] of the volumes' drawn lines (halos not)"});
  depth_ = setup.frame.declare("volumeLineDepth", {.format = GL_DEPTH_COMPONENT32F});
}

bool VolumeLinesPass::present(const Scene& scene) {
  return std::any_of(scene.volumes.begin(), scene.volumes.end(),
                     [](const SceneVolume& v) { return v.lines.has_value(); });
}

GLuint VolumeLinesPass::surfaceProgram(const SceneVolume& v) const {
  const bool twoD = v.transfer.twoDimensional();
  gl::Program& p = surfacePrograms_[int(twoD)];
  if (!p.id()) {
    const std::map<std::string, std::string> defines =
        twoD ? std::map<std::string, std::string>{{"TRANSFER_2D", "1"}}
             : std::map<std::string, std::string>{};
    p = gl::buildProgram(
        setup_.geometryProgram({{GL_VERTEX_SHADER, "frame/fullscreen.vert"},
                                {GL_FRAGMENT_SHADER, "kinds/volumes/volume_line_surfaces.frag"}},
                               defines));
  }
  return p.id();
}

void VolumeLinesPass::prepare(const std::vector<ActiveCutter>& cutters) {
  cutters_ = &cutters;
  for (const Lines& l : lines_) surfaceProgram(setup_.scene.volumes[l.volume]);
  lineProgram_ =
      setup_.bindings.build({.stages = {{GL_VERTEX_SHADER, "kinds/volumes/volume_line.vert"},
                                        {GL_GEOMETRY_SHADER, "kinds/volumes/volume_line.geom"},
                                        {GL_FRAGMENT_SHADER, "kinds/volumes/volume_line.frag"}}});
  fateProgram_ = gl::buildProgram(setup_.geometryProgram(
      {{GL_VERTEX_SHADER, "kinds/volumes/volume_line_segment_fate.vert"},
       {GL_FRAGMENT_SHADER, "kinds/volumes/volume_line_segment_fate.frag"}}));
  vertexArray_ = gl::VertexArray::create();
  const GLuint vao = vertexArray_.id();
  glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(Segment, position));
  glVertexArrayAttribFormat(vao, 1, 4, GL_FLOAT, GL_FALSE, offsetof(Segment, pen));
  glVertexArrayAttribFormat(vao, 2, 1, GL_FLOAT, GL_FALSE, offsetof(Segment, importance));
  for (GLuint a = 0; a < 3; ++a)
    glEnableVertexArrayAttrib(vao, a), glVertexArrayAttribBinding(vao, a, 0);
  middleArray_ = gl::VertexArray::create();
  const GLuint middles = middleArray_.id();
  glVertexArrayAttribFormat(middles, 0, 3, GL_FLOAT, GL_FALSE, offsetof(Segment, position));
  glVertexArrayAttribFormat(middles, 2, 1, GL_FLOAT, GL_FALSE, offsetof(Segment, importance));
  for (GLuint a : {0u, 2u})
    glEnableVertexArrayAttrib(middles, a), glVertexArrayAttribBinding(middles, a, 0);
}

void VolumeLinesPass::addPasses(Frame& frame) {
  frame.addPass({.name = "volumeLineSurfaces",
                 .reads = {setup_.gbuffer.depth()},
                 .writes = {surfaces_},
                 .run = [this](const PassContext&) { drawSurfaces(); }});
  frame.addPass({.name = "volumeLines",
                 .reads = {surfaces_},
                 .writes = {setup_.gbuffer.finalColor(), coverage_, depth_},
                 .run = [this](const PassContext& pass) { drawLines(pass); }});
}

glm::vec4 VolumeLinesPass::pen(const Lines& lines, const Family& f, VolumeLineKind kind) const {
  const VolumeLineStyle& s = *setup_.scene.volumes[lines.volume].lines;
  switch (kind) {
    case VolumeLineKind::Contour: {
      const VolumeLineIso& iso = s.isoValues[f.iso];
      return {iso.color, iso.width};
    }
    case VolumeLineKind::InteriorContour:
      return {s.interiorContour.color, s.interiorContour.width};
    case VolumeLineKind::SuggestiveContour:
      return {s.suggestiveContour.color, s.suggestiveContour.width};
    case VolumeLineKind::PlaneCut:
      return {s.planeCut.color, s.planeCut.width};
  }
  return glm::vec4(0.0f);
}

float VolumeLinesPass::importance(const Lines& lines, const Family& f) const {
  const SceneVolume& v = setup_.scene.volumes[lines.volume];
  // A contextual cutter grades a line's points by the importance of its isovalue's material.
  return v.role == Role::Interest ? 1.0f : v.material(f.query.isoValue).importance;
}

void VolumeLinesPass::extract(const Camera& camera) {
  segments_.clear();
  runs_.clear();
  const VolumeLineView view = VolumeLineView::of(camera);
  for (Lines& l : lines_) {
    const SceneVolume& v = setup_.scene.volumes[l.volume];
    const VolumeLineStyle& style = *v.lines;
    // The viewer edits the style between frames: new families restart their walks; values
    // (isovalues, ε, planes) change in place, as in Burns11 Fig. 2.8's changing threshold.
    if (l.families.empty() || !sameFamilies(l.style, style)) {
      l.families.clear();
      for (std::size_t k = 0; k < style.isoValues.size(); ++k) {
        if (style.contours)
          l.families.push_back({.iso = k, .query = {.family = VolumeLineFamily::Contour}});
        if (style.suggestive)
          l.families.push_back({.iso = k, .query = {.family = VolumeLineFamily::Suggestive}});
        for (std::size_t p = 0; p < style.planes.size(); ++p)
          l.families.push_back(
              {.iso = k, .plane = p, .query = {.family = VolumeLineFamily::Plane}});
      }
    }
    l.style = style;
    const std::uint64_t n = std::uint64_t(std::cbrt(double(v.volume->voxelCount())));
    std::size_t held = 0;  // this volume's segments so far, against style.mostSegments
    for (Family& f : l.families) {
      f.query.isoValue = style.isoValues[f.iso].value;
      f.query.epsilon = style.epsilon;
      if (f.query.family == VolumeLineFamily::Plane) {
        const VolumeLinePlane& plane = style.planes[f.plane];
        f.query.plane = glm::vec4(glm::normalize(plane.normal), plane.distance);
      }
      f.query.mostSegments =
          std::size_t(style.mostSegments) - std::min(held, std::size_t(style.mostSegments));
      const VolumeLineField field(*v.volume, v.indexToWorld(), view, f.query);
      if (!style.walk) f.tracker.reset();
      // §2.4.1.3–2.4.1.4: the previous frame's cells, n/4 probes from them and n random
      // probes (n³ ≈ the voxel count); a first frame is brute force.
      VolumeLineSet set;
      try {
        set = f.tracker.extract(field, {.probesFromPrevious = int(n / 4), .randomProbes = int(n)});
      } catch (const Error&) {  // the extraction's one error: its budget of segments
        std::ostringstream reason;
        reason << "the lines hold more than " << style.mostSegments
               << " segments (\"mostSegments\"), reached at isovalue " << f.query.isoValue
               << ": noise-like data? Smooth the volume, draw fewer isovalues, or raise it";
        throw Error(setup_.scene.file.string(), "/volumes/" + std::to_string(l.volume) + "/lines",
                    reason.str());
      }
      held += set.segmentCount();
      const float importance = this->importance(l, f);
      for (const VolumeLine& line : set.lines) {
        if (line.points.size() < 2) continue;
        const glm::vec4 p = pen(l, f, line.kind);
        const std::size_t first = segments_.size() / 2;
        const std::size_t count = line.points.size() - (line.closed ? 0 : 1);
        for (std::size_t i = 0; i < count; ++i) {
          segments_.push_back({line.points[i], p, importance});
          segments_.push_back({line.points[(i + 1) % line.points.size()], p, importance});
        }
        runs_.push_back({l.volume, first, count, line.kind, p});
      }
    }
  }
  // The segments, and their middles (where each is decided).
  std::vector<Segment> middles(segments_.size() / 2);
  for (std::size_t i = 0; i < middles.size(); ++i)
    middles[i] = {0.5f * (segments_[2 * i].position + segments_[2 * i + 1].position),
                  segments_[2 * i].pen, segments_[2 * i].importance};
  const std::size_t bytes = segments_.size() * sizeof(Segment);
  if (bytes > vertexCapacity_) {
    vertexCapacity_ = std::max<std::size_t>(bytes * 2, 1 << 16);
    vertices_ = gl::Buffer::create(GLsizeiptr(vertexCapacity_), nullptr, GL_DYNAMIC_STORAGE_BIT);
    middles_ = gl::Buffer::create(GLsizeiptr(vertexCapacity_ / 2), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glVertexArrayVertexBuffer(vertexArray_.id(), 0, vertices_.id(), 0, sizeof(Segment));
    glVertexArrayVertexBuffer(middleArray_.id(), 0, middles_.id(), 0, sizeof(Segment));
  }
  if (bytes) {
    glNamedBufferSubData(vertices_.id(), 0, GLsizeiptr(bytes), segments_.data());
    glNamedBufferSubData(middles_.id(), 0, GLsizeiptr(bytes / 2), middles.data());
  }
}

std::pair<std::size_t, std::size_t> VolumeLinesPass::segmentRange(std::size_t volume) const {
  // A volume's runs are consecutive (extract): one draw for all its segments.
  std::size_t first = segments_.size() / 2, last = first;
  for (const Run& r : runs_)
    if (r.volume == volume) first = std::min(first, r.first), last = r.first + r.count;
  return {first, last > first ? last - first : 0};
}

void VolumeLinesPass::beginFrame(const FrameState& state) {
  view_ = state.uniforms.view;
  viewProjection_ = state.uniforms.viewProjection;
  extract(state.camera);
}

void VolumeLinesPass::setCommonUniforms(GLuint program, std::size_t volume) const {
  glUseProgram(program);
  int cutBy = 0;
  for (const ActiveCutter& c : *cutters_) {
    c.cutter->setProgramUniforms(program);
    if (c.cutter->cutsVolume(volume)) {
      cutBy |= 1 << c.slot;
      c.cutter->setVolumeUniforms(program, volume);
    }
  }
  glProgramUniform1i(program, kCutBy, cutBy);
  glProgramUniform1i(program, kInterest, setup_.scene.volumes[volume].role == Role::Interest);
}

void VolumeLinesPass::drawSurfaces() const {
  const float none = 1e30f;
  glClearTexImage(setup_.frame.texture(surfaces_).id(), 0, GL_RED, GL_FLOAT, &none);
  setup_.bindShading();
  glBindTextureUnit(0, setup_.frame.texture(setup_.gbuffer.depth()).id());
  glDisable(GL_DEPTH_TEST);
  glEnablei(GL_BLEND, 0);  // the nearest over the volumes with lines
  glBlendEquationi(0, GL_MIN);
  for (const Lines& l : lines_) {
    const SceneVolume& v = setup_.scene.volumes[l.volume];
    const GLuint program = surfaceProgram(v);
    setCommonUniforms(program, l.volume);
    bindVolume_(program, l.volume);
    glProgramUniform1f(program, kStep, v.sampleDistance * smallestVoxelSpacing(v));
    std::vector<float> iso;
    for (const VolumeLineIso& i : v.lines->isoValues) iso.push_back(i.value);
    glProgramUniform1i(program, kIsoCount, GLint(iso.size()));
    glProgramUniform1fv(program, kIsoValues, GLsizei(iso.size()), iso.data());
    glBindTextureUnit(7, l.blocks.id());
    fullscreen_.draw();
  }
  glBlendEquationi(0, GL_FUNC_ADD);
  glDisablei(GL_BLEND, 0);
}

// Each segment's fate, decided once at its middle, into fates_ (a texel per segment).
void VolumeLinesPass::decideSegments(const PassContext& pass) const {
  const std::size_t count = segments_.size() / 2;
  const int rows = int((count + kFateTexels - 1) / kFateTexels);
  if (rows > fateRows_) {
    fateRows_ = std::max(rows, 2 * fateRows_);
    fates_ = gl::Texture::create2D(GL_R32F, kFateTexels, fateRows_);
    fateFramebuffer_ = gl::Framebuffer::create();
    glNamedFramebufferTexture(fateFramebuffer_.id(), GL_COLOR_ATTACHMENT0, fates_.id(), 0);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, fateFramebuffer_.id());
  glViewport(0, 0, kFateTexels, fateRows_);
  glBindVertexArray(middleArray_.id());
  const GLuint program = fateProgram_.id();
  for (const Lines& l : lines_) {
    const auto [first, n] = segmentRange(l.volume);
    if (n == 0) continue;
    const SceneVolume& v = setup_.scene.volumes[l.volume];
    setCommonUniforms(program, l.volume);
    glProgramUniform1f(program, kTolerance, 2.0f * smallestVoxelSpacing(v));
    glProgramUniform1i(program, kFateWidth, kFateTexels);
    glProgramUniform2f(program, kFateSize, float(kFateTexels), float(fateRows_));
    glDrawArrays(GL_POINTS, GLint(first), GLsizei(n));
  }
  glBindFramebuffer(GL_FRAMEBUFFER, pass.framebuffer);
  glViewport(0, 0, pass.width, pass.height);
}

void VolumeLinesPass::drawLines(const PassContext& pass) const {
  const float zero = 0.0f, far = 1.0f;
  glClearTexImage(setup_.frame.texture(coverage_).id(), 0, GL_RED, GL_FLOAT, &zero);
  glClearTexImage(setup_.frame.texture(depth_).id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &far);
  if (runs_.empty()) return;
  setup_.bindShading();
  glBindTextureUnit(5, setup_.frame.texture(surfaces_).id());
  decideSegments(pass);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glEnablei(GL_BLEND, 0);
  glBlendFunci(0, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glEnablei(GL_BLEND, 1);
  glBlendEquationi(1, GL_MAX);
  glBindVertexArray(vertexArray_.id());
  glBindTextureUnit(6, fates_.id());
  const GLuint program = lineProgram_.id();
  glUseProgram(program);
  glProgramUniform1i(program, kFateWidth, kFateTexels);
  // All halos first, pushed back by eight voxels, then all lines: a line passing behind a
  // nearer one fails the depth test where the nearer one's halo lies (Appel et al. 1979).
  for (const bool halo : {true, false}) {
    glDepthFunc(halo ? GL_LESS : GL_LEQUAL);
    if (halo)
      glEnable(GL_POLYGON_OFFSET_FILL);
    else
      glDisable(GL_POLYGON_OFFSET_FILL);
    for (const Lines& l : lines_) {
      const SceneVolume& v = setup_.scene.volumes[l.volume];
      const VolumeLineStyle& s = *v.lines;
      if (halo && !(s.halo > 0.0f)) continue;
      glProgramUniform1i(program, kHidden, int(s.hidden));
      glProgramUniform1f(program, kDimmedOpacity, s.dimmedOpacity);
      glProgramUniform3fv(program, kHaloColor, 1, &s.haloColor[0]);
      glProgramUniform1i(program, kHalo, halo);
      glProgramUniform1f(program, kExtra, halo ? s.halo : 0.0f);
      glProgramUniform1f(program, kDepthPush, halo ? 8.0f * smallestVoxelSpacing(v) : 0.0f);
      // A line running into the view changes depth fast along itself: pushed back by its depth
      // slope over the halo's reach too, a halo does not break its own line.
      if (halo) glPolygonOffset(s.halo + 4.0f, 0.0f);
      const auto [first, count] = segmentRange(l.volume);
      glProgramUniform1i(program, kFirstSegment, GLint(first));
      glDrawArrays(GL_LINES, GLint(2 * first), GLsizei(2 * count));
    }
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
  glBlendEquationi(1, GL_FUNC_ADD);
  glDisablei(GL_BLEND, 1);
  glDisablei(GL_BLEND, 0);
  glDisable(GL_DEPTH_TEST);
}

VolumeLineDrawing VolumeLinesPass::drawing() const {
  VolumeLineDrawing out{setup_.frame.width(), setup_.frame.height(), {}};
  const std::size_t count = segments_.size() / 2;
  if (count == 0) return out;
  // The fates the last frame decided (decideSegments), a texel per segment.
  std::vector<float> fate(std::size_t(kFateTexels) * std::size_t(fateRows_));
  glGetTextureImage(fates_.id(), 0, GL_RED, GL_FLOAT, GLsizei(fate.size() * sizeof(float)),
                    fate.data());

  const auto window = [&](const glm::vec3& p) {
    const glm::vec4 c = viewProjection_ * glm::vec4(p, 1.0f);
    const glm::vec2 ndc = glm::vec2(c) / c.w;
    return glm::vec2((ndc.x * 0.5f + 0.5f) * float(out.width),
                     (0.5f - ndc.y * 0.5f) * float(out.height));
  };
  // As drawn: a segment with an end behind the eye is not (volume_line.geom).
  const auto stateOf = [&](std::size_t k) {
    const auto inFront = [&](const glm::vec3& p) {
      return (viewProjection_ * glm::vec4(p, 1.0f)).w > 0.0f;
    };
    return inFront(segments_[2 * k].position) && inFront(segments_[2 * k + 1].position)
               ? int(std::lround(fate[k]))
               : 0;
  };
  for (const Run& r : runs_) {
    const VolumeLineStyle& s = *setup_.scene.volumes[r.volume].lines;
    for (std::size_t i = r.first; i < r.first + r.count;) {
      const int state = stateOf(i);
      std::size_t j = i;
      while (j < r.first + r.count && stateOf(j) == state) ++j;
      if (state == 2 || (state == 1 && s.hidden != HiddenLines::Removed)) {
        DrawnVolumeLine line{
            .kind = r.kind,
            .color = glm::vec3(r.pen),
            .width = r.pen.w,
            .opacity = state == 1 && s.hidden == HiddenLines::Dimmed ? s.dimmedOpacity : 1.0f,
            .hidden = state == 1,
            .halo = s.halo,
            .haloColor = s.haloColor};
        float depth = 0.0f;
        for (std::size_t k = i; k < j; ++k) {
          const glm::vec3& a = segments_[2 * k].position;
          line.points.push_back(window(a));
          depth -= (view_ * glm::vec4(a, 1.0f)).z;
        }
        line.points.push_back(window(segments_[2 * (j - 1) + 1].position));
        line.depth = depth / float(j - i);
        out.lines.push_back(std::move(line));
      }
      i = j;
    }
  }
  return out;
}

}  // namespace cutaway
