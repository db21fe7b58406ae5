// cutaway/fields/cutaway_surface.hpp — CPU computation of the cutaway surface
// C(p) = max_q (z(q) − m‖q − p‖)   (Burns11 eq. 4.2, Burns08 eq. 2)
// over a seed image of the region of interest's rear hull.
//
// These are the reference implementations the GPU passes are checked against, and the fast
// path on machines without a GPU (src/cutters/adaptive picks the CPU jump flooding there).
//
// Conventions (shared with the GLSL in src/cutters/adaptive/):
// - Images are row-major, row 0 at the bottom (OpenGL), pixel (x, y) centred at (x+½, y+½).
// - Depth is NDC z in [−1, 1] (−1 = near plane). A pixel with no seed has `seeded == 0`.
// - Lateral distance between pixels p and q is measured in view-plane units:
//   Δ = ((p.x − q.x)·unitX, (p.y − q.y)·unitY), ‖Δ‖ its Euclidean length.
// - Each seed q carries its own cone: slopes mE(q), mF(q) (NDC depth per view-plane unit) and
//   a unit 2-D direction f(q) (the projected floor normal, (0,0) when there is no directional
//   constraint). The cone from q evaluated at p is
//     c(p, q) = z(q) − ((1 − α) mE(q) + α mF(q))·‖Δ‖,  α = clamp(dot((q − p)/‖q − p‖, f(q)), 0, 1)
//   (Burns08 §5.5 in slope form; Burns11 eq. 6.3); α = 0 when p = q.
// - C(p) = max(nearDepth, max over seeds q of c(p, q)); `anchor` is the index y·width + x of
//   the maximising seed, −1 where no seed beats nearDepth.
//
//   cutaway::fields::SeedImage seeds(512, 512, unitX, unitY);
//   seeds.set(x, y, z, slope, slope, 0, 0);
//   cutaway::fields::CutawayField f = cutaway::fields::jumpFlooding(seeds, -1.0f);
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cutaway::fields {

struct SeedImage {
  int width = 0, height = 0;
  float unitX = 1.0f, unitY = 1.0f;  // view-plane units per pixel
  std::vector<std::uint8_t> seeded;  // 1 where the region of interest's rear hull was drawn
  std::vector<float> depth, slopeE, slopeF, floorX, floorY;

  SeedImage() = default;
  SeedImage(int w, int h, float ux, float uy);
  void set(int x, int y, float z, float mE, float mF, float fx, float fy);
};

struct CutawayField {
  int width = 0, height = 0;
  std::vector<float> depth;  // C(p), NDC
  std::vector<int> anchor;   // maximising seed index, −1 = none
};

// Exact: every pixel against every seed, O(pixels × seeds). For tests and error measurement.
CutawayField bruteForce(const SeedImage& seeds, float nearDepth);

// Borgefors chamfer propagation (Burns11 §5.1.2.2): two raster passes (forward, then
// backward) with a 3×3 kernel (weights 1, √2 in view-plane units) or 5×5 (adds the
// knight's-move 1,2 offsets, √5). A pixel takes the best of its already visited kernel
// neighbours' values minus their anchor's slope mE times the kernel step length; it
// approximates ‖Δ‖ by a sum of steps (the paper's "starburst" artifacts) and ignores the
// directional constraint.
enum class ChamferKernel { k3x3, k5x5 };
CutawayField chamfer(const SeedImage& seeds, float nearDepth, ChamferKernel kernel);

// Jump flooding (Rong & Tan 2006; Burns08 §5.1) evaluating c(p, q) exactly at every step.
// Step sizes: k = 2^⌈log2 max(w, h)⌉ / 2, then halved down to 1 ("jfa"); "jfa+1" appends one
// more step of 1; "1+jfa" prepends a step of 1; "jfa+2" appends steps 2 and 1.
// In each step every pixel p keeps its current anchor a(p) and looks at the anchors of
// p + (dx·k, dy·k) for dy = −1, 0, 1 (outer) and dx = −1, 0, 1 (inner), skipping (0,0) and
// pixels outside the image; a candidate replaces the current one only if its c(p, ·) is
// strictly greater. Every step reads the previous step's anchors (double buffering). This
// order is shared with the GPU shader so both produce the same result up to float rounding.
enum class JumpFloodingVariant { jfa, jfaPlus1, onePlusJfa, jfaPlus2 };
const char* variantName(JumpFloodingVariant v);  // "jfa", "jfa+1", "1+jfa", "jfa+2"
bool parseVariant(const std::string& name, JumpFloodingVariant& out);
std::vector<int> stepSizes(int width, int height, JumpFloodingVariant variant);

// `threads` = 0: one per hardware thread; the result does not depend on it. The kernel is
// AVX-512 (16 pixels at once) or AVX2 (8) with FMA where the processor has them, else portable
// scalar code; `avx2` and `scalar` force the narrower ones. The vector kernels give the same
// bits, the scalar one agrees up to float rounding. Scratch buffers (about 32–56 bytes a
// pixel) are kept between calls on the same thread.
enum class JumpFloodingKernel { automatic, avx2, scalar };
CutawayField jumpFlooding(const SeedImage& seeds, float nearDepth,
                          JumpFloodingVariant variant = JumpFloodingVariant::jfa, int threads = 0,
                          JumpFloodingKernel kernel = JumpFloodingKernel::automatic);

}  // namespace cutaway::fields
