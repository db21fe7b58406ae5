// Triangle meshes as a geometry kind: every visible scene object drawn into the G-buffer with
// the style and the active cutters composed into kinds/meshes/mesh.frag. Burns08 §4.1's
// order: the secondary objects first, cut; the objects of interest after, whole. An object a
// cutter clips with hardware clip planes (Diepstraten03 §4.3) is drawn once per plane. The
// objects a grading cutter cuts are drawn again, for each translucent layer, by the layer
// variants of the program (frame/translucent_layers.hpp). The geometry pass draws the objects
// the last frame showed first, then those of the rest whose boxes pass the depth test
// (frame/occlusion_culling.hpp). Objects no cutter cuts are drawn by a variant of the program
// without the cutters' code (UNCUT), which llvmpipe would otherwise run for their fragments too;
// a cut object's front faces, then its back faces, by variants for one side each; on an open
// mesh its removed front fragments are marked between the two (drawBackFaces).
#pragma once

#include <memory>

#include "frame/occlusion_culling.hpp"
#include "kinds/kind.hpp"

namespace cutaway {

class MeshKind : public GeometryKind {
 public:
  explicit MeshKind(FrameSetup& setup) : setup_(setup) {}
  // For the removal marks of the open meshes a cutter cuts (drawBackFaces).
  bool needsStencil(const std::vector<ActiveCutter>& cutters) const override;
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
  // Burns08 §4.1 on an open mesh: a back face seen through the cut is the solid's cut surface,
  // one seen through the mesh's own opening its inside. Whether object i's cut tells them
  // apart by removal marks: a cutter whose look asks for them (CutLook::marksOpenMeshes) cuts
  // it with cut surfaces and it is not watertight (on a watertight mesh a back face shows only
  // where its front was removed); not with hardware clip passes (Diepstraten03 §4.3), whose
  // draws of one object overlap.
  bool marksRemoval(const ObjectCut& cut, std::size_t i) const;
  // An object's back faces by `back`, after its front faces: `draw(program, cutSurfaces)` sets
  // the program's uniforms (where false, without the marking cutters' cut surfaces) and draws.
  // With `marks`, its front fragments the marking cutters remove are first marked in the stencil
  // (markProgram_, one value per object), and the back faces drawn as the cut shows them over
  // the marked samples and, where `unmarked`, without those cut surfaces over the rest.
  void drawBackFaces(GLuint back, bool marks, bool unmarked,
                     const std::function<void(GLuint, bool)>& draw) const;

  FrameSetup& setup_;
  gl::Program layerFrontProgram_, layerBackProgram_;  // TRANSLUCENT_LAYER, one side each
  gl::Program uncutProgram_;                   // mesh.frag with UNCUT: the objects no cutter cuts
  // UNCUT and SLAB_KEPT: the parts of cut objects a Cutter::slab keeps whole, where the
  // cutters' G-buffer channels still hold values (none added: the uncut program is it).
  gl::Program slabKeptProgram_;
  gl::Program frontProgram_, backProgram_;     // FRONT_FACES, BACK_FACES: a cut object's sides
  gl::Program markProgram_;         // FRONT_FACES and MARK_REMOVED: an open mesh's removed samples
  mutable std::size_t marked_ = 0;  // objects marked in this frame's geometry pass
  std::unique_ptr<OcclusionCulling> culling_;  // of the geometry pass's draws
  mutable std::vector<ObjectCut> layerCuts_;  // this frame's, from its first translucent layer
  mutable int layerGrading_ = 0;  // the same: the slots of the cutters leaving translucent fragments
  mutable std::vector<bool> peeled_;          // this frame's objects wholly in front of a layer
  mutable std::size_t peeledDraws_ = 0;       // this frame's layer draws they left out
  // Whether object i is drawn into the translucent layers (this frame's, once the first is).
  bool inLayers(std::size_t i) const;
};

}  // namespace cutaway
