// Line drawings from volumes (Burns11 §2.4): the extracted curves of sampled analytic fields
// against their closed forms; walking against brute force.
#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "cutaway/core/error.hpp"
#include "cutaway/styles/volume_lines.hpp"

namespace cutaway {
namespace {

// A volume of dims³ nodes spaced `spacing` apart from `origin`, holding field(world position).
Volume sampled(int dims, float spacing, glm::vec3 origin,
               const std::function<float(glm::vec3)>& field) {
  Volume v;
  v.dims = glm::ivec3(dims);
  v.indexToWorld = glm::scale(glm::translate(glm::mat4(1.0f), origin), glm::vec3(spacing));
  v.values.resize(v.voxelCount());
  for (int k = 0; k < dims; ++k)
    for (int j = 0; j < dims; ++j)
      for (int i = 0; i < dims; ++i)
        v.values[std::size_t(i) + std::size_t(dims) * (std::size_t(j) + std::size_t(dims) * k)] =
            field(glm::vec3(v.indexToWorld * glm::vec4(i, j, k, 1)));
  v.updateRange();
  return v;
}

// A ball of radius r at the origin as a signed distance, positive inside.
Volume ball(float r, int dims = 40) {
  const float spacing = 2.6f * r / float(dims - 1);
  return sampled(dims, spacing, glm::vec3(-1.3f * r),
                 [r](glm::vec3 p) { return r - glm::length(p); });
}

VolumeLineView orthographic(glm::vec3 towardsViewer) {
  return {.eye = towardsViewer * 100.0f, .orthographic = true,
          .towardsViewer = glm::normalize(towardsViewer)};
}

std::size_t pointCount(const VolumeLineSet& set) {
  std::size_t n = 0;
  for (const auto& l : set.lines) n += l.points.size();
  return n;
}

TEST(VolumeLines, ABallsOrthographicContourIsItsGreatCircle) {
  const float r = 10.0f;
  const Volume v = ball(r);
  const VolumeLineField field(v, v.indexToWorld, orthographic({0, 0, 1}), {.isoValue = 0});
  const VolumeLineSet set = extractVolumeLinesBruteForce(field);
  ASSERT_EQ(set.lines.size(), 1u);
  EXPECT_TRUE(set.lines[0].closed);
  EXPECT_EQ(set.lines[0].kind, VolumeLineKind::Contour);  // convex: s > 0 (eq. 2.6)
  EXPECT_GT(set.lines[0].points.size(), 60u);
  for (const glm::vec3& p : set.lines[0].points) {
    EXPECT_NEAR(glm::length(p), r, 0.05f) << p.x << " " << p.y << " " << p.z;
    EXPECT_NEAR(p.z, 0.0f, 0.05f) << p.x << " " << p.y << " " << p.z;
  }
}

TEST(VolumeLines, ABallsPerspectiveContourIsTheCircleTheEyeSees) {
  // From an eye at distance d, the contour is where (p − c)·(e − p) = 0: the circle in the
  // plane z = r²/d, of radius r·√(1 − r²/d²).
  const float r = 10.0f, d = 25.0f;
  const Volume v = ball(r);
  const VolumeLineView view{.eye = {0, 0, d}};
  const VolumeLineField field(v, v.indexToWorld, view, {.isoValue = 0});
  const VolumeLineSet set = extractVolumeLinesBruteForce(field);
  ASSERT_EQ(set.lines.size(), 1u);
  EXPECT_TRUE(set.lines[0].closed);
  const float planeZ = r * r / d, radius = r * std::sqrt(1.0f - r * r / (d * d));
  for (const glm::vec3& p : set.lines[0].points) {
    EXPECT_NEAR(p.z, planeZ, 0.08f);
    EXPECT_NEAR(glm::length(glm::vec2(p)), radius, 0.08f);
  }
}

TEST(VolumeLines, ACavitysContourIsInterior) {
  // A spherical hole in material: n̂ points into the hole, the radial curvature at its
  // contour is negative, and so is s (eq. 2.6).
  const float r = 10.0f;
  const Volume v = sampled(40, 0.7f, glm::vec3(-13.65f),
                           [r](glm::vec3 p) { return glm::length(p) - r; });
  const VolumeLineField field(v, v.indexToWorld, orthographic({0, 0, 1}), {.isoValue = 0});
  const VolumeLineSet set = extractVolumeLinesBruteForce(field);
  ASSERT_EQ(set.lines.size(), 1u);
  EXPECT_EQ(set.lines[0].kind, VolumeLineKind::InteriorContour);
  EXPECT_TRUE(set.lines[0].closed);
  for (const glm::vec3& p : set.lines[0].points) EXPECT_NEAR(p.z, 0.0f, 0.05f);
}

TEST(VolumeLines, ACuttingPlaneCutsABallInItsCircle) {
  const float r = 10.0f, height = 6.0f;
  const Volume v = ball(r);
  // An oblique plane n̂·p = height (eq. 2.8): the circle of radius √(r² − height²) about n̂·height.
  const glm::vec3 n = glm::normalize(glm::vec3(1, 2, 2));
  const VolumeLineField field(v, v.indexToWorld, orthographic({0, 0, 1}),
                              {.isoValue = 0,
                               .family = VolumeLineFamily::Plane,
                               .plane = glm::vec4(n * 3.0f, height * 3.0f)});
  const VolumeLineSet set = extractVolumeLinesBruteForce(field);
  ASSERT_EQ(set.lines.size(), 1u);
  EXPECT_EQ(set.lines[0].kind, VolumeLineKind::PlaneCut);
  EXPECT_TRUE(set.lines[0].closed);
  const float radius = std::sqrt(r * r - height * height);
  for (const glm::vec3& p : set.lines[0].points) {
    EXPECT_NEAR(glm::dot(p, n), height, 1e-3f);
    EXPECT_NEAR(glm::length(p - n * height), radius, 0.06f);
  }
}

// A torus about z (ring radius R, tube radius a) as a signed distance, positive inside.
Volume torus(float R, float a, int dims) {
  const float extent = R + a + 2.0f;
  return sampled(dims, 2.0f * extent / float(dims - 1), glm::vec3(-extent), [=](glm::vec3 p) {
    return a - glm::length(glm::vec2(glm::length(glm::vec2(p.x, p.y)) - R, p.z));
  });
}

TEST(VolumeLines, ATorusSeenFromItsAxisHasItsTwoEquatorsAsContours) {
  const float R = 8.0f, a = 3.0f;
  const Volume v = torus(R, a, 36);
  const VolumeLineField field(v, v.indexToWorld, orthographic({0, 0, 1}), {.isoValue = 0});
  const VolumeLineSet set = extractVolumeLinesBruteForce(field);
  ASSERT_EQ(set.lines.size(), 2u);
  std::set<int> radii;
  for (const VolumeLine& line : set.lines) {
    EXPECT_TRUE(line.closed);
    const float rho = glm::length(glm::vec2(line.points[0]));
    radii.insert(int(std::lround(rho)));
    for (const glm::vec3& p : line.points) {
      EXPECT_NEAR(p.z, 0.0f, 0.1f);
      EXPECT_NEAR(glm::length(glm::vec2(p)), rho, 0.15f);
    }
  }
  EXPECT_EQ(radii, (std::set<int>{int(R - a), int(R + a)}));
}

TEST(VolumeLines, LoopsWalkedFromOneSeedCellEachEqualBruteForce) {
  // An oblique view of a torus: contours of both kinds, loops of many cells.
  const Volume v = torus(8.0f, 3.0f, 30);
  const VolumeLineField field(v, v.indexToWorld, {.eye = {30, -20, 25}}, {.isoValue = 0});
  const VolumeLineSet brute = extractVolumeLinesBruteForce(field);
  ASSERT_GE(brute.segmentCount(), 100u);
  std::set<VolumeLineKind> kinds;
  for (const auto& l : brute.lines) kinds.insert(l.kind);
  EXPECT_TRUE(kinds.count(VolumeLineKind::Contour) && kinds.count(VolumeLineKind::InteriorContour));

  // One cell per connected loop: every brute-force cell, walked, finds nothing new; so seeding
  // with the first cell alone and adding the cells of what is still missing must take as
  // many seeds as there are loops, and end with the same segments.
  VolumeLineSet walked;
  std::vector<glm::ivec3> seeds;
  for (std::uint64_t c : brute.cells) {
    const std::size_t before = walked.segmentCount();
    bool missing = false;
    for (const CellSegment& s : field.segments(field.cellAt(c)))
      missing = missing || !walked.contains(s.entryId);
    if (!missing) continue;
    seeds.push_back(field.cellAt(c));
    VolumeLineSet one;
    walkVolumeLines(field, {field.cellAt(c)}, one);
    walked.segments.insert(walked.segments.end(), one.segments.begin(), one.segments.end());
    std::sort(walked.segments.begin(), walked.segments.end());
    EXPECT_GT(walked.segmentCount(), before);
  }
  EXPECT_EQ(walked.segments, brute.segments);
  EXPECT_LE(seeds.size(), 4u);  // the loops of a torus's contour from a general view
  // Walked from the seeds alone, the cells read are few against the volume's.
  VolumeLineSet fromSeeds;
  walkVolumeLines(field, seeds, fromSeeds);
  EXPECT_EQ(fromSeeds.segments, brute.segments);
  EXPECT_EQ(pointCount(fromSeeds), pointCount(brute));
  EXPECT_LT(fromSeeds.cellsExamined * 10, brute.cellsExamined);
  // Every loop of a closed surface's contour inside the volume is closed.
  for (const auto& l : fromSeeds.lines)
    if (l.closed) EXPECT_GE(l.points.size(), 3u);
}

TEST(VolumeLines, TheTrackerFollowsAMovingViewFromThePreviousFramesCells) {
  const Volume v = torus(8.0f, 3.0f, 30);
  VolumeLineTracker tracker;
  double found = 0, total = 0;
  std::size_t walkedCost = 0, bruteCost = 0;
  for (int frame = 0; frame < 12; ++frame) {
    const float angle = 0.05f * float(frame);
    const VolumeLineView view{.eye = {30 * std::cos(angle), 30 * std::sin(angle), 20}};
    const VolumeLineField field(v, v.indexToWorld, view, {.isoValue = 0.2f * float(frame % 3)});
    const VolumeLineSet brute = extractVolumeLinesBruteForce(field);
    const VolumeLineSet set = tracker.extract(field, {.probesFromPrevious = 4, .randomProbes = 30});
    if (frame == 0) {
      EXPECT_EQ(set.segments, brute.segments);  // the first frame is brute force
      continue;
    }
    for (std::uint64_t s : set.segments) EXPECT_TRUE(brute.contains(s));
    found += double(brute.countFoundIn(set)), total += double(brute.segmentCount());
    walkedCost += set.cellsExamined, bruteCost += brute.cellsExamined;
  }
  EXPECT_GT(found / total, 0.9);
  EXPECT_LT(walkedCost * 5, bruteCost);
}

TEST(VolumeLines, EquationTwoPointFiveProbesReachTheSurfaceOfABall) {
  const Volume v = ball(10.0f);
  const VolumeLineField field(v, v.indexToWorld, orthographic({0, 0, 1}), {.isoValue = 0});
  // From outside, alternating steps towards f = 0 and g = 0 reach the contour's cells.
  glm::vec3 p = glm::vec3(field.cells()) * glm::vec3(0.9f, 0.6f, 0.8f);
  for (int i = 0; i < 5; ++i) p = field.walkTowardsZero(p, i % 2);
  EXPECT_FALSE(field.segments(glm::ivec3(glm::floor(p))).empty())
      << p.x << " " << p.y << " " << p.z;
}

// What the data or the view can make of nothing: NaN voxels give no NaN points, an isovalue
// outside the data finds nothing without re-scanning every frame, a flat grid has no cells.
TEST(VolumeLines, MissingValuesEmptyFramesAndFlatGridsAreHandled) {
  Volume v = ball(10.0f, 24);
  for (std::size_t i = 0; i < v.values.size(); i += 7) v.values[i] = std::nanf("");
  const VolumeLineField holes(v, v.indexToWorld, orthographic({0, 0, 1}), {.isoValue = 0});
  for (const VolumeLine& line : extractVolumeLinesBruteForce(holes).lines)
    for (const glm::vec3& p : line.points) EXPECT_FALSE(glm::any(glm::isnan(p)));

  const Volume b = ball(10.0f, 24);
  const VolumeLineField none(b, b.indexToWorld, orthographic({0, 0, 1}), {.isoValue = 1e6f});
  VolumeLineTracker tracker;
  const VolumeLineSet first = tracker.extract(none, {.randomProbes = 10});
  EXPECT_TRUE(first.lines.empty());
  EXPECT_EQ(first.cellsExamined, std::size_t(23 * 23 * 23));  // brute force, once
  const VolumeLineSet second = tracker.extract(none, {.randomProbes = 10});
  EXPECT_TRUE(second.lines.empty());
  EXPECT_LE(second.cellsExamined, 10u * 5u);  // the probes' steps only

  Volume flat;
  flat.dims = {5, 5, 1};
  flat.values.assign(25, 1.0f);
  flat.updateRange();
  const VolumeLineField field(flat, flat.indexToWorld, orthographic({0, 0, 1}), {.isoValue = 0.5f});
  VolumeLineTracker probing;
  EXPECT_TRUE(
      probing.extract(field, {.randomProbes = 20, .bruteForceFirstFrame = false}).lines.empty());
  EXPECT_TRUE(extractVolumeLinesBruteForce(field).lines.empty());
}

// White noise holds lines in nearly every cell: the extraction stops at the query's budget of
// segments with an error rather than fill the memory, exactly past it, walking or not; a frame
// that failed leaves the tracker's next frame a first one (brute force).
TEST(VolumeLines, NoiseStopsAtTheBudgetOfSegments) {
  const Volume noise = sampled(24, 1.0f, glm::vec3(0.0f), [](glm::vec3 p) {
    std::uint32_t h = std::uint32_t(p.x) * 73856093u ^ std::uint32_t(p.y) * 19349663u ^
                      std::uint32_t(p.z) * 83492791u;
    h ^= h >> 13, h *= 0x5bd1e995u, h ^= h >> 15;
    return float(h & 0xffffu) / 65535.0f;
  });
  VolumeLineQuery query{.isoValue = 0.5f};
  const VolumeLineField unbounded(noise, noise.indexToWorld, orthographic({0, 0, 1}), query);
  const VolumeLineSet all = extractVolumeLinesBruteForce(unbounded);
  std::size_t held = 0;  // what the cache holds: every segment of every cell, drawn or not
  for (int z = 0; z < 23; ++z)
    for (int y = 0; y < 23; ++y)
      for (int x = 0; x < 23; ++x) held += unbounded.segments({x, y, z}).size();
  ASSERT_GT(all.segmentCount(), 2000u);
  query.mostSegments = held;
  const VolumeLineField enough(noise, noise.indexToWorld, orthographic({0, 0, 1}), query);
  EXPECT_EQ(extractVolumeLinesBruteForce(enough).segmentCount(), all.segmentCount());
  query.mostSegments = held - 1;
  const VolumeLineField short1(noise, noise.indexToWorld, orthographic({0, 0, 1}), query);
  EXPECT_THROW(extractVolumeLinesBruteForce(short1), Error);
  VolumeLineTracker tracker;
  EXPECT_THROW(tracker.extract(short1), Error);
  EXPECT_FALSE(tracker.hasHistory());
  EXPECT_EQ(tracker.extract(enough).segmentCount(), all.segmentCount());  // brute force
  query.mostSegments = 100;  // the walk from the last frame's cells stops too
  const VolumeLineField few(noise, noise.indexToWorld, orthographic({0, 0, 1}), query);
  EXPECT_THROW(tracker.extract(few), Error);
}

// A bump on a bowl, z = A·exp(−ρ²/2σ²) − Bρ², as a signed distance (positive below), seen
// from above: its radial curvature is the profile's, zero where the profile inflects, so its
// suggestive contour is the circle where h''(ρ) = 0.
TEST(VolumeLines, ABumpsSuggestiveContourIsWhereItsProfileInflects) {
  const float A = 6.0f, sigma = 4.0f, B = 0.02f;
  const auto h = [=](float rho) { return A * std::exp(-rho * rho / (2 * sigma * sigma)) - B * rho * rho; };
  const auto h2 = [=](float rho) {
    return A * std::exp(-rho * rho / (2 * sigma * sigma)) * (rho * rho / std::pow(sigma, 4.0f) - 1 / (sigma * sigma)) -
           2 * B;
  };
  float inflection = sigma;  // h'' = 0 by bisection on [σ/2, 2σ]
  for (float lo = sigma / 2, hi = 2 * sigma, i = 0; i < 60; ++i) {
    inflection = (lo + hi) / 2;
    (h2(inflection) < 0 ? lo : hi) = inflection;
  }
  const Volume v = sampled(40, 0.6f, glm::vec3(-11.7f, -11.7f, -8.0f), [&](glm::vec3 p) {
    const float rho = glm::length(glm::vec2(p));
    // The distance to the profile in the meridian plane: sampled, then refined by ternary search.
    const auto distance = [&](float t) { return glm::length(glm::vec2(rho - t, p.z - h(t))); };
    float bestT = 0.0f;
    for (float t = -16.0f; t <= 16.0f; t += 0.25f)
      if (distance(t) < distance(bestT)) bestT = t;
    float lo = bestT - 0.25f, hi = bestT + 0.25f;
    for (int i = 0; i < 40; ++i) {
      const float m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
      (distance(m1) < distance(m2) ? hi : lo) = distance(m1) < distance(m2) ? m2 : m1;
    }
    const float best = distance((lo + hi) / 2);
    return p.z < h(rho) ? best : -best;
  });
  const VolumeLineField field(v, v.indexToWorld, orthographic({0, 0, 1}),
                              {.isoValue = 0, .family = VolumeLineFamily::Suggestive});
  const VolumeLineSet set = extractVolumeLinesBruteForce(field);
  std::size_t points = 0;
  for (const VolumeLine& line : set.lines) {
    EXPECT_EQ(line.kind, VolumeLineKind::SuggestiveContour);
    for (const glm::vec3& p : line.points) {
      const float rho = glm::length(glm::vec2(p));
      EXPECT_NEAR(rho, inflection, 0.25f) << "ρ at " << p.x << " " << p.y << " " << p.z;
      EXPECT_NEAR(p.z, h(rho), 0.1f);
      ++points;
    }
  }
  EXPECT_GT(points, 40u);
  // D_s there is about 0.03 per mm² (0.011 per voxel²): a larger ε filters the whole ring.
  const VolumeLineField strict(v, v.indexToWorld, orthographic({0, 0, 1}),
                               {.isoValue = 0, .family = VolumeLineFamily::Suggestive, .epsilon = 0.05f});
  EXPECT_TRUE(extractVolumeLinesBruteForce(strict).lines.empty());
}

}  // namespace
}  // namespace cutaway
