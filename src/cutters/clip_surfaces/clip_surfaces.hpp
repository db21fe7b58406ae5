// The clip-surface cutter in the frame (Trapp13): the surfaces' uniform block and relief
// textures, the volumetric depth sprites of the capped solids (built once, or every frame for
// the per-frame parity variant), and the cap surfaces drawn in the geometry pass.
#pragma once

#include <memory>
#include <vector>

#include "cutaway/cutters/clip_surfaces.hpp"
#include "cutaway/render/frame.hpp"
#include "cutaway/render/renderer.hpp"
#include "cutaway/scene/scene.hpp"
#include "render/scene_gpu.hpp"

namespace cutaway {

// A volumetric depth sprite on the GPU (a 2-D texture array, one layer per depth level) and,
// when read back, on the CPU.
struct DepthSpriteGpu {
  gl::Texture layers;
  VolumetricDepthSprite sprite;  // toTexture, size, depth complexity; layers when read back
};

// Depth-peels `mesh` (drawn with `toTexture`, object → LDI space) into layers until a peel
// draws nothing (the depth complexity, counted by occlusion queries) or `maxLayers`, with the
// program of buildDepthPeelProgram().
gl::Program buildDepthPeelProgram();
DepthSpriteGpu buildDepthSprite(GLuint peelProgram, const GpuMesh& mesh, const glm::mat4& toTexture,
                                int resolution, bool readBack, int maxLayers = 64);

// LDI space of a box (object or world space): the box, padded by one texel, mapped to
// [0,1]³ along the orthonormal basis `basis` (columns), rays along its third axis.
glm::mat4 depthSpriteFrame(const Bounds& boxInBasis, const glm::mat3& basis, int resolution);

class ClipSurfaceCutter {
 public:
  // Uploads the surfaces, builds the static depth sprites of the capped objects (watertight,
  // cut, visible), declares the masks and adds the per-frame sprite pass if asked for.
  ClipSurfaceCutter(const SceneGpu& sceneGpu, const ClipSurfaceOptions& options, Frame& frame);
  ~ClipSurfaceCutter();
  // Binds the uniform block (2), relief textures (16–19) and mask images (0, 1).
  void bind() const;
  // Clears the clip-mask and parity images (before the geometry pass draws).
  void clearMasks() const;
  // Draws every cap of every capped object with `capProgram` (cap.vert + cap.frag).
  void drawCaps(GLuint capProgram, float time) const;
  // Objects whose caps are skipped because their meshes are not watertight.
  const std::vector<std::size_t>& uncappable() const { return uncappable_; }
  // The depth sprites' layers as AOVs (name, meaning, image).
  std::vector<Aov> spriteAovs() const;

 private:
  void buildPerFrameSprites(float time);

  const SceneGpu& sceneGpu_;
  ClipSurfaceOptions options_;
  Frame& frame_;
  struct Gpu;
  std::unique_ptr<Gpu> gpu_;
  std::vector<std::size_t> capped_, uncappable_;
};

}  // namespace cutaway
