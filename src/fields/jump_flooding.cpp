// Jump flooding of the cutaway surface on the CPU (Burns08 §5.1, Burns11 §5.1.2.3; Rong & Tan
// 2006): every step, each pixel keeps the anchor whose cone c(p, q) (Burns11 eq. 4.1 with the
// directional slope of Burns08 §5.5 / Burns11 eq. 6.3) is deepest among its own and those of
// its 8 neighbours at distance k. Same step order, candidate order and strict comparison as
// src/cutters/adaptive/jump_flooding.comp, so CPU and GPU agree up to float rounding.
//
// Speed (bench/bench_fields.cpp): a pixel's state is its anchor's whole cone (position, z,
// slopes, floor direction) plus that cone's depth at the pixel, in structure-of-arrays rows,
// so the candidates of 8 adjacent pixels are 8 contiguous, shifted row loads (no gathers) and
// the pixel's own anchor needs no evaluation (c(p, a) depends on p and a only: the previous
// step computed it). An AVX2 + FMA kernel, chosen at run time, evaluates 8 pixels at once;
// other machines run the scalar kernel. Rows are shared out to threads in chunks; a pixel is
// always computed by the same code, so the result does not depend on the number of threads.
#include <algorithm>
#include <atomic>
#include <barrier>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <system_error>
#include <thread>

#include "cutaway/fields/cutaway_surface.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define CUTAWAY_FIELDS_X86 1
// Compiles a function for AVX2 + FMA whatever the build's baseline; it only runs after the
// run-time check in rowKernel(). (GCC's target_clones cannot hold these intrinsics.)
#define CUTAWAY_AVX2 __attribute__((target("avx2,fma")))
#define CUTAWAY_AVX2_INLINE __attribute__((target("avx2,fma"), always_inline)) inline
#endif

namespace cutaway::fields {

namespace {

// A pixel with no anchor yet has depth and z = −∞ and slopes 0: its cone is −∞ everywhere,
// never strictly deeper than anything.
constexpr float kNoDepth = -std::numeric_limits<float>::infinity();
constexpr int kRowsPerChunk = 8;  // rows a thread claims at once: small enough to balance

// The cone, rewritten for speed. With d = ‖Δ‖ and a = clamp(−Δ·f, 0, d) (= α·d, Burns11
// eq. 6.3 with q − p = −Δ, no division), the slope of the header, (1 − α) m_E + α m_F
// (Burns08 §5.5), times d is
//   m_low·d + |m_F − m_E|·b,  m_low = min(m_E, m_F),  b = a if m_F ≥ m_E else d − a,
// so c(p, q) = bound − |m_F − m_E|·b with bound = z − m_low·d, and c ≤ bound exactly in
// floating point too (the subtrahend is never negative). A candidate whose bound does not beat
// the current depth at any of 8 pixels cannot win there and is skipped before the directional
// part; at the apex (d = 0) both give z, i.e. α = 0 as the header asks. Without a directional
// constraint m_low = m_E and c = bound.

// One of the two buffers of the state, one entry per pixel.
struct AnchorBuffer {
  float* depth;                         // c(p, a(p))
  std::int32_t* anchor;                 // a(p)'s position, x | y << 16
  float *z, *slopeLow;                  // its cone: z and m_low
  float *slopeDelta, *floorX, *floorY;  // m_F − m_E and f, when there is a directional constraint
};

// Scratch state kept between calls on the same thread: a 1024² pair is 32–56 MB, and on some
// systems faulting that much fresh memory in costs more than the flooding itself.
// The 14 arrays share one allocation, the i-th starting i·256 bytes past a multiple of 4 KiB:
// at equal offsets modulo 4 KiB the kernel's 3 input rows of each array and its output rows
// would all fall in the same L1 cache sets, which measured 1.7× slower at 1024².
struct Workspace {
  static constexpr std::size_t kArrays = 14, kPage = 4096, kStagger = 256;
  std::size_t capacity = 0;              // pixels
  std::unique_ptr<std::byte[]> storage;  // implicitly creates the float and int32 arrays
  AnchorBuffer buffers[2];

