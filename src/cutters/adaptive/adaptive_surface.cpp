// AdaptiveCutawaySurface: the adaptive cutter's surface passes in a frame of their own, seeded
// from the application's depth texture instead of the scene's objects of interest.
#include "cutaway/cutters/adaptive_surface.hpp"

#include <array>
#include <utility>

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

// The application's state compute() changes, saved, set to what the passes need, and put
// back: bindings, viewport, the fixed-function switches a pass relies on being off, the colour
// mask, and the pixel-transfer state the CPU path's read-back and upload go through.
class SavedState {
 public:
  SavedState() {
    for (std::size_t i = 0; i < kBindings.size(); ++i) glGetIntegerv(kBindings[i], &bindings_[i]);
    glGetIntegerv(GL_VIEWPORT, viewport_);
    glGetBooleanv(GL_COLOR_WRITEMASK, colorMask_);
    for (std::size_t i = 0; i < kSwitches.size(); ++i) {
      switches_[i] = glIsEnabled(kSwitches[i]);
      glDisable(kSwitches[i]);
    }
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    for (std::size_t i = 0; i < kPixelStore.size(); ++i) {
      glGetIntegerv(kPixelStore[i].first, &pixelStore_[i]);
      glPixelStorei(kPixelStore[i].first, kPixelStore[i].second);
    }
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  }
  ~SavedState() {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(bindings_[0]));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(bindings_[1]));
    glUseProgram(GLuint(bindings_[2]));
    glBindVertexArray(GLuint(bindings_[3]));
    glBindBuffer(GL_PIXEL_PACK_BUFFER, GLuint(bindings_[4]));
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, GLuint(bindings_[5]));
    glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
    glColorMask(colorMask_[0], colorMask_[1], colorMask_[2], colorMask_[3]);
    for (std::size_t i = 0; i < kSwitches.size(); ++i)
      if (switches_[i]) glEnable(kSwitches[i]);
    for (std::size_t i = 0; i < kPixelStore.size(); ++i)
      glPixelStorei(kPixelStore[i].first, pixelStore_[i]);
  }
  SavedState(const SavedState&) = delete;
  SavedState& operator=(const SavedState&) = delete;

 private:
  // In the order the destructor binds them back.
  static constexpr std::array<GLenum, 6> kBindings{
      GL_DRAW_FRAMEBUFFER_BINDING, GL_READ_FRAMEBUFFER_BINDING,  GL_CURRENT_PROGRAM,
      GL_VERTEX_ARRAY_BINDING,     GL_PIXEL_PACK_BUFFER_BINDING, GL_PIXEL_UNPACK_BUFFER_BINDING};
  static constexpr std::array<GLenum, 6> kSwitches{GL_DEPTH_TEST, GL_BLEND, GL_SCISSOR_TEST,
                                                   GL_STENCIL_TEST, GL_CULL_FACE,
                                                   GL_RASTERIZER_DISCARD};
  // With the values the passes need (OpenGL's defaults).
  static constexpr std::array<std::pair<GLenum, GLint>, 8> kPixelStore{{
      {GL_PACK_ALIGNMENT, 4},   {GL_UNPACK_ALIGNMENT, 4},   {GL_PACK_ROW_LENGTH, 0},
      {GL_UNPACK_ROW_LENGTH, 0}, {GL_PACK_SKIP_ROWS, 0},    {GL_UNPACK_SKIP_ROWS, 0},
      {GL_PACK_SKIP_PIXELS, 0}, {GL_UNPACK_SKIP_PIXELS, 0}}};
  GLint bindings_[kBindings.size()], viewport_[4], pixelStore_[kPixelStore.size()];
  GLboolean colorMask_[4], switches_[kSwitches.size()];
};

}  // namespace

struct AdaptiveCutawaySurface::Impl {
  explicit Impl(const AdaptiveCutawayOptions& o)
      : device(gl::ContextInfo::query()),
        options(checked(o)),
        variant(o.variant),
        compute(o.compute),
        frame(o.bufferSize, o.bufferSize, device),
        surface(frame, o.bufferSize, o.variant, cutawayOnCpu(o, device.software),
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
    surface.addPasses();
    frame.setTimed(false);  // the application may be timing this frame itself
  }

  gl::ContextInfo device;
  AdaptiveCutawayOptions options;
  const fields::JumpFloodingVariant variant;
  const AdaptiveCutawayOptions::Compute compute;
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
  // Fixed at construction.
  g.options.bufferSize = g.surface.bufferSize();
  g.options.variant = g.variant;
  g.options.compute = g.compute;
  adaptiveCutawaySchema().checkRanges(&g.options, "AdaptiveCutawaySurface");
  const SavedState saved;
  g.interestDepth = interestDepth;
  g.interestAngle = interestAngle;
  // An orthographic projection keeps w (its last row is 0 0 0 1): no z in clip w.
  g.surface.setCamera({projection, glm::mat3(view), projection[2][3] == 0.0f});
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
