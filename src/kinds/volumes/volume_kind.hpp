// Scalar volumes as a geometry kind (Burns11 §5.2.5, §7.1): each scene volume ray cast on the
// GPU after the composite, over the final colour and up to the opaque surfaces' depth, so
// that meshes in front hide it and meshes inside it (an ultrasound plane, a tool) sit in it.
// The cutters that cut a volume (Cutter::cutsVolume) decide every ray sample as they decide a
// fragment: an adaptive cutaway's rays start at its cutaway surface, Trapp13's clip surfaces
// and the box cut open it, and a grading cutter reduces each sample's opacity by R (Burns11
// ch. 2, eqs. 7.1–7.3 with the importance of the sample's material). The frame's pass:
//   volumes   every volume, those of interest first, blended over the final colour, each
//             ray stopping where the volumes before it hid the rest; the AOVs
//             volumeEntryDepth, volumeHitDepth, volumeOpacity and
//             volumeLightTransmittance over all of them
//   volumeLineSurfaces, volumeLines   the volumes' line drawings (volume_lines_pass.hpp)
#pragma once

#include <map>
#include <memory>
#include <vector>

#include "cutaway/gl/objects.hpp"
#include "frame/fullscreen.hpp"
#include "kinds/kind.hpp"
#include "kinds/volumes/volume_lines_pass.hpp"

namespace cutaway {

// The transfer function as the table the GPU reads (colour and opacity, and importance), exact
// at the texels: along the value from the first control point's to the last's, 1024 texels
// (one per label of a label volume); along the gradient magnitude from the first row's to the
// last's, 256 texels (one for a one-dimensional function). Row by row, value fastest.
struct TransferTable {
  float first = 0.0f, last = 1.0f;
  float firstGradient = 0.0f, lastGradient = 0.0f;
  int width = 0, height = 0;
  std::vector<glm::vec4> colorOpacity;
  std::vector<float> importance;
};
TransferTable transferTable(const SceneVolume& volume);

class VolumeKind : public GeometryKind {
 public:
  // Uploads the volumes; throws cutaway::Error for a volume the GPU cannot hold.
  explicit VolumeKind(FrameSetup& setup);
  static bool present(const Scene& scene) { return !scene.volumes.empty(); }
  void prepare(const std::vector<ActiveCutter>& cutters) override;
  void addPassesAfterComposite(Frame& frame) override;
  void beginFrame(const FrameState& state) override;
  // The last frame's volume lines as drawn (volume_lines_pass.hpp); none without.
  VolumeLineDrawing lineDrawing() const;
  // A volume of interest seeds the cutaway with the rear of its material: along each ray, the
  // farthest sample its transfer function makes visible (volume_rear_hull.frag).
  void drawInterestRearHulls(const RearHullRequest& request) const override;

 private:
  struct VolumeGpu {
    gl::Texture values, gradient, transfer, importance, occupancy;
    glm::vec2 transferRange{0.0f}, gradientRange{0.0f};
    TransferFunction uploaded;  // what transfer, importance and occupancy were made from
  };
  // Remakes what depends on a volume's transfer function where the scene's has changed since
  // (the viewer's editor changes it between frames): the table, the empty-space blocks, and a
  // label volume's gradient. A cache of the scene: const, its members mutable.
  void updateTransfers() const;
  void uploadTransfer(std::size_t i) const;
  void draw(const std::vector<ActiveCutter>& cutters) const;
  // Binds volume i's textures and sets the uniforms every volume program shares.
  void bindVolume(GLuint program, std::size_t i) const;
  // Bit k: the cutter of slot k cuts volume i.
  static int cutBy(const std::vector<ActiveCutter>& cutters, std::size_t volume);

  FrameSetup& setup_;
  const std::vector<ActiveCutter>* cutters_ = nullptr;
  mutable std::vector<VolumeGpu> volumes_;
  // The programs of a volume's variant (volume.frag's TRANSFER_2D, SHADOWS, MODE, SHADING and
  // CUT), built for the scene's volumes at set-up and for others on first use (the viewer's
  // edits): llvmpipe runs both sides of a branch, so what a volume does not use is compiled out.
  GLuint castProgram(const SceneVolume& v, bool cut) const;
  GLuint rearHullProgram(const SceneVolume& v) const;
  mutable std::map<int, gl::Program> castPrograms_, rearHullPrograms_;
  FullscreenTriangle fullscreen_;
  Target entryDepth_, hitDepth_, opacity_, transmittance_;
  std::unique_ptr<VolumeLinesPass> lines_;  // when a volume has lines
  GLuint occupancyUnit_, previousTransmittanceUnit_;
  // The AOVs as the volumes drawn so far left them, read by the next (volume.frag).
  gl::Texture previousEntry_, previousHit_, previousOpacity_, previousTransmittance_;
};

}  // namespace cutaway
