// Burns11 ch. 2's occlusion reduction on polygons by translucency, edge highlights and line
// drawings: the material a cutter leaves partly reduced (cutters/cutter.hpp's grading
// cutters: a surface opacity and a line opacity per fragment) is drawn as translucent layers
// over the opaque frame, composited in depth order by depth peeling (Everitt 2001,
// "Interactive order-independent transparency"): each layer is the nearest such surface
// behind the previous one and in front of the opaque depth, per MSAA sample, blended under the
// layers before it (front to back); peeling stops when a layer comes out empty (an occlusion
// query) or at the layer budget. With enough layers the result is exact: no sorting of
// triangles, no order-dependent artefacts, unlike one-pass weighted blending, whose colours of
// nested layers are an approximation.
//
// Each layer is a small G-buffer (premultiplied colour; normal with the line opacity as its
// line weight; object id with view depth), so the feature lines of a layer's surfaces are
// found by the same line pass as the opaque frame's and drawn over the layer, faded by their
// opacity (§2.3: surfaces suppressed, lines kept).
//
// Its passes: "translucentLayers" after the geometry passes (the opaque depth in; the
// accumulated premultiplied colour and coverage out), "translucentComposite" after the
// composite (the accumulation's samples averaged and blended over the final colour, so that
// the opaque surfaces' lines behind a layer are dimmed by it too).
//
//   TranslucentLayers layers(setup.frame, bindings, gbuffer, [&] { return budget; });
//   layers.addLayersPass(frame, drawLayer, lines);  // drawLayer: the kinds' translucent share
//   gbuffer.addCompositePass(frame, overlays);
//   layers.addCompositePass(frame, gbuffer.finalColor());
//
// A surface that turns translucent leaves the opaque G-buffer there and starts in a layer, so
// the line passes outline that boundary (where R leaves 0), as they outline a cut.
#pragma once

#include <functional>
#include <optional>

#include <glm/glm.hpp>

#include "cutaway/frame/frame.hpp"
#include "cutaway/gl/objects.hpp"
#include "frame/bindings.hpp"
#include "frame/fullscreen.hpp"
#include "frame/gbuffer.hpp"

namespace cutaway {

class TranslucentLayers {
 public:
  // A layer's G-buffer, written by the layer variant of the geometry programs.
  struct Layer {
    Target color, normal, objectId;
  };
  // The feature lines drawn over each layer: their colour this frame (none: no lines), and
  // the line pass over a layer into the bound coverage target (R16F, single sample) with a
  // one-sample depth attachment it may overwrite (LinePass's skipEmpty).
  struct Lines {
    std::function<std::optional<glm::vec3>()> color;
    std::function<void(const Layer&)> draw;
  };

  // Declares its targets (as multisampled as the G-buffer) and allocates the texture unit the
  // geometry programs read the previous layer's depth from (UNIT_PEEL_DEPTH).
  TranslucentLayers(Frame& frame, Bindings& bindings, const GBuffer& gbuffer,
                    std::function<int()> maxLayers);
  // What the kinds draw into the layers. `draw(first)`: every translucent fragment,
  // depth-tested (LESS) into the bound layer framebuffer, the previous layer's depth bound at
  // UNIT_PEEL_DEPTH unless `first`. `skipPeeled(ids)`, before each layer after the first, the
  // previous layer's depth in the bound framebuffer's and its per-sample object ids in `ids`
  // (-1 where it found nothing, and so no later layer will): the kinds may leave out of this
  // layer and the later ones what lies wholly at or in front of that depth where it found a
  // surface (peeled, and the peel depths only go back).
  struct LayerDraw {
    std::function<void(bool first)> draw;
    std::function<void(Target ids)> skipPeeled;
  };
  void addLayersPass(Frame& frame, LayerDraw drawLayer, Lines lines);
  void addCompositePass(Frame& frame, Target finalColor);
  // Layers peeled in the last frame (the last one empty, unless the budget ended it).
  int layersPeeled() const { return peeled_; }

 private:
  void peel(const LayerDraw& drawLayer, const Lines& lines);
  void attach();  // its targets to its framebuffers, once

  Frame& frame_;
  const GBuffer& gbuffer_;
  std::function<int()> maxLayers_;
  GLuint peelDepthUnit_;
  Layer layer_;
  Target accumulation_, lineCoverage_, linePixels_, layerDepth_, previousDepth_;
  gl::Framebuffer layerFramebuffer_, accumulationFramebuffer_, linesFramebuffer_;
  gl::Program underProgram_, overProgram_;
  gl::Query anySamples_;
  FullscreenTriangle fullscreen_;
  int peeled_ = 0;
};

}  // namespace cutaway
