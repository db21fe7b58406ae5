// The box cut in the frame: every visible object but the objects of interest, cut per
// fragment by box_cut.glsl with the box's uniforms, read from the options every frame (all of
// them are live).
#pragma once

#include <vector>

#include "cutaway/cutters/box_cut.hpp"
#include "cutters/cutter.hpp"

namespace cutaway {

class BoxCut : public Cutter {
 public:
  explicit BoxCut(FrameSetup& setup);
  // The objects whose boxes (grown by a pixel) meet the cut box this frame.
  void beginFrame(const FrameState& state) override;
  bool cuts(std::size_t index) const override;
  bool reaches(std::size_t index) const override {
    return index >= reaches_.size() || reaches_[index];  // before the first frame: all
  }
  bool cutsVolume(std::size_t index) const override;
  CutLook look(std::size_t index) const override;
  void setProgramUniforms(GLuint program) const override;
  std::optional<glm::vec3> cutOutlineColor() const override;

 private:
  const BoxCutOptions& options() const { return *setup_.scene.cutters.find<BoxCutOptions>(); }

  FrameSetup& setup_;
  GLint centerLocation_, axesLocation_, halfLocation_;
  std::vector<bool> reaches_;  // per scene object, this frame
};

}  // namespace cutaway
