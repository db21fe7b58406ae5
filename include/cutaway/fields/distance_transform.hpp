// cutaway/fields/distance_transform.hpp — distance from every pixel of a 2-D grid to the
// nearest drawn pipe: Konev18 §4's terrain-opening field D_p, compared with the threshold
// t of Konev18 eq. 1 to open the terrain over a sub-terrain network (eqs. 2–3).
//
// The network is drawn into a binary seed image (conservative line rasterisation: every
// pixel a segment touches is a seed, so no gaps, Konev18 §4 "drawn with black lines"), then
// one of two distance transforms runs over it:
// - `l1DistanceTransform`: |Δx| + |Δy| by a horizontal then a vertical 1-D pass (Konev18 §4's
//   default; the diamond-shaped level sets give the paper's zig-zag cut, its Fig. 4a);
// - `euclideanDistanceTransform`: the exact Euclidean distance by Felzenszwalb & Huttenlocher
//   2012's lower envelope of parabolas (the smooth cut of Konev18 Fig. 6).
// `bruteForceL1` and `bruteForceEuclidean` are the O(pixels × seeds) references.
//
// Conventions (shared with cutaway_surface.hpp): images are row-major, row 0 at the bottom;
// pixel (x, y) covers [x, x+1) × [y, y+1) in grid coordinates and has its centre at
// (x+½, y+½). Distances are between pixel centres, in pixels. Every pixel of an image
// without seeds is at +infinity.
//
//   std::vector<cutaway::fields::GridSegment> pipes = {{{2.5f, 3.0f}, {60.0f, 41.5f}}};
//   cutaway::fields::SeedMask seeds = cutaway::fields::rasterizeSegments(64, 48, pipes);
//   cutaway::fields::DistanceField d = cutaway::fields::l1DistanceTransform(seeds);
//   float dp = d.at(10, 20);  // pixels to the nearest pipe pixel, |Δx| + |Δy|
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace cutaway::fields {

// A binary image: 1 where the network was drawn (a seed), 0 elsewhere.
struct SeedMask {
  int width = 0, height = 0;
  std::vector<std::uint8_t> seeded;

  SeedMask() = default;
  SeedMask(int w, int h);  // all zero; w, h ≥ 0
  std::size_t index(int x, int y) const {
    return std::size_t(y) * std::size_t(width) + std::size_t(x);
  }
  bool at(int x, int y) const { return seeded[index(x, y)] != 0; }
  void set(int x, int y) { seeded[index(x, y)] = 1; }
};

struct GridPoint {
  float x = 0.0f, y = 0.0f;  // grid coordinates: pixel (i, j) covers [i, i+1) × [j, j+1)
};
struct GridSegment {
  GridPoint a, b;
};

// Marks every pixel of `mask` that the closed segment a–b passes through (a supercover: a
// segment through a pixel corner marks the pixels on both sides). Each pixel is marked when
// the segment passes within 1e-6 pixel of it, so a point sampled on the segment never falls
// into an unmarked pixel through rounding; no pixel farther than that from the segment is
// marked. Parts outside the image are clipped; segments with a non-finite endpoint are
// ignored. A zero-length segment marks the pixel(s) its point lies in.
void rasterizeSegment(SeedMask& mask, const GridSegment& segment);
SeedMask rasterizeSegments(int width, int height, std::span<const GridSegment> segments);

struct DistanceField {
  int width = 0, height = 0;
  std::vector<float> distance;  // pixels; 0 on seeds, +infinity everywhere if there is none
  float at(int x, int y) const {
    return distance[std::size_t(y) * std::size_t(width) + std::size_t(x)];
  }
};

// L1 (city-block) distance |Δx| + |Δy| to the nearest seed, exact: two 1-D passes (rows,
// then columns), each a forward and a backward sweep, O(pixels) (Konev18 §4 after
// Felzenszwalb & Huttenlocher 2012 §2: the L1 transform is separable).
DistanceField l1DistanceTransform(const SeedMask& seeds);

// Euclidean distance √(Δx² + Δy²) to the nearest seed, exact (squared distances are
// integers computed in double precision; the square root is rounded once to float):
// Felzenszwalb & Huttenlocher 2012 §2.1's lower envelope of parabolas per column, then per
// row, O(pixels).
DistanceField euclideanDistanceTransform(const SeedMask& seeds);

// The two metrics of Konev18 §4's field.
enum class Metric { L1, Euclidean };

// The distance from p to the closed segment s: min over its points q of |p − q|₁ or |p − q|₂.
double segmentDistance(GridPoint p, const GridSegment& s, Metric metric);

// The distance from every pixel centre to the nearest segment itself (not to the pixels it
// was drawn into), in pixels, so that a threshold on it, sampled bilinearly, draws a smooth
// edge at any zoom. Each segment seeds the pixels it passes through (as rasterizeSegment)
// and their 8 neighbours with itself; a forward and a backward raster sweep over 8 neighbours then
// hand each pixel's nearest segment on to its neighbours, every pixel keeping the nearest of its
// own and theirs (Danielsson 1980's vector propagation, segments in place of vectors). Exact under
// L1 (ties go to the Euclidean-nearer segment); under the Euclidean metric within 0.2 pixel, where
// near two crossing segments a third's nearest pixels can be a sliver that no neighbour hands on
// (tests/test_distance_transform.cpp, against `bruteForceSegmentDistance`). Segments outside the
// grid count within `reach` pixels of it (finite, ≥ 0): a distance up to `reach` is found wherever
// its segment lies, a larger one may come from a nearer segment farther out. O((width + 2·reach) ×
// (height + 2·reach) + drawn pixels).
DistanceField segmentDistanceField(int width, int height, std::span<const GridSegment> segments,
                                   Metric metric, float reach);

// References: every pixel against every seed, O(pixels × seeds). For tests.
DistanceField bruteForceL1(const SeedMask& seeds);
DistanceField bruteForceEuclidean(const SeedMask& seeds);
DistanceField bruteForceSegmentDistance(int width, int height,
                                        std::span<const GridSegment> segments, Metric metric);

}  // namespace cutaway::fields
