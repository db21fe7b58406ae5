// Jump flooding of the cutaway surface on the CPU (Burns08 §5.1, Burns11 §5.1.2.3; Rong & Tan
// 2006): every step, each pixel keeps the anchor whose cone c(p, q) (Burns11 eq. 4.1 with the
// directional slope of Burns08 §5.5 / Burns11 eq. 6.3) is deepest among its own and those of
// its 8 neighbours at distance k. Same step order, candidate order and strict comparison as
// src/cutters/adaptive/jump_flooding.comp, so CPU and GPU agree up to float rounding.
//
// Speed (bench/bench_fields.cpp): a pixel's state is its anchor's whole cone (position, z,
// slopes, floor direction) plus that cone's depth at the pixel, in structure-of-arrays rows,
// so the candidates of adjacent pixels are contiguous, shifted row loads (no gathers) and
// the pixel's own anchor needs no evaluation (c(p, a) depends on p and a only: the previous
// step computed it). A vector kernel (jump_flooding_simd.inc), chosen at run time, evaluates
// 16 pixels at once with AVX-512 or 8 with AVX2; other machines run the scalar kernel. Rows are
// shared out to threads in chunks; a pixel is always computed by the same code, so the result does
// not depend on the number of threads.
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
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ < 13
// GCC 12's AVX-512 intrinsics start from `__m512 __Y = __Y;` (_mm512_undefined_ps), which
// its own -Wmaybe-uninitialized reports at every use (a false positive of its headers).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <immintrin.h>
// The vector kernels are compiled for their instruction sets whatever the build's baseline
// (target attributes; GCC's target_clones cannot hold these intrinsics) and run only after
// the run-time check in rowKernel().
#define CUTAWAY_FIELDS_X86 1
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

// ---- vector kernels (jump_flooding_simd.inc) -------------------------------------------

#if CUTAWAY_FIELDS_X86

// The kernels' helpers are forced inline, but not under AddressSanitizer: clang-14's
// instrumentation of the fully inlined rows took 70-100 s for this file against 6 s
// (the CI's sanitizer build); the sanitizers check the same code paths either way.
// (clang-14 defines no __SANITIZE_ADDRESS__ when UndefinedBehaviorSanitizer is on too.)
#define CUTAWAY_SIMD_FORCE_INLINE , always_inline
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#undef CUTAWAY_SIMD_FORCE_INLINE
#define CUTAWAY_SIMD_FORCE_INLINE
#endif
#endif

