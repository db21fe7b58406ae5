// The one interface every geometry kind implements: how one kind of scene geometry (triangle
// meshes, Konev18's procedural pipe networks, volumes) reaches the frame. A kind draws its
// geometry into the G-buffer with the active cutters' decisions composed into its programs,
// casts into the key light's shadow map, and draws its objects of interest's rear hulls for the
// cutters that grow a cutaway around them (Burns08 §5.1), so that any kind can be cut and any
// kind can be of interest.
//
// Adding a kind: its folder and one line in the composer's list (src/render/renderer.cpp), as
// docs/architecture.md says.
#pragma once

#include <memory>
#include <vector>

#include "cutaway/frame/aov.hpp"
#include "cutters/cutter.hpp"
#include "frame/frame_setup.hpp"
#include "frame/frame_uniforms.hpp"

namespace cutaway {

class GeometryKind {
 public:
  virtual ~GeometryKind() = default;

  // Whether the G-buffer's depth needs a stencil (Konev18 §6's proxy passes), with these
  // cutters.
  virtual bool needsStencil(const std::vector<ActiveCutter>& /*cutters*/) const { return false; }
  // Once the geometry programs' shading is known: builds its programs, declares its targets.
  virtual void prepare(const std::vector<ActiveCutter>& /*cutters*/) {}
  // Draws into the geometry pass's G-buffer, the cutters bound.
  virtual void drawGeometry(const std::vector<ActiveCutter>& /*cutters*/,
                            const GeometryDraw& /*draw*/) const {}
  // Its fragments a grading cutter leaves partly reduced (Cutter::translucentLayers) into the
  // bound layer framebuffer of frame/translucent_layers.hpp, with the layer variant of its
  // programs (built when FrameSetup::translucentLayers); `first`: the nearest layer (no
  // previous depth to peel).
  virtual void drawTranslucentLayer(const std::vector<ActiveCutter>& /*cutters*/,
                                    const GeometryDraw& /*draw*/, bool /*first*/) const {}
  // Before each layer after the first, the previous layer's depth in the bound framebuffer's
  // and its object ids in `ids`: it may leave out of this layer and the later ones what lies
  // wholly at or in front of that depth (TranslucentLayers::LayerDraw).
  virtual void skipPeeled(const std::vector<ActiveCutter>& /*cutters*/,
                          const GeometryDraw& /*draw*/, Target /*ids*/) const {}
  // Its passes after the geometry pass (into the same G-buffer, or AOVs of its own).
  virtual void addPassesAfterGeometry(Frame&) {}
  // Its passes after the composite, over the final colour, in front of the opaque depth
  // (volumes ray cast up to the meshes).
  virtual void addPassesAfterComposite(Frame&) {}
  // Before the frame's passes run, with its camera (work on the CPU that depends on the view).
  virtual void beginFrame(const FrameState&) {}
  // Into the bound shadow-map target, the light's frame uniforms bound (styles/shadows).
  virtual void drawShadowCasters() const {}
  // Into the bound seed targets (frame/frame_setup.hpp: RearHullRequest).
  virtual void drawInterestRearHulls(const RearHullRequest&) const {}
  virtual std::vector<Aov> extraAovs() const { return {}; }
};

}  // namespace cutaway
