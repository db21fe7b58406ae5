// Distance transforms of a drawn pipe network (Konev18 §4): conservative line rasterisation
// into a seed mask, the L1 transform by 1-D passes and the exact Euclidean transform of
// Felzenszwalb & Huttenlocher 2012 ("Distance Transforms of Sampled Functions", Theory of
// Computing 8(19)), plus brute-force references.
#include "cutaway/fields/distance_transform.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace cutaway::fields {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
// Slack of the conservative rasteriser, in pixels: the segment is rounded once to double
// from float, and its position inside each pixel column is interpolated; 1e-6 pixel is far
// above that rounding (~1e-12 pixel for grids below 10⁵ pixels) and far below anything
// visible, so boundary cases always mark the pixels on both sides.
constexpr double kSlack = 1e-6;

DistanceField emptyField(const SeedMask& seeds) {
  DistanceField f;
  f.width = seeds.width;
  f.height = seeds.height;
  f.distance.assign(seeds.seeded.size(), kInfinity);
  return f;
}

// floor(v) as a pixel index clamped to [−1, n]: far-away or huge coordinates must neither
// overflow int nor make the loops walk over pixels outside the image.
int clampedFloor(double v, int n) {
  return int(std::clamp(std::floor(v), -1.0, double(n)));
}

// FH12 §2.1, algorithm DT(f) for the squared Euclidean distance: the lower envelope of the
// parabolas y = (q − p)² + f(p) rooted at every sample p with finite f(p), evaluated at
// every q. `f` and `out` have n elements, `out` may not alias `f`. Samples at +infinity add
// no parabola (FH12 handle them implicitly; with them in, the intersection formula would
// compute ∞ − ∞). With no finite sample the output is +infinity.
void lowerEnvelope(const double* f, double* out, int n, std::vector<int>& v,
                   std::vector<double>& z) {
  v.resize(std::size_t(n));
  z.resize(std::size_t(n) + 1);
  int k = -1;  // index of the rightmost parabola of the envelope
  for (int q = 0; q < n; ++q) {
    if (std::isinf(f[q])) continue;
    if (k < 0) {
      k = 0;
      v[0] = q;
      z[0] = -std::numeric_limits<double>::infinity();
      z[1] = std::numeric_limits<double>::infinity();
      continue;
    }
    // FH12 eq. (4): the parabolas from q and v[k] intersect at
    // s = ((f(q) + q²) − (f(v[k]) + v[k]²)) / (2q − 2v[k]). While s lies left of where v[k]
    // starts to be minimal, v[k] is nowhere minimal and leaves the envelope. z[0] = −∞ stops
    // the loop at the first parabola.
    double s = 0.0;
    for (;;) {
      const int p = v[std::size_t(k)];
      s = ((f[q] + double(q) * q) - (f[p] + double(p) * p)) / (2.0 * q - 2.0 * p);
      if (s > z[std::size_t(k)]) break;
      --k;
    }
    ++k;
    v[std::size_t(k)] = q;
    z[std::size_t(k)] = s;
    z[std::size_t(k) + 1] = std::numeric_limits<double>::infinity();
  }
  if (k < 0) {
    std::fill(out, out + n, std::numeric_limits<double>::infinity());
    return;
  }
  // FH12 §2.1, second loop: walk the envelope's intervals left to right.
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[std::size_t(k) + 1] < q) ++k;
    const double d = double(q - v[std::size_t(k)]);
    out[q] = d * d + f[v[std::size_t(k)]];
  }
}

std::vector<std::size_t> seedIndices(const SeedMask& seeds) {
  std::vector<std::size_t> indices;
  for (std::size_t i = 0; i < seeds.seeded.size(); ++i)
    if (seeds.seeded[i]) indices.push_back(i);
  return indices;
}

}  // namespace

SeedMask::SeedMask(int w, int h) : width(w), height(h) {
  assert(w >= 0 && h >= 0 && "a seed mask cannot have a negative size");
  seeded.assign(std::size_t(w) * std::size_t(h), 0);
}

void rasterizeSegment(SeedMask& mask, const GridSegment& segment) {
  double ax = segment.a.x, ay = segment.a.y, bx = segment.b.x, by = segment.b.y;
  if (!std::isfinite(ax) || !std::isfinite(ay) || !std::isfinite(bx) || !std::isfinite(by)) return;
  if (mask.width <= 0 || mask.height <= 0) return;
  if (ax > bx) {  // walk the pixel columns left to right
    std::swap(ax, bx);
    std::swap(ay, by);
  }
  const double dx = bx - ax, dy = by - ay;
  // Supercover by columns: in each pixel column [i, i+1) the segment covers an interval of
  // y, and every pixel row that interval touches is marked. Neighbouring columns share the
  // y at their common boundary (both columns reach kSlack past it), so the marked pixels
  // are 4-connected along the segment: no gaps, which Konev18 §4's distance field needs so
  // that no pipe appears broken in the opening.
  const int i0 = std::max(0, clampedFloor(ax - kSlack, mask.width));
  const int i1 = std::min(mask.width - 1, clampedFloor(bx + kSlack, mask.width));
  for (int i = i0; i <= i1; ++i) {
    const double xl = std::max(ax, double(i) - kSlack), xr = std::min(bx, double(i + 1) + kSlack);
    if (xl > xr) continue;
    // A vertical segment (dx = 0) spans its whole y range in its one column.
    const double yl = dx > 0.0 ? ay + (xl - ax) * (dy / dx) : ay;
    const double yr = dx > 0.0 ? ay + (xr - ax) * (dy / dx) : by;
    const int j0 = std::max(0, clampedFloor(std::min(yl, yr) - kSlack, mask.height));
    const int j1 = std::min(mask.height - 1, clampedFloor(std::max(yl, yr) + kSlack, mask.height));
    for (int j = j0; j <= j1; ++j) mask.set(i, j);
  }
}

