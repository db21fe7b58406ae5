// The terrain-opening cutter in the frame (Konev18 §4): which objects are terrain (and
// buildings), the distance texture built once, and the uniforms and images of
// terrain_opening.glsl.
#pragma once

#include <string>
#include <vector>

#include "cutaway/cutters/terrain_opening.hpp"
#include "cutters/cutter.hpp"

namespace cutaway {

class TerrainOpening : public Cutter {
 public:
  // Matches the terrain and building objects, builds D_p over the terrain's extent and
  // declares the per-pixel images (d_c and t, the fate seen).
  explicit TerrainOpening(FrameSetup& setup);
  // Clears the images and binds the distance texture and the images.
  void bindForGeometry() const override;
  void setProgramUniforms(GLuint program) const override;
  // Terrain objects, and buildings when the scene asks for them to be opened too.
  bool cuts(std::size_t index) const override;
  CutLook look(std::size_t index) const override;
  // The distance texture.
  std::vector<Aov> extraAovs() const override;
  // TERRAIN_NEAREST: the rough texture's nearest-texel lookup, else bilinear.
  std::string glslDefines() const override;
  // The trench wall lies behind the ground's fragment.
  bool cutSurfaceBehind() const override { return true; }

 private:
  const TerrainOpeningOptions& options() const {
    return *setup_.scene.cutters.find<TerrainOpeningOptions>();
  }

  FrameSetup& setup_;
  std::vector<bool> terrain_, cutBuildings_;
  TerrainField field_;
  gl::Texture texture_;
  GLuint distanceUnit_, thresholdImage_, classImage_;
  GLint frameLocation_, paramsLocation_, wallLocation_;
  Target threshold_, class_;
};

}  // namespace cutaway
