// The cutaway surface from a seed (Burns08 §5, Burns11 §5.1): the region of interest's rear
// hull as window depth and local angles in two n×n targets, turned into C(p) (eq. 4.2) by
// jump flooding, in compute passes or on the CPU, then dilated by one pixel for back faces
// (Burns08 §4.2). The adaptive cutter seeds it from the scene's objects of interest; the
// public AdaptiveCutawaySurface (cutaway/cutters/adaptive_surface.hpp) from another
// application's depth texture.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cutaway/cutters/adaptive.hpp"
#include "cutaway/frame/aov.hpp"
#include "cutaway/frame/frame.hpp"

namespace cutaway {

class CutawaySurfacePasses {
 public:
  using Options = std::function<const AdaptiveCutawayOptions&()>;
  // Declares the seed, the surface and, on the GPU path, the anchor targets in `frame`;
  // `options` is read every frame (angle-independent options: edge compression, floor…).
  CutawaySurfacePasses(Frame& frame, int bufferSize, fields::JumpFloodingVariant variant,
                       bool cpu, Options options);
  // A second surface from `seed`'s seed, every seed's angle raised to at least minAngle()
  // (radians, read every frame): the contextual structure's C₂ (Burns11 §4.1.3.1). Its
  // targets and passes are named with `suffix` ("cutawayDepthC2").
  CutawaySurfacePasses(const CutawaySurfacePasses& seed, std::string suffix,
                       std::function<float()> minAngle);
  ~CutawaySurfacePasses();

  // Written by the seeding pass: window depth of the rear hull (0 = no seed), θ in radians.
  Target seedDepth() const { return seedDepth_; }
  Target seedAngle() const { return seedAngle_; }
  // C(p) and its 1-pixel minimum, window depth, linearly filtered (Burns08 §6).
  Target cutawayDepth() const { return cutawayDepth_; }
  Target cutawayDilated() const { return cutawayDilated_; }
  int bufferSize() const { return bufferSize_; }
  bool onCpu() const { return cpu_; }

  // The camera of the next frame.
  void setCamera(const CutawayProjection& camera) { camera_ = camera; }
  // The passes after the seed's, into the frame: cutawayCpu, or cutawayAnchors,
  // jumpFloodingInit, jumpFlooding/k…, cutawayDepth; then cutawayDilate.
  void addPasses();
  // On the CPU path, after this frame's cutawayCpu pass: C's maxima (empty before).
  const GreatestDepth& greatest() const { return greatest_; }
  // After the frame: its buffers' AOVs get the size and the pixel size in view-plane units
  // (Aov::values); on the CPU path, the seeds' cones are added as the GPU path's anchorCone.
  void describeAovs(std::vector<Aov>& aovs) const;

 private:
  void addGpuPasses();
  void computeOnCpu();

  void declareSurface();

  Frame& frame_;
  const std::string suffix_;
  const std::function<float()> minAngle_;
  const int bufferSize_;
  const fields::JumpFloodingVariant variant_;
  const bool cpu_;
  Options options_;
  CutawayProjection camera_{};
  Target seedDepth_, seedAngle_, cutawayDepth_, cutawayDilated_;
  GreatestDepth greatest_;
  Target anchorCone_, anchorFloor_, anchorsA_, anchorsB_;
  struct Programs;
  std::unique_ptr<Programs> programs_;
};

}  // namespace cutaway
