// Distance transforms of a drawn network (Konev18 §4): the conservative line rasteriser
// against dense samples of each segment and the exact L∞ distance to it; the L1 passes and
// Felzenszwalb & Huttenlocher 2012's Euclidean transform against brute force and closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <tuple>
#include <vector>

#include "cutaway/fields/distance_transform.hpp"

using namespace cutaway::fields;

namespace {

struct Size {
  int width, height;
};
// Square, non-square, one-pixel-wide, degenerate and non-power-of-two sizes.
constexpr Size kSizes[] = {{1, 1},   {1, 9},  {13, 1},  {2, 2},   {7, 5}, {16, 16},
                           {31, 17}, {5, 40}, {64, 33}, {50, 50}, {0, 0}, {0, 4}};

// Seeds at random, at a random density, plus (sometimes) the four corners and a pixel on
// each border, where the passes start and end.
SeedMask randomSeeds(Size size, std::mt19937& rng) {
  SeedMask m(size.width, size.height);
  if (size.width == 0 || size.height == 0) return m;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double density = std::pow(10.0, -3.0 * u(rng));  // 0.001 … 1
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x)
      if (u(rng) < density) m.set(x, y);
  if (u(rng) < 0.3) {
    const int w = size.width - 1, h = size.height - 1;
    for (auto [x, y] : {std::pair{0, 0}, {w, 0}, {0, h}, {w, h}}) m.set(x, y);
    m.set(int(rng() % unsigned(size.width)), 0);
    m.set(0, int(rng() % unsigned(size.height)));
  }
  return m;
}

// Exact L∞ distance from (px, py) to the segment: max(|Δx(t)|, |Δy(t)|) is convex in t, so
// a ternary search over t ∈ [0, 1] converges to its minimum.
double lInfinityDistance(double px, double py, const GridSegment& s) {
  auto at = [&](double t) {
    const double x = s.a.x + t * (double(s.b.x) - s.a.x), y = s.a.y + t * (double(s.b.y) - s.a.y);
    return std::max(std::abs(px - x), std::abs(py - y));
  };
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 200; ++i) {
    const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
    if (at(m1) < at(m2))
      hi = m2;
    else
      lo = m1;
  }
  return std::min({at(lo), at(0.0), at(1.0)});
}

void expectEqualFields(const DistanceField& reference, const DistanceField& f, double tolerance,
                       const char* what) {
  ASSERT_EQ(f.width, reference.width);
  ASSERT_EQ(f.height, reference.height);
  ASSERT_EQ(f.distance.size(), reference.distance.size());
  int failures = 0;
  for (int y = 0; y < f.height && failures < 5; ++y)
    for (int x = 0; x < f.width && failures < 5; ++x) {
      const float r = reference.at(x, y), v = f.at(x, y);
      const bool ok = std::isinf(r) ? v == r : std::abs(double(r) - double(v)) <= tolerance;
      if (!ok) {
        ++failures;
        ADD_FAILURE() << what << " at " << x << ", " << y << " of " << f.width << "×" << f.height
                      << ": brute force " << r << ", fast " << v;
      }
    }
}

}  // namespace

// ---- fast transforms against brute force ------------------------------------------------

// The L1 passes are exact: integer distances held exactly in float.
TEST(DistanceTransform, L1EqualsBruteForceOnRandomSeeds) {
  std::mt19937 rng(20180611);
  for (const Size size : kSizes)
    for (int trial = 0; trial < 12; ++trial) {
      const SeedMask seeds = randomSeeds(size, rng);
      expectEqualFields(bruteForceL1(seeds), l1DistanceTransform(seeds), 0.0, "L1");
    }
}

// The lower envelope computes integer squared distances exactly, so the only rounding is the
// final float square root, the same in both; 1e-4 pixel is the brief's bound.
TEST(DistanceTransform, EuclideanEqualsBruteForceOnRandomSeeds) {
  std::mt19937 rng(2012);
  for (const Size size : kSizes)
    for (int trial = 0; trial < 12; ++trial) {
      const SeedMask seeds = randomSeeds(size, rng);
      expectEqualFields(bruteForceEuclidean(seeds), euclideanDistanceTransform(seeds), 1e-4,
                        "Euclidean");
    }
}

