// The clip-surface cutter in the frame (Trapp13): the surfaces' uniform block and relief
// textures, the volumetric depth sprites of the capped solids (built once, or every frame for
// the per-frame parity variant), and the cap surfaces drawn in the geometry pass.
#pragma once

#include <memory>
#include <vector>

#include "cutaway/cutters/clip_surfaces.hpp"
#include "cutters/cutter.hpp"

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

class ClipSurfaceCutter : public Cutter {
 public:
  // Uploads the surfaces, builds the static depth sprites of the capped objects (watertight,
  // cut, visible) and declares the masks.
  explicit ClipSurfaceCutter(FrameSetup& setup);
  ~ClipSurfaceCutter() override;
  void prepareGeometryPrograms() override;
  // The per-frame sprite pass, if asked for (Trapp13 §6.3).
  void addPreparationPasses(Frame& frame) override;
  void beginFrame(const FrameState& state) override;
  // Clears the clip-mask and parity images; binds the block, relief textures and images.
  void bindForGeometry() const override;
  bool cuts(std::size_t index) const override;
  // Not where the object's box (grown by a pixel) lies wholly where the surfaces keep all.
  bool reaches(std::size_t index) const override {
    return index >= reaches_.size() || reaches_[index];  // before the first frame: all
  }
  // Where one surface alone decides the object: its plane lifted by the relief's least and
  // greatest offset (clipSurfacesSlab).
  std::optional<Slab> slab(std::size_t index) const override {
    return index < slabs_.size() ? slabs_[index] : std::nullopt;
  }
  bool cutsVolume(std::size_t index) const override;
  CutLook look(std::size_t index) const override;
  // Every cap of every capped object (cap.vert + cap.frag).
  void drawGeometry(const GeometryDraw& draw) const override;
  // The clip mask when read (clip_mask.frag), and the cap mask from the G-buffer's cut mask.
  void addPassesAfterGeometry(Frame& frame) override;
  // The depth sprites' layers.
  std::vector<Aov> extraAovs() const override;
  // Objects whose caps are skipped because their meshes are not watertight.
  const std::vector<std::size_t>& uncappable() const { return uncappable_; }

 private:
  void buildPerFrameSprites(float time);
  // Binds what clip_surfaces.glsl and the clip mask read and write.
  void bindForMask() const;
  // Trapp13 §4.2's normal and occlusion maps of `cs`'s offset map into `texture`.
  static void uploadRelief(GLuint texture, const ClipSurface& cs);
  // The options now; `options_` keeps what a change rebuilds the renderer for (the offset
  // maps, the caps and their sprites).
  const ClipSurfaceOptions& live() const { return *setup_.scene.cutters.find<ClipSurfaceOptions>(); }

  FrameSetup& setup_;
  ClipSurfaceOptions options_;
  float sceneRadius_;
  struct Gpu;
  std::unique_ptr<Gpu> gpu_;
  std::vector<std::size_t> capped_, uncappable_;
  std::vector<bool> reaches_;  // per scene object, this frame
  std::vector<std::optional<Slab>> slabs_;
  GLuint blockBinding_, reliefUnit_, capReliefUnit_, layersUnit_, diffuseUnit_, clipMaskImage_,
      parityImage_;
  Target clipMask_, capParity_, capMask_;
};

}  // namespace cutaway
