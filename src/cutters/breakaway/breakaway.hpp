// The breakaway cutter in the frame (Diepstraten03 §5): the clusters' inflated hulls are
// drawn twice into a clip depth (greater-than, then less-than: the foremost hull surface,
// 0 where no hull covers the pixel), once for front faces (outer hulls) and once for back
// faces (inner hulls, smaller by the wall thickness).
#pragma once

#include <vector>

#include "cutaway/cutters/breakaway.hpp"
#include "cutaway/render/frame.hpp"
#include "cutaway/scene/scene.hpp"
#include "render/scene_gpu.hpp"

namespace cutaway {

class Breakaway {
 public:
  // Builds the hulls, declares the clip targets and adds the clip passes (before geometry).
  Breakaway(const Scene& scene, const BreakawayOptions& options, Frame& frame);
  // Binds the clip depths (units 11, 12) and hull normals (21) for breakaway.glsl.
  void bind() const;
  const std::vector<BreakawayCluster>& clusters() const { return clusters_; }

 private:
  void drawClipDepth(GLuint framebuffer, const std::vector<GpuMesh>& hulls) const;

  Frame& frame_;
  std::vector<BreakawayCluster> clusters_;
  std::vector<GpuMesh> outer_, inner_;
  gl::Program hullProgram_;
};

}  // namespace cutaway
