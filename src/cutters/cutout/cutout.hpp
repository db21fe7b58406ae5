// The cutout cutter in the frame (Diepstraten03 §4): the exterior units' main axes at set-up,
// their wedges per frame, and the uniforms of src/cutters/cutout/cutout.glsl per object.
#pragma once

#include <vector>

#include "cutaway/cutters/cutout.hpp"
#include "cutaway/gl/objects.hpp"
#include "cutaway/scene/scene.hpp"

namespace cutaway {

class Cutout {
 public:
  Cutout(const Scene& scene, const CutoutOptions& options);
  // The wedges face the camera (unless the rotation is fixed): call before each frame.
  void setCamera(const Camera& camera);
  // Binds the perturbation image (unit 10) for cutout.glsl.
  void bind() const;
  // Sets cutout.glsl's uniforms for object `index`: its unit's wedge, or none.
  void setUniforms(GLuint program, std::size_t index) const;
  // The wedge that cuts object `index`, or null when it is not exterior.
  const CutoutWedge* wedgeOf(std::size_t index) const;
  const std::vector<ExteriorUnit>& units() const { return units_; }

 private:
  CutoutOptions options_;
  std::vector<ExteriorUnit> units_;
  std::vector<int> unitOfObject_;  // -1: not exterior
  std::vector<CutoutWedge> wedges_;
  gl::Texture imageTexture_;
};

}  // namespace cutaway