namespace avx2 {

#define CUTAWAY_SIMD_INLINE __attribute__((target("avx2,fma") CUTAWAY_SIMD_FORCE_INLINE)) inline
#define CUTAWAY_SIMD_FUNCTION __attribute__((target("avx2,fma")))
// 8 lanes; a mask is a compare's result, lanes of all ones or zeros.
struct Simd {
  static constexpr int kWidth = 8;
  using F = __m256;
  using Mask = __m256;
  using Tail = __m256i;  // the lanes a partial vector loads and stores
  static CUTAWAY_SIMD_INLINE Tail tail(int lanes) {
    return _mm256_cmpgt_epi32(_mm256_set1_epi32(lanes), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
  }
  static CUTAWAY_SIMD_INLINE F load(const float* p) { return _mm256_loadu_ps(p); }
  static CUTAWAY_SIMD_INLINE F load(const float* p, Tail t) { return _mm256_maskload_ps(p, t); }
  static CUTAWAY_SIMD_INLINE void store(float* p, F v) { _mm256_storeu_ps(p, v); }
  static CUTAWAY_SIMD_INLINE void store(float* p, Tail t, F v) { _mm256_maskstore_ps(p, t, v); }
  static CUTAWAY_SIMD_INLINE F set1(float v) { return _mm256_set1_ps(v); }
  static CUTAWAY_SIMD_INLINE F iota() {
    return _mm256_setr_ps(0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f);
  }
  static CUTAWAY_SIMD_INLINE F zero() { return _mm256_setzero_ps(); }
  static CUTAWAY_SIMD_INLINE F add(F a, F b) { return _mm256_add_ps(a, b); }
  static CUTAWAY_SIMD_INLINE F sub(F a, F b) { return _mm256_sub_ps(a, b); }
  static CUTAWAY_SIMD_INLINE F mul(F a, F b) { return _mm256_mul_ps(a, b); }
  static CUTAWAY_SIMD_INLINE F fmadd(F a, F b, F c) { return _mm256_fmadd_ps(a, b, c); }
  static CUTAWAY_SIMD_INLINE F fnmadd(F a, F b, F c) { return _mm256_fnmadd_ps(a, b, c); }
  static CUTAWAY_SIMD_INLINE F fnmsub(F a, F b, F c) { return _mm256_fnmsub_ps(a, b, c); }
  static CUTAWAY_SIMD_INLINE F sqrt(F a) { return _mm256_sqrt_ps(a); }
  static CUTAWAY_SIMD_INLINE F min(F a, F b) { return _mm256_min_ps(a, b); }
  static CUTAWAY_SIMD_INLINE F max(F a, F b) { return _mm256_max_ps(a, b); }
  static CUTAWAY_SIMD_INLINE F abs(F a) { return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), a); }
  // An anchor's packed position (x | y << 16, in the bits of a float) as floats.
  static CUTAWAY_SIMD_INLINE F anchorX(F a) {
    return _mm256_cvtepi32_ps(_mm256_and_si256(_mm256_castps_si256(a), _mm256_set1_epi32(0xFFFF)));
  }
  static CUTAWAY_SIMD_INLINE F anchorY(F a) {
    return _mm256_cvtepi32_ps(_mm256_srli_epi32(_mm256_castps_si256(a), 16));
  }
  static CUTAWAY_SIMD_INLINE Mask greater(F a, F b) { return _mm256_cmp_ps(a, b, _CMP_GT_OQ); }
  static CUTAWAY_SIMD_INLINE bool none(Mask m) { return _mm256_movemask_ps(m) == 0; }
  static CUTAWAY_SIMD_INLINE F select(Mask m, F unset, F set) {
    return _mm256_blendv_ps(unset, set, m);
  }
  static CUTAWAY_SIMD_INLINE F selectBySign(F sign, F positive, F negative) {
    return _mm256_blendv_ps(positive, negative, sign);  // reads the sign bits
  }
};
#include "jump_flooding_simd.inc"
#undef CUTAWAY_SIMD_INLINE
#undef CUTAWAY_SIMD_FUNCTION

}  // namespace avx2

