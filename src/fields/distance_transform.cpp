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

DistanceField emptyField(int width, int height) {
  DistanceField f;
  f.width = width;
  f.height = height;
  f.distance.assign(std::size_t(width) * std::size_t(height), kInfinity);
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

// Calls visit(i, j) for every pixel of a width × height grid that the closed segment passes
// within kSlack of (see rasterizeSegment).
template <typename Visit>
void visitSegmentPixels(int width, int height, const GridSegment& segment, Visit&& visit) {
  double ax = segment.a.x, ay = segment.a.y, bx = segment.b.x, by = segment.b.y;
  if (!std::isfinite(ax) || !std::isfinite(ay) || !std::isfinite(bx) || !std::isfinite(by)) return;
  if (width <= 0 || height <= 0) return;
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
  const int i0 = std::max(0, clampedFloor(ax - kSlack, width));
  const int i1 = std::min(width - 1, clampedFloor(bx + kSlack, width));
  for (int i = i0; i <= i1; ++i) {
    const double xl = std::max(ax, double(i) - kSlack), xr = std::min(bx, double(i + 1) + kSlack);
    if (xl > xr) continue;
    // A vertical segment (dx = 0) spans its whole y range in its one column.
    const double yl = dx > 0.0 ? ay + (xl - ax) * (dy / dx) : ay;
    const double yr = dx > 0.0 ? ay + (xr - ax) * (dy / dx) : by;
    const int j0 = std::max(0, clampedFloor(std::min(yl, yr) - kSlack, height));
    const int j1 = std::min(height - 1, clampedFloor(std::max(yl, yr) + kSlack, height));
    for (int j = j0; j <= j1; ++j) visit(i, j);
  }
}

}  // namespace

SeedMask::SeedMask(int w, int h) : width(w), height(h) {
  assert(w >= 0 && h >= 0 && "a seed mask cannot have a negative size");
  seeded.assign(std::size_t(w) * std::size_t(h), 0);
}

