// Occlusion culling of a pass's scene meshes by the last frame's visibility
// (temporal coherence, as in Bittner et al. 2004, "Coherent Hierarchical Culling", with one
// batch of tests): the objects the last frame showed are drawn first; every other object is
// drawn only if its box passes the depth test against them (an occlusion query), so an object
// hidden behind them costs its box's front faces, not its triangles. Frustum culling comes with
// it: a box outside the view has no sample to pass.
//
// Exact, not a heuristic: the box is the object's world-space bounds grown by half a pixel
// (and 1e-4 of their size) and pulled towards the eye by a few depth units, so where any
// fragment of the object could pass the depth test LESS, the box's front face passes before it
// at the same sample (the depth buffer only comes nearer as the pass goes on; discarded or
// clipped fragments and depths a cutter moves back only make the object fail more). A box the
// near plane cuts, or one around the eye, counts as passing. Drawn or not, a hidden object
// writes nothing, so the G-buffer is the same bit for bit; the one difference is order: an
// object that comes into view is drawn after those shown last frame, so an exact depth tie
// between the two may go the other way for that one frame. A still view (every frame from the
// second on) draws exactly what drawing everything draws.
//
// The objects shown are read from the pass's object ids (all samples) by a compute pass after
// it, into a buffer that the next frame reads back. The mesh kind culls the geometry pass
// (visibleObjects), the adaptive cutter its ghost geometry (visibleGhosts). The boxes' far
// sides tell the translucent layers which objects an earlier layer has peeled whole
// (mayReachBehind).
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "frame/frame_setup.hpp"
#include "frame/frame_uniforms.hpp"

namespace cutaway {

class OcclusionCulling {
 public:
  // `layers`: mayReachBehind will be asked (the translucent layers').
  explicit OcclusionCulling(FrameSetup& setup, bool layers = false);
  // Off: every object is drawn in the first batch (on by default); the visible objects are
  // still marked, for the next frame culled.
  void setEnabled(bool on) { enabled_ = on; }
  // The last frame's visible objects, and this frame's view.
  void beginFrame(const FrameState& state);
  // Draws a pass's objects in two batches, drawBatch(batch) drawing those for which batch(i)
  // holds in the pass's own order: the objects shown last frame, then those of the others for
  // which `drawn` holds whose boxes pass the depth test LESS of the bound framebuffer (at the
  // objects' transforms at `time`).
  using Batch = std::function<bool(std::size_t)>;
  void draw(const Batch& drawn, float time,
            const std::function<void(const Batch&)>& drawBatch) const;
  // Objects this frame's pass did not draw: their boxes failed the depth test.
  std::size_t culled() const { return culled_; }
  // Whether object i was one of them: every fragment of it lies behind the depth the pass
  // tested against, and so behind any depth the pass leaves (which only comes nearer).
  bool hidden(std::size_t i) const { return i < hidden_.size() && hidden_[i]; }
  // For each object of `candidates`, indexed by object: whether some fragment of it could lie
  // behind the depth of the bound framebuffer at a pixel where the per-sample object ids
  // `surfaces` hold a surface (its box's far side, pushed back a few depth units, passes the
  // depth test GREATER at such a pixel; a box the near plane cuts passes; every box while
  // culling is off). Leaves the depth function LESS.
  std::vector<bool> mayReachBehind(const std::vector<std::size_t>& candidates, float time,
                                   const gl::Texture& surfaces) const;
  // The pass `name`, after the pass culled: marks the objects with a sample in `objectIds`
  // (a per-sample R32I target, −1 where none).
  void addPass(Frame& frame, const std::string& name, Target objectIds);

 private:
  FrameSetup& setup_;
  bool enabled_ = true;
  gl::Program boxProgram_, markProgram_;
  std::array<GLint, 3> markGroup_{};  // the marking program's work group size
  gl::Program surfaceBoxProgram_;  // occlusion_box.frag with SURFACES_ONLY, for mayReachBehind
  gl::VertexArray noAttributes_;
  gl::Buffer visible_;         // one uint per object, set by the marking pass
  std::vector<GLuint> shown_;  // visible_ of the last frame; empty before the first
  bool marked_ = false;        // visible_ holds a frame's marks
  mutable std::vector<gl::Query> queries_;
  mutable std::size_t culled_ = 0;
  mutable std::vector<bool> hidden_;  // this frame's, by object
  // This frame's view.
  FrameUniforms uniforms_{};  // this frame's
  float near_ = 0.0f;

  // Whether object i is drawn in the first batch: shown by the last frame (every object in the
  // first frame, and while culling is off).
  bool shown(std::size_t i) const { return !enabled_ || shown_.empty() || shown_[i] != 0; }
  // For each object of `candidates`, whether its box passes; indexed by object.
  std::vector<bool> mayBeVisible(const std::vector<std::size_t>& candidates, float time) const;
  // The boxes' near sides (front faces, nearer by a few depth units) or far sides (back faces,
  // farther), each in an occlusion query with the bound depth function; a box the near plane
  // cuts passes, an empty one fails. Leaves face culling (its mode and winding) and depth
  // writes as it found them, and colour writes on.
  enum class Side { nearSide, farSide };
  std::vector<bool> boxesPass(const std::vector<std::size_t>& candidates, float time, Side side,
                              GLuint program) const;
};

}  // namespace cutaway
