// The adaptive cutter (Burns08 §5, Burns11 §5.1) in the frame: seed the region of interest's
// rear hull, grow the cutaway surface by jump flooding (on the GPU, or on the CPU where that is
// faster: Mesa's llvmpipe), dilate it for back faces; clip the secondary objects against it in
// the geometry pass (clip.glsl) and draw the removed material's ghost lines (Burns08 §4.3).
#pragma once

#include <memory>
#include <string>

#include "cutaway/cutters/adaptive.hpp"
#include "cutters/adaptive/surface_passes.hpp"
#include "cutters/cutter.hpp"
#include "frame/occlusion_culling.hpp"

namespace cutaway {

class AdaptiveCutaway : public Cutter {
 public:
  // Declares the cutter's render targets and allocates its texture units.
  explicit AdaptiveCutaway(FrameSetup& setup);
  ~AdaptiveCutaway() override;

  void beginFrame(const FrameState& state) override;
  void addPreparationPasses(Frame& frame) override;
  std::vector<Target> geometryInputs() const override;
  void bindForGeometry() const override;
  void setProgramUniforms(GLuint program) const override;
  void setObjectUniforms(GLuint program, std::size_t index) const override;
  // The contextual structure's R applied as translucency, edge highlights or lines (Burns11
  // ch. 2).
  int translucentLayers() const override;
  // Every visible object but the objects of interest (Burns08 §4.1).
  bool cuts(std::size_t index) const override;
  bool reaches(std::size_t index) const override {
    return index >= reaches_.size() || reaches_[index];  // before the first frame: all
  }
  bool cutsVolume(std::size_t index) const override;
  CutLook look(std::size_t index) const override;
  void addPassesAfterGeometry(Frame& frame) override;
  void setOcclusionCulling(bool on) override {
    if (ghostCulling_) ghostCulling_->setEnabled(on);
  }
  std::optional<glm::vec3> cutOutlineColor() const override;
  std::optional<GhostBuffers> ghosts() const override;
  std::vector<std::pair<std::string, std::string>> facts() const override;
  // The cutaway buffers' pixel size in view-plane units, and the seeds' cones (CPU path).
  void describeAovs(std::vector<Aov>& aovs) const override;

  // The local angle θ of an object of interest, radians (Burns11 §6.2.1); the scene's angle
  // for geometry that is no scene object.
  float angleOf(const SceneObject* object) const;

 private:
  const AdaptiveCutawayOptions& options() const {
    return *setup_.scene.cutters.find<AdaptiveCutawayOptions>();
  }
  void drawGhostGeometry(GLuint framebuffer) const;
  void drawAtPixel() const;
  // C and its dilation, and C₂'s, at their texture units (clip.glsl's samplers).
  void bindSurfaces() const;
  // Burns11 §7.2: whether R = Ω (the objects it cuts are not ranked by importance).
  bool reductionIsOcclusion() const;
  // Which objects C may cut this frame (Cutter::reaches), once the CPU path has computed it.
  void findReaches();

  FrameSetup& setup_;
  // Its buffer size, compute path and variant are what a change rebuilds the renderer for.
  CutawaySurfacePasses surface_;
  // The contextual structure's C₂ (Burns11 §4.1.3), when it is on.
  std::unique_ptr<CutawaySurfacePasses> transition_;
  GLuint depthUnit_, dilatedUnit_;
  GLuint transitionDepthUnit_ = 0, transitionDilatedUnit_ = 0;
  // C and its dilation (and C₂'s, or the simple structure's cut-surface normal: clip.glsl's
  // cutawaySurfaceAt) at each pixel's centre (at_pixel.frag), for the geometry passes.
  Target atPixel_;
  GLuint atPixelUnit_ = 0;
  GLint contextualLocation_ = -1, importanceLocation_ = -1, applyLocation_ = -1;
  bool graded_ = false;
  Target seedDepthTest_;
  Target ghostNormal_, ghostObjectId_, ghostDepth_;
  std::unique_ptr<OcclusionCulling> ghostCulling_;  // of the ghost geometry's draws
  std::vector<bool> reaches_;                       // per scene object, this frame
  float time_ = 0.0f;                               // this frame's, and its uniforms
  FrameUniforms uniforms_{};
  struct Programs;
  std::unique_ptr<Programs> programs_;
};

}  // namespace cutaway
