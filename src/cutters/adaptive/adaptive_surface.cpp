// AdaptiveCutawaySurface: the adaptive cutter's surface passes in a frame of their own, seeded
// from the application's depth texture instead of the scene's objects of interest.
#include "cutaway/cutters/adaptive_surface.hpp"

#include "cutaway/gl/context.hpp"
#include "cutters/adaptive/surface_passes.hpp"
#include "frame/fullscreen.hpp"

namespace cutaway {

namespace {

// The fixed options checked, and the compute path decided, before any target exists.
AdaptiveCutawayOptions checked(const AdaptiveCutawayOptions& options) {
  adaptiveCutawaySchema().checkRanges(&options, "AdaptiveCutawaySurface");
  return options;
}

// What compute() leaves as it found it.
struct SavedState {
  GLint framebuffer, program, vertexArray, viewport[4];
  GLboolean depthTest;
  SavedState() {
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
    glGetIntegerv(GL_CURRENT_PROGRAM, &program);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertexArray);
    glGetIntegerv(GL_VIEWPORT, viewport);
    depthTest = glIsEnabled(GL_DEPTH_TEST);
  }
  ~SavedState() {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(framebuffer));
    glUseProgram(GLuint(program));
    glBindVertexArray(GLuint(vertexArray));
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    if (depthTest) glEnable(GL_DEPTH_TEST);
    else glDisable(GL_DEPTH_TEST);
  }
};

}  // namespace

struct AdaptiveCutawaySurface::Impl {
  explicit Impl(const AdaptiveCutawayOptions& o)
      : software(gl::ContextInfo::query().software),
        options(checked(o)),
        frame(o.bufferSize, o.bufferSize, software),
        surface(frame, o.bufferSize, o.variant, cutawayOnCpu(o, software),
                [this]() -> const AdaptiveCutawayOptions& { return options; }),
        import(buildFullscreenProgram("cutters/adaptive/seed_import.frag")) {
    frame.addPass({.name = "cutawaySeedImport",
                   .writes = {surface.seedDepth(), surface.seedAngle()},
                   .run = [this](const PassContext&) {
                     const GLuint program = import.id();
                     glUseProgram(program);
                     glDisable(GL_DEPTH_TEST);
                     glBindTextureUnit(0, interestDepth);
                     glBindTextureUnit(1, interestAngle);
                     glProgramUniform1i(program, 0, interestAngle != 0);
                     glProgramUniform1f(program, 1, glm::radians(options.angle));
                     glProgramUniform1i(program, 2, frame.width());
                     fullscreen.draw();
                   }});
    surface.addPasses(frame);
  }

  bool software;
  AdaptiveCutawayOptions options;
  Frame frame;
  CutawaySurfacePasses surface;
  gl::Program import;
  FullscreenTriangle fullscreen;
  GLuint interestDepth = 0, interestAngle = 0;  // of the frame being computed
};

AdaptiveCutawaySurface::AdaptiveCutawaySurface(const AdaptiveCutawayOptions& options)
    : impl_(std::make_unique<Impl>(options)) {}

AdaptiveCutawaySurface::~AdaptiveCutawaySurface() = default;

GLuint AdaptiveCutawaySurface::compute(GLuint interestDepth, const glm::mat4& projection,
                                       const glm::mat4& view, GLuint interestAngle) {
  Impl& g = *impl_;
  g.options.bufferSize = g.surface.bufferSize();  // fixed at construction
  adaptiveCutawaySchema().checkRanges(&g.options, "AdaptiveCutawaySurface");
  const SavedState saved;
  g.interestDepth = interestDepth;
  g.interestAngle = interestAngle;
  // An orthographic projection keeps w = 1 (its last row is 0 0 0 1).
  g.surface.setCamera({projection, glm::mat3(view), projection[3][3] == 1.0f});
  g.frame.execute();
  return cutawayTexture();
}

GLuint AdaptiveCutawaySurface::cutawayTexture() const {
  return impl_->frame.texture(impl_->surface.cutawayDepth()).id();
}

GLuint AdaptiveCutawaySurface::dilatedTexture() const {
  return impl_->frame.texture(impl_->surface.cutawayDilated()).id();
}

GLuint AdaptiveCutawaySurface::seedTexture() const {
  return impl_->frame.texture(impl_->surface.seedDepth()).id();
}

int AdaptiveCutawaySurface::bufferSize() const {
  return impl_->surface.bufferSize();
}

const char* AdaptiveCutawaySurface::computePath() const {
  return impl_->surface.onCpu() ? "cpu" : "gpu";
}

AdaptiveCutawayOptions& AdaptiveCutawaySurface::options() {
  return impl_->options;
}

}  // namespace cutaway
