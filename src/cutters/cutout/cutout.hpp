// The cutout cutter in the frame (Diepstraten03 §4): the exterior units' main axes at set-up,
// their wedges per frame, and the uniforms of src/cutters/cutout/cutout.glsl per object; with
// the clip-plane method (§4.3), the exterior drawn once per plane instead.
#pragma once

#include <vector>

#include "cutaway/cutters/cutout.hpp"
#include "cutaway/gl/objects.hpp"
#include "cutters/cutter.hpp"

namespace cutaway {

class Cutout : public Cutter {
 public:
  explicit Cutout(FrameSetup& setup);
  // The wedges face the camera (unless the rotation is fixed).
  void beginFrame(const FrameState& state) override;
  void bindForGeometry() const override;
  // Diepstraten03 rule 1: only the exterior objects, per fragment with the texture method…
  bool cuts(std::size_t index) const override;
  bool cutsVolume(std::size_t index) const override;
  // … or with one hardware clip plane per pass.
  int clipPasses(std::size_t index) const override;
  glm::vec4 clipPlane(std::size_t index, int pass) const override;
  CutLook look(std::size_t index) const override;
  // Outside the wedge, where no jitter reaches, an exterior object is kept whole: its front
  // faces there (and a hollow one's back faces) draw without the cutter's code. A solid one's
  // back faces stay the cutter's: each may be the wall seen through the cut (rule 5).
  std::optional<Slab> slab(std::size_t index) const override {
    return index < slabs_.size() ? slabs_[index] : std::nullopt;
  }
  void setObjectUniforms(GLuint program, std::size_t index) const override;
  void setVolumeUniforms(GLuint program, std::size_t index) const override;
  // CUTOUT_JITTER_PATTERN: the jitter's pattern (0 none, 1 sawtooth, 2 noise, 3 image).
  std::string glslDefines() const override;
  std::optional<glm::vec3> cutOutlineColor() const override { return glm::vec3(0.0f); }

 private:
  const CutoutOptions& options() const { return *setup_.scene.cutters.find<CutoutOptions>(); }
  // The wedge of exterior unit `unit`, or null for -1 (not exterior).
  const CutoutWedge* wedgeOf(int unit) const;
  void setWedgeUniforms(GLuint program, const CutoutWedge* wedge) const;
  int jitterPattern() const;  // CutoutJitter::Pattern as an int; 0 under the clip-plane method

  FrameSetup& setup_;
  const CutoutOptions::Method method_;
  std::vector<ExteriorUnit> units_;
  bool animated_ = false;  // an exterior object moves: the units follow it frame by frame
  float unitsTime_ = 0.0f;
  std::vector<int> unitOfObject_;  // -1: not exterior
  std::vector<int> unitOfVolume_;
  std::vector<CutoutWedge> wedges_;
  std::vector<std::optional<Slab>> slabs_;  // this frame's, per scene object
  gl::Texture imageTexture_;
  GLuint imageUnit_;
  GLint planesLocation_, planeCountLocation_, originLocation_, axisLocation_, jitterLocation_;
};

}  // namespace cutaway