TEST(DistanceTransform, NoSeedsIsInfinityEverywhere) {
  const SeedMask seeds(9, 4);
  for (const DistanceField& f : {l1DistanceTransform(seeds), euclideanDistanceTransform(seeds),
                                 bruteForceL1(seeds), bruteForceEuclidean(seeds)}) {
    ASSERT_EQ(f.distance.size(), 36u);
    for (float d : f.distance) EXPECT_EQ(d, std::numeric_limits<float>::infinity());
  }
  EXPECT_TRUE(l1DistanceTransform(SeedMask(0, 0)).distance.empty());
  EXPECT_TRUE(euclideanDistanceTransform(SeedMask(3, 0)).distance.empty());
}

// ---- closed forms -------------------------------------------------------------------------

// One seed q: D(p) = |px − qx| + |py − qy| (L1) and √((px − qx)² + (py − qy)²) (Euclidean,
// double-precision closed form rounded to float: 1e-6 relative is a few float ulps).
TEST(DistanceTransform, SingleSeedClosedForms) {
  for (auto [qx, qy] : {std::pair{0, 0}, {12, 7}, {39, 24}, {39, 0}, {0, 24}}) {
    SeedMask seeds(40, 25);
    seeds.set(qx, qy);
    const DistanceField l1 = l1DistanceTransform(seeds), e = euclideanDistanceTransform(seeds);
    for (int y = 0; y < seeds.height; ++y)
      for (int x = 0; x < seeds.width; ++x) {
        EXPECT_EQ(l1.at(x, y), float(std::abs(x - qx) + std::abs(y - qy)))
            << "seed " << qx << ", " << qy << " at " << x << ", " << y;
        const double expected = std::hypot(x - qx, y - qy);
        EXPECT_NEAR(e.at(x, y), expected, 1e-6 * std::max(1.0, expected))
            << "seed " << qx << ", " << qy << " at " << x << ", " << y;
      }
  }
}

// A full seeded column x = c: both metrics give |x − c| (the row pass alone decides).
TEST(DistanceTransform, SeededLineIsDistanceToTheLine) {
  SeedMask seeds(30, 11);
  for (int y = 0; y < seeds.height; ++y) seeds.set(8, y);
  const DistanceField l1 = l1DistanceTransform(seeds), e = euclideanDistanceTransform(seeds);
  for (int y = 0; y < seeds.height; ++y)
    for (int x = 0; x < seeds.width; ++x) {
      EXPECT_EQ(l1.at(x, y), float(std::abs(x - 8))) << x << ", " << y;
      EXPECT_EQ(e.at(x, y), float(std::abs(x - 8))) << x << ", " << y;
    }
}

// Konev18 Fig. 4a / Fig. 6: L1 level sets are diamonds, Euclidean ones circles, so along a
// diagonal from a seed L1 exceeds the Euclidean distance by the factor √2.
TEST(DistanceTransform, L1IsTheZigZagMetric) {
  SeedMask seeds(21, 21);
  seeds.set(10, 10);
  const DistanceField l1 = l1DistanceTransform(seeds), e = euclideanDistanceTransform(seeds);
  for (int k = 1; k <= 10; ++k) {
    EXPECT_EQ(l1.at(10 + k, 10 + k), float(2 * k));
    EXPECT_NEAR(l1.at(10 + k, 10 + k) / e.at(10 + k, 10 + k), std::sqrt(2.0), 1e-6) << k;
  }
}

// ---- rasterisation ------------------------------------------------------------------------