SeedMask rasterizeSegments(int width, int height, std::span<const GridSegment> segments) {
  SeedMask mask(width, height);
  for (const GridSegment& s : segments) rasterizeSegment(mask, s);
  return mask;
}

DistanceField l1DistanceTransform(const SeedMask& seeds) {
  // L1 is separable: min over seeds of |Δx| + |Δy| = min over rows y' of (|y − y'| + min over
  // x' of |x − x'| on row y'), so a 1-D transform along rows followed by one along columns is
  // exact (FH12 §2: d(p, q) = |p − q| per dimension). Each 1-D transform is a forward sweep
  // (distance to the nearest seed on the left, +1 a step) and a backward one (on the right).
  // Values are small integers held exactly in float; ∞ + 1 stays ∞.
  DistanceField f = emptyField(seeds);
  const int w = seeds.width, h = seeds.height;
  for (int y = 0; y < h; ++y) {
    float* row = f.distance.data() + std::size_t(y) * std::size_t(w);
    for (int x = 0; x < w; ++x)
      row[x] = seeds.at(x, y) ? 0.0f : (x > 0 ? row[x - 1] + 1.0f : kInfinity);
    for (int x = w - 2; x >= 0; --x) row[x] = std::min(row[x], row[x + 1] + 1.0f);
  }
  for (int x = 0; x < w; ++x) {
    float* column = f.distance.data() + x;
    const std::size_t stride = std::size_t(w);
    for (int y = 1; y < h; ++y)
      column[y * stride] = std::min(column[y * stride], column[(y - 1) * stride] + 1.0f);
    for (int y = h - 2; y >= 0; --y)
      column[y * stride] = std::min(column[y * stride], column[(y + 1) * stride] + 1.0f);
  }
  return f;
}

DistanceField euclideanDistanceTransform(const SeedMask& seeds) {
  // FH12 §3: the 2-D squared Euclidean transform is the 1-D transform along columns followed
  // by the 1-D transform along rows of its result. Squared distances are integers below
  // 2⁵³ and the envelope is evaluated as d² + f, so both passes are exact in double.
  DistanceField f = emptyField(seeds);
  const int w = seeds.width, h = seeds.height;
  if (w == 0 || h == 0) return f;
  std::vector<double> squared(seeds.seeded.size());
  std::vector<double> in(std::size_t(std::max(w, h))), out(in.size());
  std::vector<int> v;
  std::vector<double> z;
  for (int x = 0; x < w; ++x) {
    for (int y = 0; y < h; ++y)
      in[std::size_t(y)] = seeds.at(x, y) ? 0.0 : std::numeric_limits<double>::infinity();
    lowerEnvelope(in.data(), out.data(), h, v, z);
    for (int y = 0; y < h; ++y) squared[seeds.index(x, y)] = out[std::size_t(y)];
  }
  for (int y = 0; y < h; ++y) {
    const double* row = squared.data() + seeds.index(0, y);
    lowerEnvelope(row, out.data(), w, v, z);
    for (int x = 0; x < w; ++x)
      f.distance[seeds.index(x, y)] = float(std::sqrt(out[std::size_t(x)]));  // √∞ = ∞
  }
  return f;
}

DistanceField bruteForceL1(const SeedMask& seeds) {
  DistanceField f = emptyField(seeds);
  const std::vector<std::size_t> seedList = seedIndices(seeds);
  const std::size_t w = std::size_t(seeds.width);
  for (int y = 0; y < seeds.height; ++y)
    for (int x = 0; x < seeds.width; ++x) {
      long best = -1;
      for (std::size_t q : seedList) {
        const long d = std::labs(long(x) - long(q % w)) + std::labs(long(y) - long(q / w));
        if (best < 0 || d < best) best = d;
      }
      if (best >= 0) f.distance[seeds.index(x, y)] = float(best);
    }
  return f;
}

DistanceField bruteForceEuclidean(const SeedMask& seeds) {
  DistanceField f = emptyField(seeds);
  const std::vector<std::size_t> seedList = seedIndices(seeds);
  const std::size_t w = std::size_t(seeds.width);
  for (int y = 0; y < seeds.height; ++y)
    for (int x = 0; x < seeds.width; ++x) {
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t q : seedList) {
        const double dx = double(x) - double(q % w), dy = double(y) - double(q / w);
        best = std::min(best, dx * dx + dy * dy);
      }
      f.distance[seeds.index(x, y)] = float(std::sqrt(best));
    }
  return f;
}

}  // namespace cutaway::fields