  void reserve(std::size_t n) {
    if (n <= capacity) return;
    capacity = n;
    const std::size_t stride = (n * 4 + kPage - 1) / kPage * kPage + kStagger;
    storage = std::make_unique_for_overwrite<std::byte[]>(kArrays * stride + 64);
    // 64-byte aligned start, so that the stagger is relative to page and line boundaries.
    std::byte* a = storage.get() + (64 - reinterpret_cast<std::uintptr_t>(storage.get()) % 64) % 64;
    for (AnchorBuffer& b : buffers) {
      b.anchor = reinterpret_cast<std::int32_t*>(a);
      a += stride;
      for (float** p : {&b.depth, &b.z, &b.slopeLow, &b.slopeDelta, &b.floorX, &b.floorY}) {
        *p = reinterpret_cast<float*>(a);
        a += stride;
      }
    }
  }
};

// Row y of a buffer. Read-only rows outside the image have depth == nullptr; the last step's
// output row has only depth and anchor.
template <typename Float, typename Int>
struct Row {
  Float* depth = nullptr;
  Int* anchor = nullptr;
  Float *z = nullptr, *slopeLow = nullptr, *slopeDelta = nullptr, *floorX = nullptr,
        *floorY = nullptr;
};
using InRow = Row<const float, const std::int32_t>;
using OutRow = Row<float, std::int32_t>;

template <typename R>
R row(const AnchorBuffer& b, std::size_t offset, bool directional) {
  R r{b.depth + offset, b.anchor + offset, b.z + offset, b.slopeLow + offset};
  if (directional) {
    r.slopeDelta = b.slopeDelta + offset;
    r.floorX = b.floorX + offset;
    r.floorY = b.floorY + offset;
  }
  return r;
}

// One row of one step: p = (x, y) for x in [0, width).
struct RowTask {
  InRow rows[3];  // rows y − k, y, y + k (index dy + 1)
  OutRow out;
  int width, step;
  float y, unitX, unitY;
};

// ---- scalar kernel ---------------------------------------------------------------------

template <bool kDirectional>
float coneDepthScalar(const InRow& q, int i, float px, float py, float unitX, float unitY) {
  const auto a = std::uint32_t(q.anchor[i]);
  const float dx = (px - float(a & 0xFFFF)) * unitX;  // p − q is exact; only the scaling rounds
  const float dy = (py - float(a >> 16)) * unitY;
  const float distance = std::sqrt(dx * dx + dy * dy);
  const float bound = q.z[i] - q.slopeLow[i] * distance;
  if constexpr (!kDirectional) return bound;
  const float alphaDistance = std::clamp(-(dx * q.floorX[i] + dy * q.floorY[i]), 0.0f, distance);
  const float delta = q.slopeDelta[i];
  return bound - std::abs(delta) * (std::signbit(delta) ? distance - alphaDistance : alphaDistance);
}

template <bool kDirectional>
void floodRowScalar(const RowTask& t) {
  for (int x = 0; x < t.width; ++x) {
    const InRow* best = &t.rows[1];
    int bestIndex = x;
    float bestDepth = t.rows[1].depth[x];
    for (int dy = -1; dy <= 1; ++dy) {
      const InRow& r = t.rows[dy + 1];
      if (!r.depth) continue;
      for (int dx = -1; dx <= 1; ++dx) {
        const int qx = x + dx * t.step;
        if ((dx == 0 && dy == 0) || qx < 0 || qx >= t.width) continue;
        const float c = coneDepthScalar<kDirectional>(r, qx, float(x), t.y, t.unitX, t.unitY);
        if (c > bestDepth) {  // strict, as the GPU
          bestDepth = c;
          best = &r;
          bestIndex = qx;
        }
      }
    }
    t.out.depth[x] = bestDepth;
    t.out.anchor[x] = best->anchor[bestIndex];
    if (!t.out.z) continue;  // the last step: nothing reads the cones any more
    t.out.z[x] = best->z[bestIndex];
    t.out.slopeLow[x] = best->slopeLow[bestIndex];
    if constexpr (kDirectional) {
      t.out.slopeDelta[x] = best->slopeDelta[bestIndex];
      t.out.floorX[x] = best->floorX[bestIndex];
      t.out.floorY[x] = best->floorY[bestIndex];
    }
  }
}

// ---- AVX2 kernel -----------------------------------------------------------------------

#if CUTAWAY_FIELDS_X86

// 8 values from p, or those of the lanes set in mask (a segment's last, partial vector).
template <bool kMasked>
CUTAWAY_AVX2_INLINE __m256 load8(const float* p, __m256i mask) {
  if constexpr (kMasked)
    return _mm256_maskload_ps(p, mask);
  else
    return _mm256_loadu_ps(p);
}
template <bool kMasked>
CUTAWAY_AVX2_INLINE __m256 load8(const std::int32_t* p, __m256i mask) {
  return load8<kMasked>(reinterpret_cast<const float*>(p), mask);  // the bits, for blending
}
template <bool kMasked>
CUTAWAY_AVX2_INLINE void store8(float* p, __m256i mask, __m256 v) {
  if constexpr (kMasked)
    _mm256_maskstore_ps(p, mask, v);
  else
    _mm256_storeu_ps(p, v);
}
template <bool kMasked>
CUTAWAY_AVX2_INLINE void store8(std::int32_t* p, __m256i mask, __m256 v) {
  store8<kMasked>(reinterpret_cast<float*>(p), mask, v);
}

// The state of 8 adjacent pixels.
struct Lanes {
  __m256 depth, anchor, z, slopeLow, slopeDelta, floorX, floorY;
};

// The pixels' coordinates and the view-plane units, the same for all candidates.
struct Pixels {
  __m256 x, y, unitX, unitY;
};

// One candidate for 8 pixels: the anchors in `row` at x … x+7 replace the current ones where
// their cones are strictly deeper (the GPU's comparison).
template <bool kDirectional, bool kMasked>
CUTAWAY_AVX2_INLINE void considerAvx2(Lanes& best, const InRow& row, int x, const Pixels& p,
                                      __m256i mask) {
  Lanes q;
  q.anchor = load8<kMasked>(row.anchor + x, mask);
  q.z = load8<kMasked>(row.z + x, mask);
  q.slopeLow = load8<kMasked>(row.slopeLow + x, mask);
  const __m256i a = _mm256_castps_si256(q.anchor);
  const __m256 qx = _mm256_cvtepi32_ps(_mm256_and_si256(a, _mm256_set1_epi32(0xFFFF)));
  const __m256 qy = _mm256_cvtepi32_ps(_mm256_srli_epi32(a, 16));
  const __m256 dx = _mm256_mul_ps(_mm256_sub_ps(p.x, qx), p.unitX);
  const __m256 dy = _mm256_mul_ps(_mm256_sub_ps(p.y, qy), p.unitY);
  // Exact sqrt: as fast here as rsqrt with a Newton step, since nothing divides by it.
  const __m256 distance = _mm256_sqrt_ps(_mm256_fmadd_ps(dx, dx, _mm256_mul_ps(dy, dy)));
  __m256 depth = _mm256_fnmadd_ps(q.slopeLow, distance, q.z);    // the bound
  __m256 deeper = _mm256_cmp_ps(depth, best.depth, _CMP_GT_OQ);  // strict, as the GPU
  if constexpr (kDirectional) {
    // About 4 in 5 candidates lose at all 8 pixels. Skipping them pays with the directional
    // part to skip (measured 7–15% faster); for the plain cone, the mispredicted branches
    // cost more than the blends they save (5–10% slower).
    if (_mm256_movemask_ps(deeper) == 0) return;
    q.slopeDelta = load8<kMasked>(row.slopeDelta + x, mask);
    q.floorX = load8<kMasked>(row.floorX + x, mask);
    q.floorY = load8<kMasked>(row.floorY + x, mask);
    const __m256 along = _mm256_fnmsub_ps(dx, q.floorX, _mm256_mul_ps(dy, q.floorY));  // −Δ·f
    const __m256 alphaDistance = _mm256_min_ps(_mm256_max_ps(along, _mm256_setzero_ps()), distance);
    // b = a, or d − a where m_F − m_E is negative (blendv reads the sign bit).
    const __m256 b =
        _mm256_blendv_ps(alphaDistance, _mm256_sub_ps(distance, alphaDistance), q.slopeDelta);
    const __m256 magnitude = _mm256_andnot_ps(_mm256_set1_ps(-0.0f), q.slopeDelta);
    depth = _mm256_fnmadd_ps(magnitude, b, depth);
    deeper = _mm256_cmp_ps(depth, best.depth, _CMP_GT_OQ);
  }
  best.depth = _mm256_max_ps(depth, best.depth);  // = blend(best, depth, deeper)
  best.anchor = _mm256_blendv_ps(best.anchor, q.anchor, deeper);
  best.z = _mm256_blendv_ps(best.z, q.z, deeper);
  best.slopeLow = _mm256_blendv_ps(best.slopeLow, q.slopeLow, deeper);
  if constexpr (kDirectional) {
    best.slopeDelta = _mm256_blendv_ps(best.slopeDelta, q.slopeDelta, deeper);
    best.floorX = _mm256_blendv_ps(best.floorX, q.floorX, deeper);
    best.floorY = _mm256_blendv_ps(best.floorY, q.floorY, deeper);
  }
}

// 8 pixels x … x+7 (fewer when kMasked) whose left (x − k) and right (x + k) neighbours are
// inside the image exactly when kLeft, kRight. Candidates in the GPU's order: dy outer, dx
// inner, the pixel's own anchor first.
template <bool kDirectional, bool kLeft, bool kRight, bool kMasked>
CUTAWAY_AVX2_INLINE void floodVectorAvx2(const RowTask& t, int x, __m256i mask) {
  const Pixels p{_mm256_add_ps(_mm256_set1_ps(float(x)),
                               _mm256_setr_ps(0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f)),
                 _mm256_set1_ps(t.y), _mm256_set1_ps(t.unitX), _mm256_set1_ps(t.unitY)};
  const int k = t.step;
  const InRow& own = t.rows[1];
  Lanes best;
  best.depth = load8<kMasked>(own.depth + x, mask);
  best.anchor = load8<kMasked>(own.anchor + x, mask);
  best.z = load8<kMasked>(own.z + x, mask);
  best.slopeLow = load8<kMasked>(own.slopeLow + x, mask);
  if constexpr (kDirectional) {
    best.slopeDelta = load8<kMasked>(own.slopeDelta + x, mask);
    best.floorX = load8<kMasked>(own.floorX + x, mask);
    best.floorY = load8<kMasked>(own.floorY + x, mask);
  }
  if (const InRow& below = t.rows[0]; below.depth) {
    if constexpr (kLeft) considerAvx2<kDirectional, kMasked>(best, below, x - k, p, mask);
    considerAvx2<kDirectional, kMasked>(best, below, x, p, mask);
    if constexpr (kRight) considerAvx2<kDirectional, kMasked>(best, below, x + k, p, mask);
  }
  if constexpr (kLeft) considerAvx2<kDirectional, kMasked>(best, own, x - k, p, mask);
  if constexpr (kRight) considerAvx2<kDirectional, kMasked>(best, own, x + k, p, mask);
  if (const InRow& above = t.rows[2]; above.depth) {
    if constexpr (kLeft) considerAvx2<kDirectional, kMasked>(best, above, x - k, p, mask);
    considerAvx2<kDirectional, kMasked>(best, above, x, p, mask);
    if constexpr (kRight) considerAvx2<kDirectional, kMasked>(best, above, x + k, p, mask);
  }
  const OutRow& o = t.out;
  store8<kMasked>(o.depth + x, mask, best.depth);
  store8<kMasked>(o.anchor + x, mask, best.anchor);
  if (!o.z) return;  // the last step: nothing reads the cones any more
  store8<kMasked>(o.z + x, mask, best.z);
  store8<kMasked>(o.slopeLow + x, mask, best.slopeLow);
  if constexpr (kDirectional) {
    store8<kMasked>(o.slopeDelta + x, mask, best.slopeDelta);
    store8<kMasked>(o.floorX + x, mask, best.floorX);
    store8<kMasked>(o.floorY + x, mask, best.floorY);
  }
}

template <bool kDirectional, bool kLeft, bool kRight>
CUTAWAY_AVX2 void floodSegmentAvx2(const RowTask& task, int x0, int x1) {
  const RowTask t = task;  // a local copy, which the stores cannot alias
  int x = x0;
  for (; x + 8 <= x1; x += 8)
    floodVectorAvx2<kDirectional, kLeft, kRight, false>(t, x, _mm256_setzero_si256());
  if (x < x1) {
    const __m256i mask =
        _mm256_cmpgt_epi32(_mm256_set1_epi32(x1 - x), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
    floodVectorAvx2<kDirectional, kLeft, kRight, true>(t, x, mask);
  }
}

// Splits the row where the left neighbour enters (x = k) and the right one leaves
// (x = width − k) the image, so that each piece runs without per-pixel bounds checks.
template <bool kDirectional>
CUTAWAY_AVX2 void floodRowAvx2(const RowTask& t) {
  const int w = t.width, k = t.step;
  int cuts[4] = {0, std::min(k, w), std::max(w - k, 0), w};
  std::sort(cuts, cuts + 4);
  for (int i = 0; i < 3; ++i) {
    const int x0 = cuts[i], x1 = cuts[i + 1];
    if (x0 == x1) continue;
    const bool left = x0 >= k, right = x1 <= w - k;
    if (left && right)
      floodSegmentAvx2<kDirectional, true, true>(t, x0, x1);
    else if (left)
      floodSegmentAvx2<kDirectional, true, false>(t, x0, x1);
    else if (right)
      floodSegmentAvx2<kDirectional, false, true>(t, x0, x1);
    else
      floodSegmentAvx2<kDirectional, false, false>(t, x0, x1);
  }
}

#endif  // CUTAWAY_FIELDS_X86

using RowKernel = void (*)(const RowTask&);

RowKernel rowKernel(bool directional, [[maybe_unused]] JumpFloodingKernel choice) {
#if CUTAWAY_FIELDS_X86
  __builtin_cpu_init();
  if (choice == JumpFloodingKernel::automatic && __builtin_cpu_supports("avx2") &&
      __builtin_cpu_supports("fma"))
    return directional ? floodRowAvx2<true> : floodRowAvx2<false>;
#endif
  return directional ? floodRowScalar<true> : floodRowScalar<false>;
}

// The i-th row a step of size k computes: the rows y ≡ 0 (mod k) bottom to top, then y ≡ 1,
// and so on. Row y reads rows y − k, y and y + k, so in this order each input row is read three
// times in a row, not k rows apart: at 1024² the directional state (56 MB) exceeds the cache,
// and the large steps ran from memory.
int rowInStepOrder(int i, int h, int k) {
  const int q = h / k, longResidues = h % k;  // residues below h % k have q + 1 rows, others q
  if (i < longResidues * (q + 1)) return i / (q + 1) + i % (q + 1) * k;
  const int rest = i - longResidues * (q + 1);
  return longResidues + rest / q + rest % q * k;
}

// Every seed starts as its own anchor, at distance 0 (jfa_init.frag); other pixels have none.
// One simple loop per array, for the vectoriser.
void initialiseRow(const SeedImage& s, const OutRow& o, int y, bool directional) {
  const int w = s.width;
  const std::size_t row = std::size_t(y) * std::size_t(w);
  const std::uint8_t* seeded = s.seeded.data() + row;
  const float *depth = s.depth.data() + row, *slopeE = s.slopeE.data() + row,
              *slopeF = s.slopeF.data() + row;
  for (int x = 0; x < w; ++x) {
    const float z = depth[x];
    o.depth[x] = seeded[x] ? z : kNoDepth;
    o.z[x] = seeded[x] ? z : kNoDepth;
  }
  for (int x = 0; x < w; ++x) o.anchor[x] = x | y << 16;
  if (!directional) {
    for (int x = 0; x < w; ++x) {
      const float m = slopeE[x];
      o.slopeLow[x] = seeded[x] ? m : 0.0f;
    }
    return;
  }
  const float *floorX = s.floorX.data() + row, *floorY = s.floorY.data() + row;
  for (int x = 0; x < w; ++x) {
    const float mE = slopeE[x], mF = slopeF[x];
    o.slopeLow[x] = seeded[x] ? std::min(mE, mF) : 0.0f;
  }
  for (int x = 0; x < w; ++x) {
    const float delta = slopeF[x] - slopeE[x];
    o.slopeDelta[x] = seeded[x] ? delta : 0.0f;
  }
  for (int x = 0; x < w; ++x) {
    const float fx = floorX[x], fy = floorY[x];
    o.floorX[x] = seeded[x] ? fx : 0.0f;
    o.floorY[x] = seeded[x] ? fy : 0.0f;
  }
}

// C(p) = max(nearDepth, c(p, a(p))) (Burns11 eq. 4.2, clamped); the anchor only where it
// beats the near plane.
void finishRow(const InRow& r, int width, int y, float nearDepth, CutawayField& f) {
  const std::size_t row = std::size_t(y) * std::size_t(width);
  for (int x = 0; x < width; ++x) {
    const float c = r.depth[x];
    const auto a = std::uint32_t(r.anchor[x]);
    f.depth[row + std::size_t(x)] = std::max(c, nearDepth);
    f.anchor[row + std::size_t(x)] = c > nearDepth ? int(a >> 16) * width + int(a & 0xFFFF) : -1;
  }
}

}  // namespace

CutawayField jumpFlooding(const SeedImage& seeds, float nearDepth, JumpFloodingVariant variant,
                          int threads, JumpFloodingKernel kernelChoice) {
  CutawayField f;
  jumpFlooding(seeds, nearDepth, f, variant, threads, kernelChoice);
  return f;
}

void jumpFlooding(const SeedImage& seeds, float nearDepth, CutawayField& f,
                  JumpFloodingVariant variant, int threads, JumpFloodingKernel kernelChoice) {
  const int w = seeds.width, h = seeds.height;
  assert(w > 0 && h > 0 && w <= 65536 && h <= 65536 && "anchors are packed in 16 + 16 bits");
  assert(std::size_t(w) * std::size_t(h) <= std::size_t(std::numeric_limits<int>::max()));
  const std::size_t n = std::size_t(w) * std::size_t(h);
  // Without a floor direction anywhere, α = 0 and the cone is z − m_E‖Δ‖: the kernel then
  // neither carries nor evaluates m_F and f.
  bool directional = false;
  for (std::size_t row = 0; row < n && !directional; row += std::size_t(w)) {
    const std::uint8_t* seeded = seeds.seeded.data() + row;
    const float *floorX = seeds.floorX.data() + row, *floorY = seeds.floorY.data() + row;
    int any = 0;  // no early exit within a row, so that the loop vectorises
    for (int x = 0; x < w; ++x)
      any |= (seeded[x] != 0) & ((floorX[x] != 0.0f) | (floorY[x] != 0.0f));
    directional = any != 0;
  }
  const RowKernel kernel = rowKernel(directional, kernelChoice);
  const std::vector<int> steps = stepSizes(w, h, variant);

  thread_local Workspace workspace;
  workspace.reserve(n);
  const AnchorBuffer* buffers = workspace.buffers;
  f.width = w;
  f.height = h;
  f.depth.resize(n);  // every element is written by finishRow()
  f.anchor.resize(n);

  // Phase 0 initialises buffer 0, phase s + 1 runs step s from buffer s % 2 into the other;
  // all threads finish a phase before any starts the next, since a step reads the previous
  // step's anchors only. The last phase also writes the result.
  const int phases = int(steps.size()) + 1;
  auto runRow = [&](int phase, int y) {
    const std::size_t offset = std::size_t(y) * std::size_t(w);
    const AnchorBuffer& out = buffers[phase % 2];
    if (phase == 0) {
      initialiseRow(seeds, row<OutRow>(out, offset, directional), y, directional);
    } else {
      const AnchorBuffer& in = buffers[(phase - 1) % 2];
      const int k = steps[std::size_t(phase - 1)];
      RowTask t{};
      for (int dy = -1; dy <= 1; ++dy)
        if (const int qy = y + dy * k; qy >= 0 && qy < h)
          t.rows[dy + 1] = row<InRow>(in, std::size_t(qy) * std::size_t(w), directional);
      t.out = row<OutRow>(out, offset, directional);
      if (phase == phases - 1) t.out = {t.out.depth, t.out.anchor};
      t.width = w;
      t.step = k;
      t.y = float(y);
      t.unitX = seeds.unitX;
      t.unitY = seeds.unitY;
      kernel(t);
    }
    if (phase == phases - 1) finishRow(row<InRow>(out, offset, false), w, y, nearDepth, f);
  };

  const int rowChunks = (h + kRowsPerChunk - 1) / kRowsPerChunk;
  const int workers = std::clamp(
      threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency())), 1, rowChunks);
  const auto nextChunk = std::make_unique<std::atomic<int>[]>(std::size_t(phases));
  std::barrier phaseDone(workers);
  auto work = [&] {
    for (int phase = 0; phase < phases; ++phase) {
      for (int chunk; (chunk = nextChunk[std::size_t(phase)].fetch_add(1)) < rowChunks;)
        for (int i = chunk * kRowsPerChunk; i < std::min(h, (chunk + 1) * kRowsPerChunk); ++i)
          runRow(phase, phase == 0 ? i : rowInStepOrder(i, h, steps[std::size_t(phase - 1)]));
      phaseDone.arrive_and_wait();
    }
  };
  std::vector<std::jthread> helpers;
  try {
    for (int i = 1; i < workers; ++i) helpers.emplace_back(work);
  } catch (const std::system_error&) {
    // Fewer threads than asked for: the barrier stops waiting for the missing ones and the
    // threads there are take all the rows.
    for (int i = int(helpers.size()) + 1; i < workers; ++i) phaseDone.arrive_and_drop();
  }
  work();
}

}  // namespace cutaway::fields