TEST(RasterizeSegments, AxisAlignedAndDiagonalClosedForms) {
  // A horizontal segment inside row 3 marks exactly the pixels its x range touches.
  const std::vector<GridSegment> horizontal{{{1.25f, 3.5f}, {6.75f, 3.5f}}};
  const SeedMask h = rasterizeSegments(10, 8, horizontal);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 10; ++x)
      EXPECT_EQ(h.at(x, y), y == 3 && x >= 1 && x <= 6) << x << ", " << y;
  // A diagonal through pixel corners (0,0)–(5,5): the supercover marks the diagonal pixels
  // and, at every corner it passes, the two pixels touching that corner.
  const std::vector<GridSegment> diagonal{{{0.0f, 0.0f}, {5.0f, 5.0f}}};
  const SeedMask d = rasterizeSegments(8, 8, diagonal);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const bool onDiagonal = x == y && x <= 5;
      const bool besideCorner = std::abs(x - y) == 1 && std::max(x, y) <= 5;
      EXPECT_EQ(d.at(x, y), onDiagonal || besideCorner) << x << ", " << y;
    }
  // A point: the one pixel it lies in.
  const std::vector<GridSegment> point{{{2.5f, 4.5f}, {2.5f, 4.5f}}};
  const SeedMask p = rasterizeSegments(5, 6, point);
  EXPECT_EQ(std::count(p.seeded.begin(), p.seeded.end(), 1), 1);
  EXPECT_TRUE(p.at(2, 4));
}

// Random segments, partly outside the image, of every direction and length (zero included):
// every pixel a dense sample of a segment falls into is a seed, and every seed's centre is
// within ½ pixel (+ the 1e-6 slack, + 1e-9 for the search) of some segment in L∞ — so no
// seed is farther than 1 pixel from a segment.
TEST(RasterizeSegments, ConservativeAndTightOnRandomSegments) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int trial = 0; trial < 60; ++trial) {
    const Size size{1 + int(rng() % 60u), 1 + int(rng() % 60u)};
    std::vector<GridSegment> segments;
    const int count = 1 + int(rng() % 6u);
    for (int i = 0; i < count; ++i) {
      auto point = [&] {
        // Some endpoints on exact pixel boundaries, some beyond the image.
        GridPoint p{-5.0f + (size.width + 10) * u(rng), -5.0f + (size.height + 10) * u(rng)};
        if (u(rng) < 0.3f) p = {std::round(p.x), std::round(p.y)};
        return p;
      };
      const GridPoint a = point();
      const GridPoint b = u(rng) < 0.1f ? a : (u(rng) < 0.2f ? GridPoint{a.x, point().y} : point());
      segments.push_back({a, b});
    }
    const SeedMask mask = rasterizeSegments(size.width, size.height, segments);

    for (const GridSegment& s : segments) {
      const double length = std::hypot(double(s.b.x) - s.a.x, double(s.b.y) - s.a.y);
      const int samples = 2 + int(length * 64.0);
      for (int k = 0; k <= samples; ++k) {
        const double t = double(k) / samples;
        const double x = s.a.x + t * (double(s.b.x) - s.a.x),
                     y = s.a.y + t * (double(s.b.y) - s.a.y);
        const int px = int(std::floor(x)), py = int(std::floor(y));
        if (px < 0 || py < 0 || px >= size.width || py >= size.height) continue;
        EXPECT_TRUE(mask.at(px, py))
            << "trial " << trial << ": sample " << x << ", " << y << " of segment (" << s.a.x
            << ", " << s.a.y << ")–(" << s.b.x << ", " << s.b.y << ") in an unmarked pixel";
      }
    }
    for (int y = 0; y < size.height; ++y)
      for (int x = 0; x < size.width; ++x) {
        if (!mask.at(x, y)) continue;
        double nearest = std::numeric_limits<double>::infinity();
        for (const GridSegment& s : segments)
          nearest = std::min(nearest, lInfinityDistance(x + 0.5, y + 0.5, s));
        EXPECT_LE(nearest, 0.5 + 1e-6 + 1e-9) << "trial " << trial << ": seed " << x << ", " << y
                                              << " is " << nearest << " (L∞) from every segment";
      }
  }
}