void rasterizeSegment(SeedMask& mask, const GridSegment& segment) {
  visitSegmentPixels(mask.width, mask.height, segment, [&](int i, int j) { mask.set(i, j); });
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
  DistanceField f = emptyField(seeds.width, seeds.height);
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
  DistanceField f = emptyField(seeds.width, seeds.height);
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
  DistanceField f = emptyField(seeds.width, seeds.height);
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
  DistanceField f = emptyField(seeds.width, seeds.height);
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

double segmentDistance(GridPoint p, const GridSegment& s, Metric metric) {
  const double px = double(p.x) - s.a.x, py = double(p.y) - s.a.y;
  const double dx = double(s.b.x) - s.a.x, dy = double(s.b.y) - s.a.y;
  if (metric == Metric::Euclidean) {
    const double len2 = dx * dx + dy * dy;
    const double u = len2 > 0.0 ? std::clamp((px * dx + py * dy) / len2, 0.0, 1.0) : 0.0;
    return std::hypot(px - u * dx, py - u * dy);
  }
  // |p − a − u·d|₁ is convex and piecewise linear in u: its minimum over [0, 1] is at an end
  // or where one coordinate's term vanishes.
  const auto at = [&](double u) {
    u = std::clamp(u, 0.0, 1.0);
    return std::abs(px - u * dx) + std::abs(py - u * dy);
  };
  double best = std::min(at(0.0), at(1.0));
  if (dx != 0.0) best = std::min(best, at(px / dx));
  if (dy != 0.0) best = std::min(best, at(py / dy));
  return best;
}

DistanceField segmentDistanceField(int width, int height, std::span<const GridSegment> segments,
                                   Metric metric, float reach) {
  assert(std::isfinite(reach) && reach >= 0.0f && "segmentDistanceField needs a finite reach");
  // The grid grows by `reach` on each side, so that a segment outside it still seeds the
  // pixels its neighbourhood of radius `reach` covers: the straight path from a pixel to its
  // nearest point at distance ≤ reach then runs inside the grown grid.
  const int m = int(std::ceil(reach)), gw = width + 2 * m, gh = height + 2 * m;
  DistanceField f = emptyField(width, height);
  if (width == 0 || height == 0) return f;
  std::vector<float> distance(std::size_t(gw) * std::size_t(gh), kInfinity);
  // nearest[i]: the index of pixel i's nearest segment found so far, −1 none.
  std::vector<int> nearest(distance.size(), -1);
  const auto offer = [&](int x, int y, int s) {
    if (x < 0 || x >= gw || y < 0 || y >= gh || s < 0) return;
    const std::size_t i = std::size_t(y) * std::size_t(gw) + std::size_t(x);
    if (nearest[i] == s) return;
    // An L1 tie goes to the Euclidean-nearer segment: L1's equidistant sets are areas, and a
    // tie kept by whichever came first could hide the segment that wins beyond them.
    const GridPoint centre{float(x - m) + 0.5f, float(y - m) + 0.5f};
    const GridSegment& candidate = segments[std::size_t(s)];
    const float d = float(segmentDistance(centre, candidate, metric));
    const bool better =
        d < distance[i] ||
        (metric == Metric::L1 && d == distance[i] &&
         segmentDistance(centre, candidate, Metric::Euclidean) <
             segmentDistance(centre, segments[std::size_t(nearest[i])], Metric::Euclidean));
    if (better) distance[i] = d, nearest[i] = s;
  };
  // Each segment offered to the pixels it is drawn into and their 8 neighbours: a pixel
  // drawn by two segments keeps one, and without the ring the other could reach no pixel.
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const GridSegment& g = segments[s];
    const float shift = float(m);
    visitSegmentPixels(gw, gh, {{g.a.x + shift, g.a.y + shift}, {g.b.x + shift, g.b.y + shift}},
                       [&](int x, int y) {
                         for (int dy = -1; dy <= 1; ++dy)
                           for (int dx = -1; dx <= 1; ++dx) offer(x + dx, y + dy, int(s));
                       });
  }
  const auto from = [&](int x, int y, int nx, int ny) {
    if (nx >= 0 && nx < gw && ny >= 0 && ny < gh)
      offer(x, y, nearest[std::size_t(ny) * std::size_t(gw) + std::size_t(nx)]);
  };
  // Forward: the row below and the left, then the right; backward: the mirror.
  for (int y = 0; y < gh; ++y) {
    for (int x = 0; x < gw; ++x)
      from(x, y, x - 1, y), from(x, y, x - 1, y - 1), from(x, y, x, y - 1),
          from(x, y, x + 1, y - 1);
    for (int x = gw - 2; x >= 0; --x) from(x, y, x + 1, y);
  }
  for (int y = gh - 1; y >= 0; --y) {
    for (int x = gw - 1; x >= 0; --x)
      from(x, y, x + 1, y), from(x, y, x + 1, y + 1), from(x, y, x, y + 1),
          from(x, y, x - 1, y + 1);
    for (int x = 1; x < gw; ++x) from(x, y, x - 1, y);
  }
  for (int y = 0; y < height; ++y)
    std::copy_n(distance.data() + std::size_t(y + m) * std::size_t(gw) + std::size_t(m), width,
                f.distance.data() + std::size_t(y) * std::size_t(width));
  return f;
}

DistanceField bruteForceSegmentDistance(int width, int height,
                                        std::span<const GridSegment> segments, Metric metric) {
  DistanceField f = emptyField(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double best = std::numeric_limits<double>::infinity();
      for (const GridSegment& s : segments)
        best = std::min(best, segmentDistance({float(x) + 0.5f, float(y) + 0.5f}, s, metric));
      f.distance[std::size_t(y) * std::size_t(width) + std::size_t(x)] = float(best);
    }
  return f;
}

}  // namespace cutaway::fields
