// Burns11 ch. 2's occlusion reduction by translucency and edge highlights on polygons: the
// material a cutter leaves partly reduced (opacity 0 < α < 1, cutters/cutter.hpp's grading
// cutters) is drawn as translucent layers over the opaque frame, composited in depth order by
// depth peeling (Everitt 2001, "Interactive order-independent transparency"): each layer is
// the nearest translucent surface behind the previous one and in front of the opaque depth,
// per MSAA sample, blended under the layers before it (front to back); peeling stops when a
// layer comes out empty (an occlusion query) or at the layer budget. With enough layers the
// result is exact: no sorting of triangles, no order-dependent artefacts, unlike one-pass
// weighted blending, whose colours of nested layers are an approximation.
//
// Its passes: "translucentLayers" after the geometry passes (the opaque depth in; the
// accumulated premultiplied colour and coverage out), "translucentComposite" after the
// composite (the accumulation's samples averaged and blended over the final colour, so that
// the opaque surfaces' lines behind a layer are dimmed by it too).
//
//   TranslucentLayers layers(setup.frame, gbuffer, [&] { return options.layers; });
//   layers.addLayersPass(frame, drawLayer);     // drawLayer: every kind's translucent fragments
//   gbuffer.addCompositePass(frame, overlays);
//   layers.addCompositePass(frame, gbuffer.finalColor());
#pragma once

#include <functional>

#include "cutaway/frame/frame.hpp"
#include "cutaway/gl/objects.hpp"
#include "frame/bindings.hpp"
#include "frame/fullscreen.hpp"
#include "frame/gbuffer.hpp"

namespace cutaway {

class TranslucentLayers {
 public:
  // Declares its targets (as multisampled as the G-buffer) and allocates the texture unit the
  // geometry programs read the previous layer's depth from (UNIT_PEEL_DEPTH).
  TranslucentLayers(Frame& frame, Bindings& bindings, const GBuffer& gbuffer,
                    std::function<int()> maxLayers);
  // `drawLayer(first)`: draws every translucent fragment, depth-tested (LESS) into the bound
  // layer framebuffer, the previous layer's depth bound at UNIT_PEEL_DEPTH unless `first`.
  void addLayersPass(Frame& frame, std::function<void(bool first)> drawLayer);
  void addCompositePass(Frame& frame, Target finalColor);
  // Layers peeled in the last frame (the last one empty, unless the budget ended it).
  int layersPeeled() const { return peeled_; }

 private:
  void peel(const std::function<void(bool)>& drawLayer);

  Frame& frame_;
  const GBuffer& gbuffer_;
  std::function<int()> maxLayers_;
  GLuint peelDepthUnit_;
  Target accumulation_, layerColor_, layerDepth_, previousDepth_;
  gl::Framebuffer layerFramebuffer_, accumulationFramebuffer_;
  gl::Program underProgram_, overProgram_;
  gl::Query anySamples_;
  FullscreenTriangle fullscreen_;
  int peeled_ = 0;
};

}  // namespace cutaway