// Rasterised network, then both transforms: seeds at 0 and the fast versions equal brute force.
TEST(RasterizeSegments, NetworkDistanceFieldsMatchBruteForce) {
  const std::vector<GridSegment> network{{{3.2f, 4.1f}, {40.7f, 20.3f}},
                                         {{40.7f, 20.3f}, {44.0f, 2.0f}},
                                         {{10.0f, 28.9f}, {30.5f, 29.5f}}};
  const SeedMask seeds = rasterizeSegments(48, 32, network);
  expectEqualFields(bruteForceL1(seeds), l1DistanceTransform(seeds), 0.0, "L1");
  expectEqualFields(bruteForceEuclidean(seeds), euclideanDistanceTransform(seeds), 1e-4,
                    "Euclidean");
  const DistanceField l1 = l1DistanceTransform(seeds);
  for (std::size_t i = 0; i < seeds.seeded.size(); ++i)
    EXPECT_EQ(l1.distance[i] == 0.0f, seeds.seeded[i] != 0) << i;
}

// Non-finite endpoints are ignored; coordinates far beyond int range do not overflow.
TEST(RasterizeSegments, IgnoresNonFiniteAndClipsHugeCoordinates) {
  SeedMask mask(10, 10);
  rasterizeSegment(mask, {{std::numeric_limits<float>::quiet_NaN(), 1.0f}, {5.0f, 5.0f}});
  rasterizeSegment(mask, {{std::numeric_limits<float>::infinity(), 1.0f}, {5.0f, 5.0f}});
  EXPECT_EQ(std::count(mask.seeded.begin(), mask.seeded.end(), 1), 0);
  rasterizeSegment(mask, {{-1e30f, 4.5f}, {1e30f, 4.5f}});
  for (int x = 0; x < 10; ++x) EXPECT_TRUE(mask.at(x, 4)) << x;
  EXPECT_EQ(std::count(mask.seeded.begin(), mask.seeded.end(), 1), 10);
}

// ---- the distance to the segments themselves (the smooth opening) -----------------------

// Worked by hand: Euclidean to the interior and to an end; L1 to a slanted segment is the
// vertical or horizontal step to it, whichever is shorter (the dual norm of L1 is L∞:
// |n·p − c| / max(|nₓ|, |n_y|)); on an axis-aligned segment both metrics agree.
TEST(SegmentDistance, ClosedForms) {
  const GridSegment slanted{{0.0f, 0.0f}, {100.0f, 50.0f}};  // y = x / 2
  EXPECT_NEAR(segmentDistance({50.0f, 40.0f}, slanted, Metric::Euclidean), 15.0 / std::sqrt(1.25),
              1e-9);
  EXPECT_NEAR(segmentDistance({50.0f, 40.0f}, slanted, Metric::L1), 15.0, 1e-9);  // straight down
  EXPECT_NEAR(segmentDistance({80.0f, 0.0f}, slanted, Metric::L1), 40.0, 1e-9);   // straight up
  EXPECT_NEAR(segmentDistance({-3.0f, -4.0f}, slanted, Metric::Euclidean), 5.0, 1e-9);  // end a
  EXPECT_NEAR(segmentDistance({-3.0f, -4.0f}, slanted, Metric::L1), 7.0, 1e-9);
  EXPECT_NEAR(segmentDistance({103.0f, 54.0f}, slanted, Metric::L1), 7.0, 1e-9);  // end b
  const GridSegment diagonal{{-10.0f, -10.0f}, {10.0f, 10.0f}};
  EXPECT_NEAR(segmentDistance({0.0f, 2.0f}, diagonal, Metric::L1), 2.0, 1e-9);
  EXPECT_NEAR(segmentDistance({0.0f, 2.0f}, diagonal, Metric::Euclidean), std::sqrt(2.0), 1e-6);
  const GridSegment axis{{2.0f, 5.0f}, {2.0f, 9.0f}};
  for (const Metric m : {Metric::L1, Metric::Euclidean})
    EXPECT_NEAR(segmentDistance({6.0f, 7.5f}, axis, m), 4.0, 1e-9);
  const GridSegment point{{1.0f, 1.0f}, {1.0f, 1.0f}};
  EXPECT_NEAR(segmentDistance({4.0f, 5.0f}, point, Metric::Euclidean), 5.0, 1e-9);
  EXPECT_NEAR(segmentDistance({4.0f, 5.0f}, point, Metric::L1), 7.0, 1e-9);
}

