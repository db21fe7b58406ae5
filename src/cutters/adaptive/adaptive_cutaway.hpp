// The adaptive cutter's preparation passes (Burns08 §5, Burns11 §5.1): seed the region of
// interest's rear hull, grow the cutaway surface by jump flooding (on the GPU, or on the CPU
// where that is faster: Mesa's llvmpipe), and dilate it for back faces.
#pragma once

#include <memory>
#include <string>

#include "cutaway/gl/context.hpp"
#include "cutaway/render/frame.hpp"
#include "render/scene_gpu.hpp"

namespace cutaway {

class AdaptiveCutaway {
 public:
  // Declares the cutter's render targets and adds its passes to `frame` (before geometry).
  AdaptiveCutaway(const SceneGpu& sceneGpu, const AdaptiveCutawayOptions& options,
                  const gl::ContextInfo& info, Frame& frame);
  ~AdaptiveCutaway();
  AdaptiveCutaway(const AdaptiveCutaway&) = delete;
  AdaptiveCutaway& operator=(const AdaptiveCutaway&) = delete;

  // Per-frame camera state for the passes; call before the frame executes.
  void setCamera(const Camera& camera, float aspect);
  // Binds the cutaway depth (unit 8) and its dilation (unit 9) for clip.glsl.
  void bindForClipping() const;
  // "gpu" or "cpu": where jump flooding runs.
  const char* computePath() const { return cpu_ ? "cpu" : "gpu"; }
  // The local angle θ of an object of interest, radians (Burns11 §6.2.1).
  float angleOf(const SceneObject& object) const;
  // Rear hulls of every object of interest and interest proxy (Burns11 §4.2.2).
  static bool seedsCutaway(const SceneObject& object) { return object.role == Role::Interest; }

 private:
  void addGpuPasses();
  void addCpuPass();
  void computeOnCpu();

  const SceneGpu& sceneGpu_;
  AdaptiveCutawayOptions options_;
  bool cpu_;
  Frame& frame_;
  CutawayProjection camera_{};
  struct Programs;
  std::unique_ptr<Programs> programs_;
};

}  // namespace cutaway
