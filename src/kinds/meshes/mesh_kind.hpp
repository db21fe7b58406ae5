// Triangle meshes as a geometry kind: every visible scene object drawn into the G-buffer with
// the style and the active cutters composed into kinds/meshes/mesh.frag. Burns08 §4.1's
// order: the secondary objects first, cut; the objects of interest after, whole. An object a
// cutter clips with hardware clip planes (Diepstraten03 §4.3) is drawn once per plane. The
// objects a grading cutter cuts are drawn again, for each translucent layer, by the layer
// variants of the program (frame/translucent_layers.hpp). The geometry pass draws the objects
// the last frame showed first, then those of the rest whose boxes pass the depth test
// (frame/occlusion_culling.hpp). Objects no cutter cuts are drawn by a variant of the program
// without the cutters' code (UNCUT), which llvmpipe would otherwise run for their fragments too;
// a cut object's front faces, then its back faces, by variants for one side each.
#pragma once

#include <memory>

#include "frame/occlusion_culling.hpp"
#include "kinds/kind.hpp"

namespace cutaway {

class MeshKind : public GeometryKind {
 public:
  explicit MeshKind(FrameSetup& setup) : setup_(setup) {}
  void prepare(const std::vector<ActiveCutter>& cutters) override;
  void drawGeometry(const std::vector<ActiveCutter>& cutters,
                    const GeometryDraw& draw) const override;
  void drawTranslucentLayer(const std::vector<ActiveCutter>& cutters, const GeometryDraw& draw,
                            bool first) const override;
  void skipPeeled(const std::vector<ActiveCutter>& cutters, const GeometryDraw& draw,
                  Target ids) const override;
  void addPassesAfterGeometry(Frame& frame) override;
  void beginFrame(const FrameState& state) override;
  // Object draws the last frame's translucent layers left out (skipPeeled).
  std::size_t peeledDraws() const { return peeledDraws_; }
  OcclusionCulling& culling() { return *culling_; }
  const OcclusionCulling& culling() const { return *culling_; }

 private:
  std::vector<ObjectCut> objectCuts(const std::vector<ActiveCutter>& cutters) const;
  void setObjectUniforms(GLuint program, const std::vector<ActiveCutter>& cutters,
                         const ObjectCut& cut, const SceneObject& o, std::size_t i) const;

  FrameSetup& setup_;
  gl::Program layerFrontProgram_, layerBackProgram_;  // TRANSLUCENT_LAYER, one side each
  gl::Program uncutProgram_;                   // mesh.frag with UNCUT: the objects no cutter cuts
  // UNCUT and SLAB_KEPT: the parts of cut objects a Cutter::slab keeps whole, where the
  // cutters' G-buffer channels still hold values (none added: the uncut program is it).
  gl::Program slabKeptProgram_;
  gl::Program frontProgram_, backProgram_;     // FRONT_FACES, BACK_FACES: a cut object's sides
  std::unique_ptr<OcclusionCulling> culling_;  // of the geometry pass's draws
  mutable std::vector<ObjectCut> layerCuts_;  // this frame's, from its first translucent layer
  mutable int layerGrading_ = 0;  // the same: the slots of the cutters leaving translucent fragments
  mutable std::vector<bool> peeled_;          // this frame's objects wholly in front of a layer
  mutable std::size_t peeledDraws_ = 0;       // this frame's layer draws they left out
  // Whether object i is drawn into the translucent layers (this frame's, once the first is).
  bool inLayers(std::size_t i) const;
};

}  // namespace cutaway