// Random networks, partly outside the grid, against every pixel measured to every segment.
// Every value is a distance to some segment, so never below brute force; within `reach` it
// is brute force's, exactly under L1 and within 0.2 pixel under the Euclidean metric, where
// near two crossing segments a third's nearest pixels can be a sliver that no neighbour hands
// on (measured worst over 4000 trials of up to 8 segments: 0.090; over 2000 of up to 30
// long segments crossing in under 90 × 90 pixels: 0.142).
TEST(SegmentDistance, FieldMatchesBruteForceOnRandomNetworks) {
  std::mt19937 rng(1980);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (const auto& [segmentsAtMost, trials] : {std::pair{8, 400}, {30, 200}})
    for (const Metric metric : {Metric::L1, Metric::Euclidean}) {
      const double tolerance = metric == Metric::L1 ? 1e-4 : 0.2;
      double worst = 0.0;
      for (int trial = 0; trial < trials; ++trial) {
        const Size size{1 + int(rng() % 90u), 1 + int(rng() % 90u)};
        const float reach = 40.0f * u(rng);
        std::vector<GridSegment> segments;
        const int count = 1 + int(rng() % unsigned(segmentsAtMost));
        for (int i = 0; i < count; ++i) {
          auto point = [&] {
            return GridPoint{-30.0f + (size.width + 60) * u(rng),
                             -30.0f + (size.height + 60) * u(rng)};
          };
          const GridPoint a = point();
          segments.push_back({a, u(rng) < 0.1f ? a : point()});
        }
        const DistanceField fast =
            segmentDistanceField(size.width, size.height, segments, metric, reach);
        const DistanceField brute =
            bruteForceSegmentDistance(size.width, size.height, segments, metric);
        ASSERT_EQ(fast.distance.size(), brute.distance.size());
        for (int y = 0; y < size.height; ++y)
          for (int x = 0; x < size.width; ++x) {
            const double b = brute.at(x, y), f = fast.at(x, y);
            ASSERT_GE(f, b - 1e-4) << "trial " << trial << ": " << x << ", " << y;
            if (b <= reach) worst = std::max(worst, f - b);
          }
      }
      EXPECT_LE(worst, tolerance) << (metric == Metric::L1 ? "L1" : "Euclidean") << ", up to "
                                  << segmentsAtMost << " segments";
    }
}

// Empty grids, no segments, and a reach of 0 (only what is drawn inside counts).
TEST(SegmentDistance, EdgeCases) {
  const std::vector<GridSegment> none, one{{{-5.0f, 2.5f}, {-1.0f, 2.5f}}};
  EXPECT_TRUE(segmentDistanceField(0, 7, one, Metric::L1, 3.0f).distance.empty());
  const DistanceField empty = segmentDistanceField(4, 3, none, Metric::Euclidean, 10.0f);
  for (const float d : empty.distance) EXPECT_EQ(d, std::numeric_limits<float>::infinity());
  // The segment ends 1 pixel left of the grid: reach 2 finds it, reach 0 does not.
  EXPECT_FLOAT_EQ(segmentDistanceField(4, 3, one, Metric::L1, 2.0f).at(0, 2), 1.5f);
  EXPECT_EQ(segmentDistanceField(4, 3, one, Metric::L1, 0.0f).at(0, 2),
            std::numeric_limits<float>::infinity());
}
