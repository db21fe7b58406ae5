// The breakaway cutter in the frame (Diepstraten03 §5): the clusters' inflated hulls are
// drawn twice into a clip depth (greater-than, then less-than: the foremost hull surface,
// 0 where no hull covers the pixel), once for front faces (outer hulls) and once for back
// faces (inner hulls, smaller by the wall thickness).
#pragma once

#include <vector>

#include "cutaway/cutters/breakaway.hpp"
#include "cutters/cutter.hpp"

namespace cutaway {

class Breakaway : public Cutter {
 public:
  // Builds the hulls, declares the clip targets and allocates its texture units.
  explicit Breakaway(FrameSetup& setup);
  // An interior object that moves takes its hull along: built again at the frame's time.
  void beginFrame(const FrameState& state) override;
  void addPreparationPasses(Frame& frame) override;
  std::vector<Target> geometryInputs() const override { return {clipDepth_, innerDepth_, hullNormal_}; }
  void bindForGeometry() const override;
  // Diepstraten03 rule 1: only the exterior objects.
  bool cuts(std::size_t index) const override;
  bool cutsVolume(std::size_t index) const override;
  CutLook look(std::size_t index) const override;
  std::optional<glm::vec3> cutOutlineColor() const override { return glm::vec3(0.0f); }

 private:
  const BreakawayOptions& options() const {
    return *setup_.scene.cutters.find<BreakawayOptions>();
  }
  void drawClipDepth(GLuint framebuffer, const std::vector<GpuMesh>& hulls) const;
  void buildHulls(float time);

  FrameSetup& setup_;
  std::vector<GpuMesh> outer_, inner_;
  bool animated_ = false;
  float hullsTime_ = 0.0f;
  gl::Program hullProgram_;
  GLuint clipUnit_, innerUnit_, normalUnit_;
  Target clipDepth_, innerDepth_, hullNormal_;
};

}  // namespace cutaway
