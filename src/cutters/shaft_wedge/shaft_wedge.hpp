// The shaft wedge in the frame (Konev18 §7): active wherever a pipe network contributes
// shafts; cuts their two cylinders in the mesh pass (shaft_wedge.glsl) with each network's
// opening coefficient and colours, read every frame (they are live in the viewer).
#pragma once

#include "cutters/cutter.hpp"

namespace cutaway {

class ShaftWedge : public Cutter {
 public:
  explicit ShaftWedge(FrameSetup& setup);
  bool cuts(std::size_t index) const override;
  CutLook look(std::size_t index) const override;
  void setObjectUniforms(GLuint program, std::size_t index) const override;

 private:
  FrameSetup& setup_;
  GLint openingLocation_, innerLocation_;
};

}  // namespace cutaway
