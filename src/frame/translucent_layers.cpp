#include "frame/translucent_layers.hpp"

namespace cutaway {

TranslucentLayers::TranslucentLayers(Frame& frame, Bindings& bindings, const GBuffer& gbuffer,
                                     std::function<int()> maxLayers)
    : frame_(frame),
      gbuffer_(gbuffer),
      maxLayers_(std::move(maxLayers)),
      peelDepthUnit_(bindings.textureUnit("PEEL_DEPTH")),
      layerFramebuffer_(gl::Framebuffer::create()),
      accumulationFramebuffer_(gl::Framebuffer::create()),
      underProgram_(buildFullscreenProgram("frame/layer_under.frag")),
      overProgram_(buildFullscreenProgram("frame/layer_over.frag")),
      anySamples_(gl::Query::create(GL_ANY_SAMPLES_PASSED)) {
  const int samples = gbuffer.samples();
  // Premultiplied colour and coverage; half floats keep 8-bit colours exact through the
  // blending.
  accumulation_ = frame.declare("translucentAccumulation", {.format = GL_RGBA16F, .samples = samples});
  layerColor_ = frame.declare("translucentLayer", {.format = GL_RGBA16F, .samples = samples});
  const GLenum depthFormat = frame.desc(gbuffer.depth()).format;  // copied from the opaque depth
  layerDepth_ = frame.declare("translucentLayerDepth", {.format = depthFormat, .samples = samples});
  previousDepth_ = frame.declare("translucentPreviousDepth", {.format = depthFormat, .samples = samples});
}

void TranslucentLayers::addLayersPass(Frame& frame, std::function<void(bool)> drawLayer) {
  frame.addPass({.name = "translucentLayers",
                 .reads = {gbuffer_.depth()},
                 .writes = {accumulation_, layerColor_, layerDepth_},
                 .run = [this, drawLayer = std::move(drawLayer)](const PassContext&) {
                   peel(drawLayer);
                 }});
}

void TranslucentLayers::peel(const std::function<void(bool)>& drawLayer) {
  const auto id = [this](Target t) { return frame_.texture(t).id(); };
  if (glCheckNamedFramebufferStatus(layerFramebuffer_.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    glNamedFramebufferTexture(layerFramebuffer_.id(), GL_COLOR_ATTACHMENT0, id(layerColor_), 0);
    const GLenum depthFormat = frame_.desc(layerDepth_).format;
    const bool stencil = depthFormat == GL_DEPTH32F_STENCIL8 || depthFormat == GL_DEPTH24_STENCIL8;
    glNamedFramebufferTexture(layerFramebuffer_.id(),
                              stencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT,
                              id(layerDepth_), 0);
    glNamedFramebufferTexture(accumulationFramebuffer_.id(), GL_COLOR_ATTACHMENT0, id(accumulation_), 0);
  }
  const int w = frame_.width(), h = frame_.height();
  const auto copyDepth = [&](Target from, Target to) {
    glCopyImageSubData(id(from), GL_TEXTURE_2D_MULTISAMPLE, 0, 0, 0, 0, id(to),
                       GL_TEXTURE_2D_MULTISAMPLE, 0, 0, 0, 0, w, h, 1);
  };
  const float zero[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(accumulationFramebuffer_.id(), GL_COLOR, 0, zero);
  peeled_ = 0;
  const int budget = maxLayers_();
  for (int k = 0; k < budget; ++k) {
    // The layer behind layer k − 1 and in front of the opaque surfaces: the depth test (LESS)
    // against the opaque depth, the fragment shader's against the previous layer's.
    if (k > 0) copyDepth(layerDepth_, previousDepth_);
    copyDepth(gbuffer_.depth(), layerDepth_);
    glClearNamedFramebufferfv(layerFramebuffer_.id(), GL_COLOR, 0, zero);
    glBindFramebuffer(GL_FRAMEBUFFER, layerFramebuffer_.id());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glBindTextureUnit(peelDepthUnit_, id(previousDepth_));
    glBeginQuery(GL_ANY_SAMPLES_PASSED, anySamples_.id());
    drawLayer(k == 0);
    glEndQuery(GL_ANY_SAMPLES_PASSED);
    GLuint any = 0;
    glGetQueryObjectuiv(anySamples_.id(), GL_QUERY_RESULT, &any);
    ++peeled_;
    if (!any) break;
    // Front to back: the layer goes under what is accumulated (Porter–Duff "under" on
    // premultiplied colour: C += (1 − A) c, A += (1 − A) a).
    glBindFramebuffer(GL_FRAMEBUFFER, accumulationFramebuffer_.id());
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE_MINUS_DST_ALPHA, GL_ONE);
    glUseProgram(underProgram_.id());
    glBindTextureUnit(0, id(layerColor_));
    fullscreen_.draw();
    glDisable(GL_BLEND);
  }
}

void TranslucentLayers::addCompositePass(Frame& frame, Target finalColor) {
  frame.addPass({.name = "translucentComposite",
                 .reads = {accumulation_},
                 .writes = {finalColor},
                 .run = [this](const PassContext&) {
                   glDisable(GL_DEPTH_TEST);
                   glEnable(GL_BLEND);
                   glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // "over" the final colour
                   glUseProgram(overProgram_.id());
                   glBindTextureUnit(0, frame_.texture(accumulation_).id());
                   glProgramUniform1i(overProgram_.id(), 0, gbuffer_.samples());
                   fullscreen_.draw();
                   glDisable(GL_BLEND);
                 }});
}

}  // namespace cutaway