// 16 lanes: Zen 5 and recent Intel processors run them at about the cost of 8 (the 32 registers
// alone gained nothing: bench/RESULTS.md, the 8-lane kernel compiled for AVX-512VL).
namespace avx512 {

#define CUTAWAY_SIMD_INLINE \
  __attribute__((target("avx512f,avx512dq,fma") CUTAWAY_SIMD_FORCE_INLINE)) inline
#define CUTAWAY_SIMD_FUNCTION __attribute__((target("avx512f,avx512dq,fma")))
struct Simd {
  static constexpr int kWidth = 16;
  using F = __m512;
  using Mask = __mmask16;
  using Tail = __mmask16;
  static CUTAWAY_SIMD_INLINE Tail tail(int lanes) { return Tail((1u << lanes) - 1u); }
  static CUTAWAY_SIMD_INLINE F load(const float* p) { return _mm512_loadu_ps(p); }
  static CUTAWAY_SIMD_INLINE F load(const float* p, Tail t) { return _mm512_maskz_loadu_ps(t, p); }
  static CUTAWAY_SIMD_INLINE void store(float* p, F v) { _mm512_storeu_ps(p, v); }
  static CUTAWAY_SIMD_INLINE void store(float* p, Tail t, F v) { _mm512_mask_storeu_ps(p, t, v); }
  static CUTAWAY_SIMD_INLINE F set1(float v) { return _mm512_set1_ps(v); }
  static CUTAWAY_SIMD_INLINE F iota() {
    return _mm512_set_ps(15.0f, 14.0f, 13.0f, 12.0f, 11.0f, 10.0f, 9.0f, 8.0f, 7.0f, 6.0f, 5.0f,
                         4.0f, 3.0f, 2.0f, 1.0f, 0.0f);
  }
  static CUTAWAY_SIMD_INLINE F zero() { return _mm512_setzero_ps(); }
  static CUTAWAY_SIMD_INLINE F add(F a, F b) { return _mm512_add_ps(a, b); }
  static CUTAWAY_SIMD_INLINE F sub(F a, F b) { return _mm512_sub_ps(a, b); }
  static CUTAWAY_SIMD_INLINE F mul(F a, F b) { return _mm512_mul_ps(a, b); }
  static CUTAWAY_SIMD_INLINE F fmadd(F a, F b, F c) { return _mm512_fmadd_ps(a, b, c); }
  static CUTAWAY_SIMD_INLINE F fnmadd(F a, F b, F c) { return _mm512_fnmadd_ps(a, b, c); }
  static CUTAWAY_SIMD_INLINE F fnmsub(F a, F b, F c) { return _mm512_fnmsub_ps(a, b, c); }
  static CUTAWAY_SIMD_INLINE F sqrt(F a) { return _mm512_sqrt_ps(a); }
  static CUTAWAY_SIMD_INLINE F min(F a, F b) { return _mm512_min_ps(a, b); }
  static CUTAWAY_SIMD_INLINE F max(F a, F b) { return _mm512_max_ps(a, b); }
  static CUTAWAY_SIMD_INLINE F abs(F a) { return _mm512_abs_ps(a); }
  static CUTAWAY_SIMD_INLINE F anchorX(F a) {
    return _mm512_cvtepi32_ps(_mm512_and_si512(_mm512_castps_si512(a), _mm512_set1_epi32(0xFFFF)));
  }
  static CUTAWAY_SIMD_INLINE F anchorY(F a) {
    return _mm512_cvtepi32_ps(_mm512_srli_epi32(_mm512_castps_si512(a), 16));
  }
  static CUTAWAY_SIMD_INLINE Mask greater(F a, F b) { return _mm512_cmp_ps_mask(a, b, _CMP_GT_OQ); }
  static CUTAWAY_SIMD_INLINE bool none(Mask m) { return m == 0; }
  static CUTAWAY_SIMD_INLINE F select(Mask m, F unset, F set) {
    return _mm512_mask_blend_ps(m, unset, set);
  }
  static CUTAWAY_SIMD_INLINE F selectBySign(F sign, F positive, F negative) {
    return _mm512_mask_blend_ps(_mm512_movepi32_mask(_mm512_castps_si512(sign)), positive,
                                negative);
  }
};
#include "jump_flooding_simd.inc"
#undef CUTAWAY_SIMD_INLINE
#undef CUTAWAY_SIMD_FUNCTION

}  // namespace avx512

#undef CUTAWAY_SIMD_FORCE_INLINE
#endif  // CUTAWAY_FIELDS_X86

using RowKernel = void (*)(const RowTask&);

RowKernel rowKernel(bool directional, [[maybe_unused]] JumpFloodingKernel choice) {
#if CUTAWAY_FIELDS_X86
  __builtin_cpu_init();
  const bool fma = __builtin_cpu_supports("fma");
  if (choice == JumpFloodingKernel::automatic && fma && __builtin_cpu_supports("avx512f") &&
      __builtin_cpu_supports("avx512dq"))
    return directional ? avx512::floodRow<true> : avx512::floodRow<false>;
  if (choice != JumpFloodingKernel::scalar && fma && __builtin_cpu_supports("avx2"))
    return directional ? avx2::floodRow<true> : avx2::floodRow<false>;
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
  CutawayField f;
  f.width = w;
  f.height = h;
  f.depth.resize(n);
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
  return f;
}

}  // namespace cutaway::fields
