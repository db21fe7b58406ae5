#include "frame/translucent_layers.hpp"

#include "frame/samples.hpp"

namespace cutaway {

TranslucentLayers::TranslucentLayers(Frame& frame, Bindings& bindings, const GBuffer& gbuffer,
                                     std::function<int()> maxLayers)
    : frame_(frame),
      gbuffer_(gbuffer),
      maxLayers_(std::move(maxLayers)),
      peelDepthUnit_(bindings.textureUnit("PEEL_DEPTH")),
      layerFramebuffer_(gl::Framebuffer::create()),
      accumulationFramebuffer_(gl::Framebuffer::create()),
      linesFramebuffer_(gl::Framebuffer::create()),
      underProgram_(
          buildFullscreenProgram("frame/layer_under.frag", sampleDefines(gbuffer.samples()))),
      overProgram_(
          buildFullscreenProgram("frame/layer_over.frag", sampleDefines(gbuffer.samples()))),
      anySamples_(gl::Query::create(GL_ANY_SAMPLES_PASSED)) {
  const int samples = gbuffer.samples();
  // Premultiplied colour and coverage; half floats keep 8-bit colours exact through the
  // blending. The layer's other buffers as the G-buffer's (frame/gbuffer.glsl).
  accumulation_ =
      frame.declare("translucentAccumulation", {.format = GL_RGBA16F, .samples = samples});
  layer_.color = frame.declare("translucentLayer", {.format = GL_RGBA16F, .samples = samples});
  layer_.normal = frame.declare("translucentLayerNormal", {.format = GL_R32UI, .samples = samples});
  layer_.objectId =
      frame.declare("translucentLayerObjectId", {.format = GL_RG32I, .samples = samples});
  lineCoverage_ = frame.declare("translucentLayerLines", {.format = GL_R16F});
  linePixels_ = frame.declare("translucentLayerLinePixels", {.format = GL_DEPTH_COMPONENT16});
  const GLenum depthFormat = frame.desc(gbuffer.depth()).format;  // copied from the opaque depth
  layerDepth_ = frame.declare("translucentLayerDepth", {.format = depthFormat, .samples = samples});
  previousDepth_ =
      frame.declare("translucentPreviousDepth", {.format = depthFormat, .samples = samples});
  attach();
}

void TranslucentLayers::addLayersPass(Frame& frame, LayerDraw drawLayer, Lines lines) {
  frame.addPass(
      {.name = "translucentLayers",
       .reads = {gbuffer_.depth()},
       .writes = {accumulation_, layer_.color, layer_.normal, layer_.objectId, layerDepth_},
       .run = [this, drawLayer = std::move(drawLayer),
               lines = std::move(lines)](const PassContext&) { peel(drawLayer, lines); }});
}

void TranslucentLayers::attach() {
  const auto id = [this](Target t) { return frame_.texture(t).id(); };
  const GLuint layer = layerFramebuffer_.id();
  // At the G-buffer's locations (frame/gbuffer.glsl); the cut mask (3) is not kept.
  const Target colors[3] = {layer_.color, layer_.normal, layer_.objectId};
  GLenum buffers[3];
  for (int i = 0; i < 3; ++i) {
    buffers[i] = colors[i].valid() ? GL_COLOR_ATTACHMENT0 + GLenum(i) : GL_NONE;
    if (colors[i].valid()) glNamedFramebufferTexture(layer, buffers[i], id(colors[i]), 0);
  }
  glNamedFramebufferDrawBuffers(layer, 3, buffers);
  const GLenum depthFormat = frame_.desc(layerDepth_).format;
  const bool stencil = depthFormat == GL_DEPTH32F_STENCIL8 || depthFormat == GL_DEPTH24_STENCIL8;
  glNamedFramebufferTexture(layer, stencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT,
                            id(layerDepth_), 0);
  glNamedFramebufferTexture(accumulationFramebuffer_.id(), GL_COLOR_ATTACHMENT0, id(accumulation_),
                            0);
  glNamedFramebufferTexture(linesFramebuffer_.id(), GL_COLOR_ATTACHMENT0, id(lineCoverage_), 0);
  glNamedFramebufferTexture(linesFramebuffer_.id(), GL_DEPTH_ATTACHMENT, id(linePixels_), 0);
}

void TranslucentLayers::peel(const LayerDraw& drawLayer, const Lines& lines) {
  const auto id = [this](Target t) { return frame_.texture(t).id(); };
  const int w = frame_.width(), h = frame_.height();
  const auto copyDepth = [&](Target from, Target to) {
    const GLenum target = frame_.desc(from).textureTarget();
    glCopyImageSubData(id(from), target, 0, 0, 0, 0, id(to), target, 0, 0, 0, 0, w, h, 1);
  };
  const float zero[4] = {0, 0, 0, 0};
  const GLuint noWeight[4] = {0, 0, 0, 0};
  const GLint noObject[4] = {-1, 0, 0, 0};
  glClearNamedFramebufferfv(accumulationFramebuffer_.id(), GL_COLOR, 0, zero);
  glClearNamedFramebufferfv(linesFramebuffer_.id(), GL_COLOR, 0, zero);
  const std::optional<glm::vec3> lineColor = lines.color();
  peeled_ = 0;
  const int budget = maxLayers_();
  for (int k = 0; k < budget; ++k) {
    // The layer behind layer k − 1 and in front of the opaque surfaces: the depth test (LESS)
    // against the opaque depth, the fragment shader's against the previous layer's.
    const GLuint layer = layerFramebuffer_.id();
    if (k > 0) {
      copyDepth(layerDepth_, previousDepth_);
      glBindFramebuffer(GL_FRAMEBUFFER, layer);  // its depth: the previous layer's, still
      glEnable(GL_DEPTH_TEST);
      drawLayer.skipPeeled(layer_.objectId);
    }
    copyDepth(gbuffer_.depth(), layerDepth_);
    glClearNamedFramebufferfv(layer, GL_COLOR, 0, zero);
    glClearNamedFramebufferuiv(layer, GL_COLOR, 1, noWeight);
    glClearNamedFramebufferiv(layer, GL_COLOR, 2, noObject);
    glBindFramebuffer(GL_FRAMEBUFFER, layer);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glBindTextureUnit(peelDepthUnit_, id(previousDepth_));
    glBeginQuery(GL_ANY_SAMPLES_PASSED, anySamples_.id());
    drawLayer.draw(k == 0);
    glEndQuery(GL_ANY_SAMPLES_PASSED);
    GLuint any = 0;
    glGetQueryObjectuiv(anySamples_.id(), GL_QUERY_RESULT, &any);
    ++peeled_;
    if (!any) break;
    glDisable(GL_DEPTH_TEST);
    if (lineColor) {
      glBindFramebuffer(GL_FRAMEBUFFER, linesFramebuffer_.id());
      lines.draw(layer_);
    }
    // Front to back: the layer (its lines over its surfaces) goes under what is accumulated
    // (Porter–Duff "under" on premultiplied colour: C += (1 − A) c, A += (1 − A) a).
    glBindFramebuffer(GL_FRAMEBUFFER, accumulationFramebuffer_.id());
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE_MINUS_DST_ALPHA, GL_ONE);
    const GLuint under = underProgram_.id();
    glUseProgram(under);
    glBindTextureUnit(0, id(layer_.color));
    glBindTextureUnit(1, id(lineCoverage_));
    const glm::vec3 color = lineColor.value_or(glm::vec3(0.0f));
    glProgramUniform4f(under, 0, color.r, color.g, color.b, lineColor ? 1.0f : 0.0f);
    fullscreen_.draw();
    glDisable(GL_BLEND);
  }
  glDisable(GL_DEPTH_TEST);  // also when the loop ended at an empty layer
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
