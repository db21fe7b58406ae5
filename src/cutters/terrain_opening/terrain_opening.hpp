// The terrain-opening cutter in the frame (Konev18 §4): which objects are terrain (and
// buildings), the distance texture built once, and the uniforms and images of
// terrain_opening.glsl.
#pragma once

#include <vector>

#include "cutaway/cutters/terrain_opening.hpp"
#include "cutaway/render/frame.hpp"
#include "cutaway/render/renderer.hpp"
#include "cutaway/scene/scene.hpp"

namespace cutaway {

class TerrainOpening {
 public:
  // Matches the terrain and building objects, builds D_p over the terrain's extent and
  // declares the per-pixel images (d_c and t, the fate seen).
  TerrainOpening(const Scene& scene, const TerrainOpeningOptions& options, Frame& frame);
  bool isTerrain(std::size_t object) const { return terrain_[object]; }
  // Terrain objects, and buildings when the scene asks for them to be opened too.
  bool cuts(std::size_t object) const { return terrain_[object] || cutBuildings_[object]; }
  // Clears the images and binds texture unit 23 and image units 2, 3; sets the uniforms.
  void prepare(GLuint program) const;
  const TerrainField& field() const { return field_; }
  // The distance texture as an AOV.
  Aov fieldAov() const;

 private:
  TerrainOpeningOptions options_;
  Frame& frame_;
  std::vector<bool> terrain_, cutBuildings_;
  TerrainField field_;
  gl::Texture texture_;
};

}  // namespace cutaway
