// Diepstraten03: the main axis against closed forms, the cutout's per-fragment signed
// distance on the GPU against cutout_function.cpp pixel by pixel, the clip-plane method
// against the texture method, and the breakaway clip depth against CPU ray casting.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <random>

#include "cutaway/core/error.hpp"
#include "cutaway/core/noise.hpp"
#include "cutaway/cutters/breakaway.hpp"
#include "cutaway/cutters/cutout.hpp"
#include "cutaway/geometry/main_axis.hpp"
#include "cutaway/render/renderer.hpp"
#include "cutaway/render/techniques.hpp"
#include "expect_error.hpp"
#include "gl_test_context.hpp"
#include "mismatches.hpp"
#include "render_aovs.hpp"
#include "run_command.hpp"

using namespace cutaway;
using test::aov;
using test::renderAovs;

namespace {

const std::string kData = CUTAWAY_TEST_DATA;

// The corners of a box with half-extents h, rotated by r.
std::vector<glm::vec3> boxCorners(glm::vec3 h, const glm::mat3& r, glm::vec3 centre) {
  std::vector<glm::vec3> points;
  for (float x : {-1.0f, 1.0f})
    for (float y : {-1.0f, 1.0f})
      for (float z : {-1.0f, 1.0f}) points.push_back(centre + r * (h * glm::vec3(x, y, z)));
  return points;
}

// Variance along x of a uniform density on the surface of the box [−a,a]×[−b,b]×[−c,c]:
// faces x = ±a (area 4bc each) contribute a², the other four faces a²/3 (x uniform on
// [−a, a]).
double boxSurfaceVariance(double a, double b, double c) {
  const double area = 8.0 * (b * c + a * c + a * b);
  return (8.0 * b * c * a * a + 8.0 * (a * c + a * b) * a * a / 3.0) / area;
}

}  // namespace

TEST(MainAxis, RotatedBoxMatchesClosedForm) {
  const glm::vec3 h(3.0f, 2.0f, 1.0f), centre(5.0f, -2.0f, 7.0f);
  const glm::mat3 r =
      glm::mat3(glm::rotate(glm::mat4(1.0f), 0.7f, glm::normalize(glm::vec3(1, 2, 3))));
  const PrincipalAxes a = principalAxes(boxCorners(h, r, centre));
  EXPECT_NEAR(glm::length(a.center - centre), 0.0f, 1e-4f);
  const double expected[3] = {boxSurfaceVariance(3, 2, 1), boxSurfaceVariance(2, 1, 3),
                              boxSurfaceVariance(1, 3, 2)};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(a.eigenvalues[std::size_t(i)], expected[i], 1e-4 * expected[0]) << "axis " << i;
    // Each axis is the rotated box axis, up to sign.
    EXPECT_NEAR(std::abs(glm::dot(a.axes[std::size_t(i)], r[i])), 1.0f, 1e-5f) << "axis " << i;
  }
  EXPECT_NEAR(a.extentMax - a.extentMin, 6.0f, 1e-4f);
  EXPECT_NEAR(glm::dot(glm::cross(a.axes[0], a.axes[1]), a.axes[2]), 1.0f, 1e-5f);
}

// A long box (x half-extent 2) whose end face x = 2 is tessellated into a dense grid: the
// vertex average sits near that face and the vertex covariance points across the box; the
// hull-surface covariance still finds x.
TEST(MainAxis, UnevenTessellationDoesNotBiasIt) {
  std::vector<glm::vec3> points = boxCorners({2, 1, 1}, glm::mat3(1.0f), glm::vec3(0.0f));
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) points.emplace_back(2.0f, -1.0f + i / 20.0f, -1.0f + j / 20.0f);
  // The naive estimate the test guards against: vertex mean and covariance.
  glm::dvec3 mean(0.0);
  for (const auto& p : points) mean += glm::dvec3(p);
  mean /= double(points.size());
  glm::dvec3 variance(0.0);
  for (const auto& p : points) variance += (glm::dvec3(p) - mean) * (glm::dvec3(p) - mean);
  ASSERT_LT(variance.x, variance.y) << "the naive vertex covariance should fail on this mesh";

  const PrincipalAxes a = principalAxes(points);
  EXPECT_NEAR(std::abs(a.axes[0].x), 1.0f, 1e-5f);
  EXPECT_NEAR(glm::length(a.center), 0.0f, 1e-4f);
  EXPECT_NEAR(a.eigenvalues[0], boxSurfaceVariance(2, 1, 1), 1e-4);
}

// Points on an ellipsoid with semi-axes 3, 2, 1, crowded on one side: the main axes are the
// ellipsoid's (the hull surface is sampled uniformly whatever the point density).
TEST(MainAxis, CrowdedEllipsoidKeepsItsAxes) {
  std::mt19937 rng(7);
  std::normal_distribution<float> n(0.0f, 1.0f);
  std::vector<glm::vec3> points;
  for (int i = 0; i < 4000; ++i) {
    glm::vec3 d = glm::normalize(glm::vec3(n(rng), n(rng), n(rng)));
    if (i % 4 != 0) d.x = std::abs(d.x);  // three quarters on the +x side
    points.push_back(glm::vec3(3, 2, 1) * d);
  }
  const PrincipalAxes a = principalAxes(points);
  EXPECT_GT(std::abs(a.axes[0].x), 0.999f);
  EXPECT_GT(std::abs(a.axes[1].y), 0.999f);
  EXPECT_GT(std::abs(a.axes[2].z), 0.999f);
  EXPECT_NEAR(a.center.x, 0.0f, 0.05f);
}

TEST(MainAxis, FlatPointsAreRejected) {
  std::vector<glm::vec3> flat{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5f, 0.5f, 0}};
  EXPECT_THROW((void)principalAxes(flat), Error);
}

// The wedge: both planes contain the main axis, open by the relative angle, and the bisector
// faces the viewer; the axial range adds two planes across the axis.
TEST(CutoutWedge, PlanesMeetOnTheAxisAndFaceTheViewer) {
  const PrincipalAxes a = principalAxes(boxCorners({3, 2, 1}, glm::mat3(1.0f), glm::vec3(1, 2, 3)));
  CutoutOptions options{.angle = 70.0f};
  const glm::vec3 viewer(0.3f, 0.2f, 1.0f);
  const CutoutWedge w = cutoutWedge(a, options, viewer);
  ASSERT_EQ(w.planes.size(), 2u);
  for (const auto& p : w.planes) {
    for (float s : {-5.0f, 0.0f, 4.0f})  // points on the axis lie on both planes
      EXPECT_NEAR(glm::dot(glm::vec3(p), a.center + s * a.axes[0]) + p.w, 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(glm::vec3(p), a.axes[0]), 0.0f, 1e-6f);
  }
  // Inward normals of a wedge of opening α are 180° − α apart.
  const float between =
      glm::degrees(std::acos(glm::dot(glm::vec3(w.planes[0]), glm::vec3(w.planes[1]))));
  EXPECT_NEAR(between, 180.0f - 70.0f, 1e-3f);
  // The viewer's direction (off the axis) is inside the wedge; its opposite is not.
  const glm::vec3 towards = glm::normalize(viewer - glm::dot(viewer, a.axes[0]) * a.axes[0]);
  CutoutJitter none;
  EXPECT_GT(cutoutDistance(w, none, a.center + towards), 0.0f);
  EXPECT_LT(cutoutDistance(w, none, a.center - towards), 0.0f);
  // The signed distance is the distance to the nearer plane inside a right-angled wedge.
  options.angle = 90.0f;
  const CutoutWedge right = cutoutWedge(a, options, viewer);
  EXPECT_NEAR(cutoutDistance(right, none, a.center + 2.0f * towards), 2.0f * std::sqrt(0.5f),
              1e-5f);

  options.axialRange = glm::vec2(0.25f, 0.5f);
  const CutoutWedge partial = cutoutWedge(a, options, viewer);
  ASSERT_EQ(partial.planes.size(), 4u);
  // Axis extent is [−3, 3] about the centre: the cut spans s ∈ [−1.5, 0].
  EXPECT_GT(cutoutDistance(partial, none, a.center + towards - 0.75f * a.axes[0]), 0.0f);
  EXPECT_LT(cutoutDistance(partial, none, a.center + towards + 0.75f * a.axes[0]), 0.0f);
  EXPECT_LT(cutoutDistance(partial, none, a.center + towards - 2.0f * a.axes[0]), 0.0f);
}

// A set rotation turns the wedge about the main axis, whatever the viewer: its bisector lies
// `rotation` degrees from the second principal axis towards the third, so a point at angle φ
// about the axis (from the second axis towards the third) is removed exactly where
// |φ − rotation| < angle / 2 (mod 360°). Worked by hand, one point per degree.
TEST(CutoutWedge, ARotationTurnsTheWedgeAboutTheMainAxis) {
  const PrincipalAxes a = principalAxes(boxCorners({3, 2, 1}, glm::mat3(1.0f), glm::vec3(1, 2, 3)));
  const CutoutJitter none;
  for (const float rotation : {0.0f, 50.0f, -120.0f, 300.0f})
    for (const float angle : {40.0f, 90.0f, 150.0f}) {
      const CutoutOptions options{.angle = angle, .rotation = rotation};
      const CutoutWedge w = cutoutWedge(a, options, {0.3f, -0.8f, 0.5f});
      int removed = 0;
      for (int k = 0; k < 360; ++k) {
        const float degrees = float(k) + 0.5f, phi = glm::radians(degrees);
        const glm::vec3 p = a.center + 0.4f * a.axes[0] +
                            0.7f * (std::cos(phi) * a.axes[1] + std::sin(phi) * a.axes[2]);
        const float off = std::abs(std::remainder(degrees - rotation, 360.0f));
        if (std::abs(off - angle / 2) < 1.0f) continue;  // within a degree of a plane
        const bool expected = off < angle / 2;
        removed += expected;
        EXPECT_EQ(cutoutDistance(w, none, p) > 0.0f, expected)
            << "rotation " << rotation << ", angle " << angle << ", point at " << degrees << "°";
      }
      EXPECT_NEAR(removed, angle - 2, 2) << "rotation " << rotation << ", angle " << angle;
    }
}

TEST(CutoutJitter, PatternsStayInRangeAndSawtoothIsATriangleWave) {
  const PrincipalAxes a = principalAxes(boxCorners({3, 1, 1}, glm::mat3(1.0f), glm::vec3(0.0f)));
  const CutoutWedge w = cutoutWedge(a, {}, {0, 0, 1});
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-3.0f, 3.0f);
  for (const auto pattern : {CutoutJitter::Pattern::Sawtooth, CutoutJitter::Pattern::Noise}) {
    CutoutJitter j{.pattern = pattern};
    for (int i = 0; i < 2000; ++i) {
      const float p = cutoutPerturbation(w, j, {u(rng), u(rng), u(rng)});
      EXPECT_GE(p, -1.0f);
      EXPECT_LE(p, 1.0f);
    }
  }
  // On the axis (radial 0: tri(0) = 1) the sawtooth is (1 + tri(s·f/L)) / 2: 1 at s = 0,
  // 0 half a period away.
  CutoutJitter saw{.pattern = CutoutJitter::Pattern::Sawtooth, .frequency = 6.0f};
  EXPECT_NEAR(cutoutPerturbation(w, saw, {0, 0, 0}), 1.0f, 1e-6f);
  EXPECT_NEAR(cutoutPerturbation(w, saw, {0.5f, 0, 0}), 0.0f, 1e-6f);
  EXPECT_NEAR(cutoutPerturbation(w, saw, {0.25f, 0, 0}), 0.5f, 1e-6f);
}

// The half-spaces the mesh kind draws without the cutter's code (Cutter::Slab), over random
// wedges (two planes, or four with an axial range, from random boxes' axes and viewers), every
// jitter, and random boxes: a point of the box in any of them is kept by cutoutDistance, with
// the jitter at its extremes; and a plane that keeps part of the box by more than the jitter
// (and a hair) gives one.
TEST(CutoutWedge, TheHalfSpacesKeptWholeHoldNoPointTheWedgeRemoves) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  auto random3 = [&] { return glm::vec3(u(rng), u(rng), u(rng)); };
  int inKept = 0, missed = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const glm::mat3 r = glm::mat3(glm::rotate(glm::mat4(1.0f), 3.0f * u(rng),
                                              glm::normalize(random3() + glm::vec3(0, 0, 1.5f))));
    const PrincipalAxes axes = principalAxes(boxCorners({3, 1.5f, 1}, r, 5.0f * random3()));
    CutoutOptions options;
    options.angle = 20.0f + 80.0f * (u(rng) + 1.0f);
    if (trial % 2) options.axialRange = glm::vec2(0.2f, 0.7f);
    const CutoutWedge wedge = cutoutWedge(axes, options, random3() * 10.0f);
    CutoutJitter jitter{.pattern = CutoutJitter::Pattern(trial % 3), .amplitude = 0.05f};
    Bounds box;
    box.extend(axes.center + 4.0f * random3());
    box.extend(axes.center + 4.0f * random3());
    const std::vector<glm::vec4> kept = cutoutKeptHalfSpaces(wedge, jitter, box);
    const float amplitude =
        jitter.pattern == CutoutJitter::Pattern::None ? 0.0f : jitter.amplitude * wedge.axisLength;
    // Where the jitter may reach its extremes, its greatest displacement stands for it.
    auto greatest = [&](const glm::vec3& p) {
      float d = 1e30f;
      for (const glm::vec4& plane : wedge.planes)
        d = std::min(d, glm::dot(glm::vec3(plane), p) + plane.w);
      return d + amplitude;
    };
    for (int k = 0; k < 200; ++k) {
      const glm::vec3 p = box.min + (box.max - box.min) * (0.5f * random3() + 0.5f);
      bool held = false;
      for (const glm::vec4& h : kept) held = held || glm::dot(glm::vec3(h), p) + h.w >= 0.0f;
      if (held) {
        ++inKept;
        EXPECT_LE(greatest(p), 0.0f) << trial;
        EXPECT_LE(cutoutDistance(wedge, jitter, p), 0.0f) << trial;
      }
      for (const glm::vec4& plane : wedge.planes)
        if (-(glm::dot(glm::vec3(plane), p) + plane.w) > amplitude + 1e-3f && !held) ++missed;
    }
  }
  EXPECT_EQ(missed, 0);
  EXPECT_GT(inKept, 400 * 50);
}

// The noise pattern's base (cutaway/core/noise.hpp) against what value noise is: lattice values
// uniform in [0, 1) and independent of their neighbours (over 200² lattice points: mean ½ and
// variance 1/12 within 4σ, neighbour correlations under 4/√N, a χ² of ten bins under its
// 0.1 % point), interpolated through them exactly, and C¹ across the cells (smoothstep's
// slope vanishes on the lattice lines: a step ε off a line changes the value by ≤ 3ε²).
TEST(CutoutJitter, TheNoiseIsSmoothValueNoiseOfIndependentUniformLatticeValues) {
  constexpr int n = 200;
  std::vector<double> v(n * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) v[std::size_t(j * n + i)] = latticeValue(i - n / 2, j - n / 2);
  double mean = 0.0;
  std::array<int, 10> bins{};
  for (double x : v) {
    mean += x;
    ASSERT_GE(x, 0.0);
    ASSERT_LT(x, 1.0);
    ++bins[std::size_t(x * 10.0)];
  }
  mean /= double(v.size());
  double variance = 0.0;
  for (double x : v) variance += (x - mean) * (x - mean);
  variance /= double(v.size());
  auto correlation = [&](int di, int dj) {
    double sum = 0.0;
    int count = 0;
    for (int j = 0; j + dj < n; ++j)
      for (int i = 0; i + di < n; ++i, ++count)
        sum += (v[std::size_t(j * n + i)] - mean) * (v[std::size_t((j + dj) * n + i + di)] - mean);
    return sum / count / variance;
  };
  double chi2 = 0.0;
  const double expected = double(v.size()) / 10.0;
  for (int b : bins) chi2 += (b - expected) * (b - expected) / expected;
  const double sigma = std::sqrt(1.0 / 12.0 / double(v.size()));
  std::printf(
      "lattice values: mean %.5f, variance %.5f (1/12 = %.5f), chi2 %.2f, correlations "
      "%.4f %.4f %.4f\n",
      mean, variance, 1.0 / 12.0, chi2, correlation(1, 0), correlation(0, 1), correlation(1, 1));
  EXPECT_NEAR(mean, 0.5, 4.0 * sigma);
  EXPECT_NEAR(variance, 1.0 / 12.0, 0.003);
  EXPECT_LT(chi2, 27.88);  // χ²(9) at p = 0.001
  for (const auto [di, dj] : {std::pair{1, 0}, {0, 1}, {1, 1}, {2, 0}, {0, 2}})
    EXPECT_LT(std::abs(correlation(di, dj)), 4.0 / n) << di << "," << dj;

  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-50.0f, 50.0f);
  const float eps = 0.01f;
  double worstOnLattice = 0.0, worstSlope = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const int i = int(std::floor(u(rng))), j = int(std::floor(u(rng)));
    const float y = u(rng);
    worstOnLattice = std::max(
        worstOnLattice, double(std::abs(valueNoise(float(i), float(j)) - latticeValue(i, j))));
    const float at = valueNoise(float(i), y);
    worstSlope = std::max({worstSlope, double(std::abs(valueNoise(float(i) + eps, y) - at)),
                           double(std::abs(valueNoise(float(i) - eps, y) - at))});
  }
  std::printf(
      "value noise: on the lattice off by %.2e; a step of %.2f off a lattice line "
      "changes it by %.2e (3ε² = %.2e)\n",
      worstOnLattice, eps, worstSlope, 3.0 * eps * eps);
  EXPECT_EQ(worstOnLattice, 0.0);
  EXPECT_LE(worstSlope, 3.0 * eps * eps + 1e-5);
}

// The noise jitter as the cutter applies it (Diepstraten03 §4.5, cutoutPerturbation): the
// octaves' sum Σ wₒ(2 v(2ᵒ uv) − 1) / Σ wₒ with wₒ = 2⁻ᵒ, at uv = (along the axis, from the
// axis) × frequency. Against closed forms at 20,000 far-apart points: one octave of value
// noise with smoothstep weights s and uniform lattice values has mean 0 and variance
// (1/3)·E[(1 − s)² + s²]² = (1/3)(26/35)², and independent octaves add their variances by
// wₒ², so K octaves have (1/3)(26/35)² Σwₒ² / (Σwₒ)². Turning a point about the axis leaves it
// unchanged. (The GPU's pattern equals this one pixel by pixel: CutoutGpuCpu/noise.)
TEST(CutoutJitter, TheFractalNoiseHasTheClosedFormsVarianceAndTurnsWithTheAxis) {
  const CutoutWedge wedge{.origin = {0.3f, -0.2f, 0.1f}, .axis = {0.0f, 0.0f, 1.0f}};
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> along(-400.0f, 400.0f), radial(0.0f, 800.0f),
      angle(0.0f, 6.2831853f);
  for (const int octaves : {1, 2, 4}) {
    const CutoutJitter jitter{
        .pattern = CutoutJitter::Pattern::Noise, .frequency = 1.0f, .octaves = octaves};
    double sumW = 0.0, sumW2 = 0.0;
    for (int o = 0; o < octaves; ++o) sumW += std::ldexp(1.0, -o), sumW2 += std::ldexp(1.0, -2 * o);
    const double expected = (1.0 / 3.0) * std::pow(26.0 / 35.0, 2.0) * sumW2 / (sumW * sumW);
    constexpr int kPoints = 20000;
    double mean = 0.0, square = 0.0, worstTurn = 0.0;
    for (int i = 0; i < kPoints; ++i) {
      const float z = along(rng), r = radial(rng), a = angle(rng), b = angle(rng);
      const auto at = [&](float t) {
        return wedge.origin + glm::vec3(r * std::cos(t), r * std::sin(t), z);
      };
      const double p = cutoutPerturbation(wedge, jitter, at(a));
      mean += p, square += p * p;
      worstTurn = std::max(worstTurn, std::abs(p - cutoutPerturbation(wedge, jitter, at(b))));
    }
    mean /= kPoints;
    const double variance = square / kPoints - mean * mean;
    std::printf("%d octaves: mean %.4f, variance %.5f (closed form %.5f)\n", octaves, mean,
                variance, expected);
    // Standard errors: √(var/N) ≈ 0.003 for the mean, ~1.5% of the variance.
    EXPECT_NEAR(mean, 0.0, 0.015) << octaves;
    EXPECT_NEAR(variance, expected, 0.06 * expected) << octaves;
    // float rounding of the radius after a turn, at radii up to 800 lattice cells.
    EXPECT_LE(worstTurn, 2e-3) << octaves;
  }
}

namespace {

// A unit cube (exterior, watertight) around a tetrahedron (interior), seen from above.
std::string cubeScene(const std::string& cutter) {
  return R"({"resolution": [120, 90], "samples": 1, "style": {"name": "gooch", "lines": false},
    "camera": {"eye": [2.2, 2.6, 3.0], "target": [0.5, 0.5, 0.5], "fov": 40},
    "objects": [
      {"name": "cube", "file": "meshes/cube.obj", "role": "exterior",
       "transform": {"scale": [1.6, 1, 1]}},
      {"name": "tetra", "file": "meshes/tetra.obj", "role": "interior",
       "transform": {"translate": [0.3, 0.3, 0.3], "scale": [0.4, 0.4, 0.4]}}]
    )" + (cutter.empty() ? std::string() : ", \"cutters\": {" + cutter + "}") +
         "}";
}

// The wedge the renderer builds for the cube this frame.
CutoutWedge cubeWedge(const Scene& scene) {
  const std::vector<ExteriorUnit> units = exteriorUnits(scene);
  const Camera camera = scene.resolvedCamera();
  return cutoutWedge(units.at(0).axes, *scene.cutters.find<CutoutOptions>(), camera.eye - units[0].axes.center);
}

}  // namespace

class CutoutGpuCpu : public ::testing::TestWithParam<std::string> {};

// Every pixel of the plain frame that shows the cube's outside at p: where the C++ distance
// at p is clearly positive, the cutout frame must not show that surface; where clearly
// negative it must show it unchanged; and where the cut frame shows the cube's outside, the
// GPU's distance AOV equals the C++ one at its position.
TEST_P(CutoutGpuCpu, SignedDistanceAndRemovalAgree) {
  const std::string jitter = GetParam();
  const std::filesystem::path pattern = test::scratchPath("cutout", "test-perturbation.png");
  if (jitter == "image") {  // a small made-up pattern: diagonal gradient with a bright blob
    Rgba8Image img(8, 6);
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 8; ++x) {
        const auto v = std::uint8_t((x * 29 + y * 13 + (x == 3 && y == 2 ? 120 : 0)) % 256);
        img.at(x, y)[0] = img.at(x, y)[1] = img.at(x, y)[2] = v;
        img.at(x, y)[3] = 255;
      }
    writePng(pattern, img);
  }
  // "rotated": no jitter, the wedge at a set rotation instead of facing the camera.
  std::string options = R"("cutout": {"angle": 100)";
  if (jitter == "rotated") options += R"(, "rotation": 140)";
  if (jitter != "none" && jitter != "rotated") {
    options += R"(, "jitter": {"pattern": ")" + jitter + R"(", "amplitude": 0.06, "frequency": 5)";
    if (jitter == "image") options += R"(, "image": ")" + pattern.string() + "\"";
    options += "}";
  }
  options += "}";
  const Scene cut = parseScene(cubeScene(options), "cube.json", kData);
  const Scene plain = parseScene(cubeScene(""), "cube.json", kData);
  const auto cutAovs = renderAovs(cut);
  const auto plainAovs = renderAovs(plain);
  const CutoutWedge wedge = cubeWedge(cut);
  const CutoutJitter& j = cut.cutters.find<CutoutOptions>()->jitter;
  const FloatImage &plainId = aov(plainAovs, "objectId"), &plainPos = aov(plainAovs, "position"),
                   &plainNormal = aov(plainAovs, "normal"), &cutId = aov(cutAovs, "objectId"),
                   &cutPos = aov(cutAovs, "position"), &cutMask = aov(cutAovs, "cutMask"),
                   &distance = aov(cutAovs, "cutoutDistance");
  const glm::vec3 eye = cut.resolvedCamera().eye;
  // Float noise in interpolated positions, plus GL's coarse bilinear weights for the image.
  const float tolerance = 2e-5f * wedge.axisLength +
                          (jitter == "image" ? 0.02f * j.amplitude * wedge.axisLength : 0.0f);
  const float margin = 0.01f * wedge.axisLength;
  int removed = 0, kept = 0, compared = 0;
  test::Mismatches wrong;  // expected and got: 1 removed, 0 kept
  for (int y = 0; y < plainId.height; ++y)
    for (int x = 0; x < plainId.width; ++x) {
      const glm::vec3 p = glm::make_vec3(plainPos.at(x, y));
      const bool outside = plainId.at(x, y)[0] == 0.0f &&
                           glm::dot(glm::make_vec3(plainNormal.at(x, y)), eye - p) > 0.0f;
      if (outside) {
        const float d = cutoutDistance(wedge, j, p);
        const bool same = cutId.at(x, y)[0] == 0.0f && cutMask.at(x, y)[0] == 0.0f &&
                          glm::length(glm::make_vec3(cutPos.at(x, y)) - p) < 1e-4f;
        if (d > margin) ++removed;
        if (d < -margin) ++kept;
        if ((d > margin && same) || (d < -margin && !same)) wrong.add(x, y, d > margin, !same);
      }
      if (cutId.at(x, y)[0] == 0.0f && cutMask.at(x, y)[0] == 0.0f) {
        const float gpu = distance.at(x, y)[0];
        const float cpu = cutoutDistance(wedge, j, glm::make_vec3(cutPos.at(x, y)));
        EXPECT_NEAR(gpu, cpu, tolerance) << "pixel " << x << "," << y;
        EXPECT_LE(gpu, tolerance) << "a visible exterior fragment lies in the wedge";
        ++compared;
      } else {
        EXPECT_TRUE(std::isnan(distance.at(x, y)[0]) || cutId.at(x, y)[0] == 0.0f);
      }
    }
  EXPECT_EQ(wrong.count(), 0) << wrong;
  EXPECT_GT(removed, 300) << "the wedge should open the cube";
  EXPECT_GT(kept, 300);
  EXPECT_GT(compared, 1000);
}

INSTANTIATE_TEST_SUITE_P(Patterns, CutoutGpuCpu,
                         ::testing::Values("none", "sawtooth", "noise", "image", "rotated"));

// Diepstraten03 §4.5 with an image as the perturbation texture, against the definition rather
// than the C++ mirror: the wedge's plane distance d(p) is displaced by A·L·(2g − 1), g the
// image's grey level read bilinearly with repeat at u = (p − o)·a · F/L (o, a, L the main
// axis' origin, direction and extent; A, F the amplitude and frequency). The image is two
// texels, black and white, so g is a triangle wave along the axis. Each exterior pixel of the
// plain frame is removed exactly where the displaced distance is positive; within 1% of L of
// zero either way.
TEST(Cutout, AnImageJitterDisplacesTheWedgeByItsGreyLevelAlongTheAxis) {
  const std::filesystem::path file = test::scratchPath("cutout", "test-black-white.png");
  Rgba8Image img(2, 1);
  img.at(1, 0)[0] = img.at(1, 0)[1] = img.at(1, 0)[2] = 255;
  img.at(0, 0)[3] = img.at(1, 0)[3] = 255;
  writePng(file, img);
  const float amplitude = 0.08f, frequency = 2.0f;
  char options[400];
  std::snprintf(options, sizeof options,
                R"("cutout": {"angle": 100, "jitter": {"pattern": "image", "amplitude": %g,
                   "frequency": %g, "image": "%s"}})",
                amplitude, frequency, file.c_str());
  const Scene cut = parseScene(cubeScene(options), "cube.json", kData);
  const Scene plain = parseScene(cubeScene(""), "cube.json", kData);
  const auto cutAovs = renderAovs(cut), plainAovs = renderAovs(plain);
  const CutoutWedge wedge = cubeWedge(cut);
  const FloatImage &plainId = aov(plainAovs, "objectId"), &plainPos = aov(plainAovs, "position"),
                   &plainNormal = aov(plainAovs, "normal"), &cutId = aov(cutAovs, "objectId"),
                   &cutPos = aov(cutAovs, "position"), &cutMask = aov(cutAovs, "cutMask");
  const glm::vec3 eye = cut.resolvedCamera().eye;
  const float L = wedge.axisLength;
  int removed = 0, kept = 0, shifted = 0;
  test::Mismatches wrong;  // expected and got: 1 removed, 0 kept
  for (int y = 0; y < plainId.height; ++y)
    for (int x = 0; x < plainId.width; ++x) {
      const glm::vec3 p = glm::make_vec3(plainPos.at(x, y));
      if (plainId.at(x, y)[0] != 0.0f ||
          glm::dot(glm::make_vec3(plainNormal.at(x, y)), eye - p) <= 0.0f)
        continue;  // not the cube's outside
      float planes = 1e30f;
      for (const glm::vec4& plane : wedge.planes)
        planes = std::min(planes, glm::dot(glm::vec3(plane), p) + plane.w);
      // Texel 0 (black) centred at u = 1/4, texel 1 (white) at 3/4, repeating.
      const float u = glm::dot(p - wedge.origin, wedge.axis) * frequency / L;
      const float phase = 2.0f * u - 0.5f;                      // in texels from texel 0's centre
      const float w = phase - 2.0f * std::floor(phase / 2.0f);  // [0, 2): one repeat
      const float grey = w < 1.0f ? w : 2.0f - w;
      const float d = planes + amplitude * L * (2.0f * grey - 1.0f);
      if (std::abs(d) < 0.01f * L) continue;
      const bool same = cutId.at(x, y)[0] == 0.0f && cutMask.at(x, y)[0] == 0.0f &&
                        glm::length(glm::make_vec3(cutPos.at(x, y)) - p) < 1e-4f;
      d > 0.0f ? ++removed : ++kept;
      if ((d > 0.0f) == same) wrong.add(x, y, d > 0.0f, !same);
      shifted += (d > 0.0f) != (planes > 0.0f);
    }
  EXPECT_GT(removed, 300);
  EXPECT_GT(kept, 300);
  EXPECT_GT(shifted, 100) << "the jitter should move the boundary";
  EXPECT_EQ(wrong.count(), 0) << "of " << removed + kept << ": " << wrong;
}

// A jitter image wider than the device's largest texture would upload as nothing (no jitter):
// refused, naming its place in the scene file.
TEST(Cutout, AJitterImageLargerThanTheDeviceTakesIsRefused) {
  Scene scene = parseScene(cubeScene(R"("cutout": {"angle": 100})"), "cube.json", kData);
  CutoutJitter& jitter = scene.cutters.find<CutoutOptions>()->jitter;
  const int wide = test::glContext().info().maxTextureSize + 1;
  jitter.pattern = CutoutJitter::Pattern::Image;
  jitter.imageData = FloatImage(wide, 2, 1);
  test::expectError([&] { Renderer(scene, test::glContext().info()); },
                    {"cube.json", "/cutters/cutout/jitter/image",
                     "a jitter image of " + std::to_string(wide) + "×2 texels exceeds"});
}

// Rule 5: through the wedge the cube's inside shows as its cut wall, in the wall colour, and
// the interior object is never cut.
TEST(Cutout, WallsAreShownAndInteriorIsWhole) {
  const Scene cut = parseScene(cubeScene(R"("cutout": {"angle": 100})"), "cube.json", kData);
  const auto aovs = renderAovs(cut);
  const FloatImage &id = aov(aovs, "objectId"), &mask = aov(aovs, "cutMask");
  int walls = 0, tetra = 0;
  for (int y = 0; y < id.height; ++y)
    for (int x = 0; x < id.width; ++x) {
      walls += mask.at(x, y)[0] == 1.0f;
      tetra += id.at(x, y)[0] == 1.0f;
      if (mask.at(x, y)[0] == 1.0f) EXPECT_EQ(id.at(x, y)[0], 0.0f) << "walls belong to the cube";
    }
  EXPECT_GT(walls, 500);
  EXPECT_GT(tetra, 50);
  // A hollow exterior ("solid": false) shows its inside, no walls.
  Scene hollow = cut;
  hollow.objects[0].params["solid"] = false;
  const auto hollowAovs = renderAovs(hollow);
  const FloatImage& hollowMask = aov(hollowAovs, "cutMask");
  for (float v : hollowMask.data) ASSERT_EQ(v, 0.0f);
}

// Rule 5's wall where the view ray leaves the wedge: each wall pixel's position is the ray's
// exit from the intersection of the wedge's half-spaces (clipped here in the test's own
// terms: the camera's ray through the pixel centre), its normal that exit plane's, and the
// point lies within the cube; and the outside the plain frame shows removed exactly inside
// the half-spaces. With a set rotation (two planes), and with an axial range too (four
// planes: the wedge's end walls as well).
class CutoutWall : public ::testing::TestWithParam<std::string> {};

TEST_P(CutoutWall, LiesWhereTheViewRayLeavesTheWedge) {
  const Scene cut = parseScene(cubeScene(R"("cutout": )" + GetParam()), "cube.json", kData);
  ASSERT_EQ(cubeWedge(cut).planes.size(),
            GetParam().find("axialRange") != std::string::npos ? 4u : 2u);
  const auto aovs = renderAovs(cut);
  const FloatImage &id = aov(aovs, "objectId"), &mask = aov(aovs, "cutMask"),
                   &position = aov(aovs, "position"), &normal = aov(aovs, "normal");
  const CutoutWedge wedge = cubeWedge(cut);
  const Camera camera = cut.resolvedCamera();
  const glm::mat4 inverse =
      glm::inverse(camera.projectionMatrix(float(cut.width) / float(cut.height)) * camera.view());
  // The plain frame: each point of the cube's outside it shows is removed exactly where it
  // lies inside every half-space (n·x + w > 0), by the test's own plane tests, so a plane the
  // GPU dropped shows here even where no wall is seen on it.
  Scene plain = cut;
  plain.cutters.disable<CutoutOptions>();
  const auto plainAovs = renderAovs(plain);
  const FloatImage &plainId = aov(plainAovs, "objectId"), &plainPos = aov(plainAovs, "position");
  int removed = 0;
  test::Mismatches removal;  // 1 removed, 0 kept
  for (int y = 0; y < id.height; ++y)
    for (int x = 0; x < id.width; ++x) {
      if (plainId.at(x, y)[0] != 0.0f) continue;
      const glm::vec3 p = glm::make_vec3(plainPos.at(x, y));
      float inside = 1e30f;
      for (const glm::vec4& plane : wedge.planes)
        inside = std::min(inside, glm::dot(glm::vec3(plane), p) + plane.w);
      if (std::abs(inside) < 1e-3f) continue;  // on a plane: either way
      const bool same =
          id.at(x, y)[0] == 0.0f && glm::length(glm::make_vec3(position.at(x, y)) - p) < 1e-4f;
      removed += inside > 0.0f;
      if ((inside > 0.0f) == same) removal.add(x, y, inside > 0.0f, !same);
    }
  EXPECT_GT(removed, 300);
  EXPECT_EQ(removal.count(), 0) << removal;
  int walls = 0, endWalls = 0, outside = 0;
  test::Mismatches off, turned;  // distances to the exit point; cosines to the exit plane's normal
  for (int y = 0; y < id.height; ++y)
    for (int x = 0; x < id.width; ++x) {
      if (id.at(x, y)[0] != 0.0f || mask.at(x, y)[0] != 1.0f) continue;
      ++walls;
      const glm::vec2 ndc((x + 0.5f) / id.width * 2 - 1, 1 - (y + 0.5f) / id.height * 2);
      const glm::vec4 a = inverse * glm::vec4(ndc, -1, 1), b = inverse * glm::vec4(ndc, 1, 1);
      const glm::vec3 from = glm::vec3(a) / a.w, dir = glm::normalize(glm::vec3(b) / b.w - from);
      // Where the ray leaves the last half-space it is inside (n·x + w > 0: removed side).
      float exit = 1e30f;
      glm::vec3 exitNormal(0.0f);
      for (const glm::vec4& plane : wedge.planes) {
        const glm::vec3 n(plane);
        const float along = glm::dot(n, dir);
        if (along >= 0.0f) continue;
        const float t = -(glm::dot(n, from) + plane.w) / along;
        if (t < exit) exit = t, exitNormal = n;
      }
      ASSERT_LT(exit, 1e29f) << "a wall pixel whose ray never leaves the wedge at " << x << ","
                             << y;
      const glm::vec3 p = glm::make_vec3(position.at(x, y));
      endWalls += std::abs(glm::dot(exitNormal, wedge.axis)) > 0.99f;
      const float distance = glm::length(p - (from + exit * dir));
      if (distance > 2e-3f) off.add(x, y, 0.0, distance);
      const float cosine = glm::dot(glm::normalize(glm::make_vec3(normal.at(x, y))), exitNormal);
      if (cosine < 0.999f) turned.add(x, y, 1.0, cosine);
      // The cube spans [0, 1.6] × [0, 1]².
      outside += glm::any(glm::lessThan(p, glm::vec3(-1e-3f))) ||
                 glm::any(glm::greaterThan(p, glm::vec3(1.6f, 1.0f, 1.0f) + 1e-3f));
    }
  EXPECT_GT(walls, 100);
  // An axial range's end planes show as walls too.
  if (wedge.planes.size() == 4) EXPECT_GT(endWalls, 20);
  // Pixels whose ray grazes the wedge's edge may take the other plane.
  EXPECT_LE(off.count(), walls / 100)
      << "of " << walls << " wall pixels, off the exit point: " << off;
  EXPECT_LE(turned.count(), walls / 100) << "of " << walls << " wall normals, turned: " << turned;
  EXPECT_EQ(outside, 0);
  std::printf("%s: %d removed; %d wall pixels (%d end walls), %d off the exit point, %d turned\n",
              GetParam().c_str(), removed, walls, endWalls, off.count(), turned.count());
}

INSTANTIATE_TEST_SUITE_P(Wedges, CutoutWall,
                         ::testing::Values(R"({"angle": 100, "rotation": 20})",
                                           R"({"angle": 100, "rotation": 20,
                                               "axialRange": [0.25, 0.7]})"));

// Diepstraten03 §4.3: the exterior drawn once per plane with a hardware clip plane shows the
// same objects as the per-fragment method (which adds only the walls' shading).
TEST(Cutout, ClipPlanesMatchTheTextureMethod) {
  const Scene texture = parseScene(cubeScene(R"("cutout": {"angle": 80})"), "cube.json", kData);
  const Scene planes = parseScene(cubeScene(R"("cutout": {"angle": 80, "method": "clipPlanes"})"),
                                  "cube.json", kData);
  const FloatImage a = aov(renderAovs(texture), "objectId");
  const FloatImage b = aov(renderAovs(planes), "objectId");
  int differ = 0;
  for (std::size_t i = 0; i < a.data.size(); ++i) differ += a.data[i] != b.data[i];
  // Hardware clipping and per-fragment discards round differently on boundary pixels only.
  EXPECT_LE(differ, int(a.data.size() / 200)) << differ << " pixels differ";
}

// Every frame of a view clips with the same planes: the objects of interest, drawn after the
// clipped exterior with no plane, stay whole in the second frame too (Mesa's llvmpipe kept
// clipping them with the last exterior object's plane).
TEST(Cutout, ClipPlanesDrawTheSecondFrameAsTheFirst) {
  Scene scene = loadScene(std::string(CUTAWAY_SOURCE_DIR) + "/examples/engine-cutout.json");
  scene.width = 160, scene.height = 120;
  setOption(scene, "cutters.cutout.method", "clipPlanes");
  Renderer renderer(scene, test::glContext().info());
  renderer.setOcclusionCulling(false);
  renderer.render();
  const Rgba8Image first = renderer.readColor();
  renderer.render();
  EXPECT_EQ(renderer.readColor().pixels, first.pixels);
}

// A solid cluster, sheets (points in a plane: a flat interior object; in an axis plane, and
// turned off the axes, where floats leave them nearly coplanar), a wire (points on a line),
// a triangle and one point repeated all grow into a solid.
TEST(Breakaway, InflatedHullContainsTheOffsetBody) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const glm::mat3 turn(glm::rotate(glm::mat4(1.0f), 0.7f, glm::normalize(glm::vec3(1, 2, 3))));
  for (const std::string cluster :
       {"solid", "sheet", "turned sheet", "wire", "triangle", "point"}) {
    SCOPED_TRACE(cluster);
    std::vector<glm::vec3> points;
    for (int i = 0; i < 60; ++i) {
      const glm::vec3 p(2.0f * u(rng), cluster == "wire" ? 0.5f : u(rng),
                        cluster == "solid" ? 0.5f * u(rng) : 0.5f);
      points.push_back(cluster == "turned sheet" ? turn * p : p);
    }
    if (cluster == "triangle") points.resize(3);
    if (cluster == "point") points.assign(5, glm::vec3(0.3f, -0.2f, 0.1f));
    const float offset = 0.3f;
    const Mesh hull = inflatedHull(points, offset);
    EXPECT_TRUE(hull.report.watertight);
    // Support functions: h_inflated(d) lies in [h(d) + 0.9·offset, h(d) + offset] for every
    // direction d (the exact offset body has h(d) + offset).
    std::normal_distribution<float> n(0.0f, 1.0f);
    for (int i = 0; i < 2000; ++i) {
      const glm::vec3 d = glm::normalize(glm::vec3(n(rng), n(rng), n(rng)));
      float h = -1e30f, hi = -1e30f;
      for (const auto& p : points) h = std::max(h, glm::dot(p, d));
      for (const auto& p : hull.positions) hi = std::max(hi, glm::dot(p, d));
      ASSERT_GE(hi, h + 0.9f * offset);
      ASSERT_LE(hi, h + offset * (1.0f + 1e-5f) + 1e-6f);
    }
  }
}

namespace {

// The nearest hit of each pixel-centre ray with `hull`: its window depth (0 where the ray
// misses) and world point, rows top to bottom as the AOVs.
struct HullHits {
  FloatImage depth;
  std::vector<glm::vec3> point;
};
HullHits rayCastHull(const Scene& scene, const Mesh& hull) {
  const Camera camera = scene.resolvedCamera();
  const glm::mat4 viewProjection =
      camera.projectionMatrix(float(scene.width) / float(scene.height)) * camera.view();
  const glm::mat4 inverse = glm::inverse(viewProjection);
  HullHits hits{FloatImage(scene.width, scene.height, 1),
                std::vector<glm::vec3>(std::size_t(scene.width) * std::size_t(scene.height))};
  for (int y = 0; y < scene.height; ++y)
    for (int x = 0; x < scene.width; ++x) {
      const glm::vec2 ndc((x + 0.5f) / scene.width * 2 - 1, 1 - (y + 0.5f) / scene.height * 2);
      const glm::vec4 a = inverse * glm::vec4(ndc, -1, 1), b = inverse * glm::vec4(ndc, 1, 1);
      const glm::vec3 from = glm::vec3(a) / a.w, dir = glm::vec3(b) / b.w - from;
      float nearest = 2.0f;  // in units of the segment near → far
      for (const float t : rayHits(hull, from, dir)) nearest = std::min(nearest, t);
      hits.depth.at(x, y)[0] = 0.0f;
      if (nearest <= 1.0f) {
        const glm::vec3 point = from + nearest * dir;
        const glm::vec4 h = viewProjection * glm::vec4(point, 1.0f);
        hits.depth.at(x, y)[0] = 0.5f * h.z / h.w + 0.5f;
        hits.point[std::size_t(y) * std::size_t(scene.width) + std::size_t(x)] = point;
      }
    }
  return hits;
}

// Pixels where `clip` differs from the ray cast's depth by more than 1e-5 (window depths);
// `covered` counts the pixels the hull covers.
test::Mismatches clipDepthMismatches(const FloatImage& clip, const HullHits& hits, int& covered) {
  test::Mismatches mismatched;
  covered = 0;
  for (int y = 0; y < clip.height; ++y)
    for (int x = 0; x < clip.width; ++x) {
      const float expected = hits.depth.at(x, y)[0], got = clip.at(x, y)[0];
      covered += expected > 0.0f;
      if (std::abs(got - expected) > 1e-5f) mismatched.add(x, y, expected, got);
    }
  return mismatched;
}

}  // namespace

// The clip depth pass (greater-than, then less-than) against the nearest hit of a ray with
// the outer hulls, per pixel; and exterior front faces in front of it are gone.
TEST(Breakaway, ClipDepthMatchesRayCastHullAndRemovesWhatHidesTheInterior) {
  const Scene scene = parseScene(
      cubeScene(R"("breakaway": {"offset": 0.1, "wallThickness": 0.05})"), "cube.json", kData);
  const Scene plain = parseScene(cubeScene(""), "cube.json", kData);
  const auto aovs = renderAovs(scene);
  const auto plainAovs = renderAovs(plain);
  const FloatImage& clip = aov(aovs, "breakawayClipDepth");
  const std::vector<BreakawayCluster> clusters = breakawayClusters(scene, *scene.cutters.find<BreakawayOptions>());
  ASSERT_EQ(clusters.size(), 1u);
  const HullHits hits = rayCastHull(scene, clusters[0].outerHull);
  int covered = 0, removed = 0, wrong = 0;
  const test::Mismatches mismatched = clipDepthMismatches(clip, hits, covered);
  const FloatImage &plainId = aov(plainAovs, "objectId"), &plainDepth = aov(plainAovs, "depth"),
                   &id = aov(aovs, "objectId"), &depth = aov(aovs, "depth");
  for (int y = 0; y < clip.height; ++y)
    for (int x = 0; x < clip.width; ++x) {
      // The cube's surface in front of the hull is removed.
      const float expected = hits.depth.at(x, y)[0];
      if (plainId.at(x, y)[0] == 0.0f && expected > 0.0f &&
          plainDepth.at(x, y)[0] < expected - 1e-4f) {
        ++removed;
        wrong += id.at(x, y)[0] == 0.0f && depth.at(x, y)[0] == plainDepth.at(x, y)[0];
      }
    }
  EXPECT_GT(covered, 200);
  // Pixels whose centre grazes the hull's silhouette may round either way.
  EXPECT_LE(mismatched.count(), covered / 50) << "of " << covered << ": " << mismatched;
  EXPECT_GT(removed, 100);
  EXPECT_EQ(wrong, 0);
}

// Interior objects of two groups make two clusters and two hulls (Diepstraten03 §5: one hole
// per cluster): the clip depth is the nearer of the two ray casts on every pixel.
TEST(Breakaway, TwoGroupsOpenTwoHoles) {
  const Scene scene = parseScene(
      R"({"resolution": [120, 90], "samples": 1, "style": {"name": "gooch", "lines": false},
      "camera": {"eye": [2.2, 2.6, 3.0], "target": [0.8, 0.5, 0.5], "fov": 40},
      "cutters": {"breakaway": {"offset": 0.08}},
      "objects": [
        {"name": "cube", "file": "meshes/cube.obj", "role": "exterior",
         "transform": {"scale": [1.6, 1, 1]}},
        {"name": "left", "file": "meshes/tetra.obj", "role": "interior", "group": "a",
         "transform": {"translate": [0.15, 0.3, 0.3], "scale": [0.3, 0.3, 0.3]}},
        {"name": "right", "file": "meshes/tetra.obj", "role": "interior", "group": "b",
         "transform": {"translate": [1.1, 0.3, 0.3], "scale": [0.3, 0.3, 0.3]}}]})",
      "groups.json", kData);
  const std::vector<BreakawayCluster> clusters =
      breakawayClusters(scene, *scene.cutters.find<BreakawayOptions>());
  ASSERT_EQ(clusters.size(), 2u);
  const HullHits a = rayCastHull(scene, clusters[0].outerHull),
                 b = rayCastHull(scene, clusters[1].outerHull);
  HullHits nearer = a;
  int onlyA = 0, onlyB = 0;
  for (std::size_t i = 0; i < nearer.depth.data.size(); ++i) {
    const float da = a.depth.data[i], db = b.depth.data[i];
    onlyA += da > 0.0f && db == 0.0f, onlyB += db > 0.0f && da == 0.0f;
    if (db > 0.0f && (da == 0.0f || db < da)) nearer.depth.data[i] = db;
  }
  EXPECT_GT(onlyA, 100);  // two holes, apart
  EXPECT_GT(onlyB, 100);
  int covered = 0;
  const test::Mismatches mismatched =
      clipDepthMismatches(aov(renderAovs(scene), "breakawayClipDepth"), nearer, covered);
  EXPECT_LE(mismatched.count(), covered / 50) << "of " << covered << ": " << mismatched;
}

// The wall's two hulls (Diepstraten03 §5): the outer grown by the offset, the inner by the
// offset less the wall thickness, each against the support function of the interior's points
// (the exact offset body's, less at most a tenth: inflatedHull's bound); the GPU's inner clip
// depth against a ray cast of the inner hull; and the wall seen through the hole lies on the
// outer hull, where the ray meets it.
TEST(Breakaway, TheWallLiesBetweenTheOuterAndTheInnerHull) {
  const float offset = 0.12f, thickness = 0.08f;
  const Scene scene = parseScene(
      cubeScene(R"("breakaway": {"offset": 0.12, "wallThickness": 0.08})"), "cube.json", kData);
  const std::vector<BreakawayCluster> clusters =
      breakawayClusters(scene, *scene.cutters.find<BreakawayOptions>());
  ASSERT_EQ(clusters.size(), 1u);
  std::vector<glm::vec3> interior;
  for (const std::size_t i : clusters[0].objects) {
    const SceneObject& o = scene.objects[i];
    for (const glm::vec3& p : o.mesh->positions)
      interior.push_back(glm::vec3(o.transformAt(0.0f) * glm::vec4(p, 1.0f)));
  }
  std::mt19937 rng(5);
  std::normal_distribution<float> n(0.0f, 1.0f);
  for (int i = 0; i < 500; ++i) {
    const glm::vec3 d = glm::normalize(glm::vec3(n(rng), n(rng), n(rng)));
    float h = -1e30f, outer = -1e30f, inner = -1e30f;
    for (const glm::vec3& p : interior) h = std::max(h, glm::dot(p, d));
    for (const glm::vec3& p : clusters[0].outerHull.positions)
      outer = std::max(outer, glm::dot(p, d));
    for (const glm::vec3& p : clusters[0].innerHull.positions)
      inner = std::max(inner, glm::dot(p, d));
    EXPECT_GE(outer, h + 0.9f * offset - 1e-5f);
    EXPECT_LE(outer, h + offset + 1e-5f);
    EXPECT_GE(inner, h + 0.9f * (offset - thickness) - 1e-5f);
    EXPECT_LE(inner, h + (offset - thickness) + 1e-5f);
  }

  const auto aovs = renderAovs(scene);
  const HullHits innerHits = rayCastHull(scene, clusters[0].innerHull);
  int covered = 0;
  const test::Mismatches mismatched =
      clipDepthMismatches(aov(aovs, "breakawayInnerDepth"), innerHits, covered);
  EXPECT_GT(covered, 100);
  EXPECT_LE(mismatched.count(), covered / 50) << "of " << covered << ": " << mismatched;
  // The cut wall: the cube's inside seen through the hole, shown at the outer hull's surface.
  const HullHits outerHits = rayCastHull(scene, clusters[0].outerHull);
  const FloatImage &id = aov(aovs, "objectId"), &mask = aov(aovs, "cutMask"),
                   &position = aov(aovs, "position");
  int wall = 0, off = 0;
  for (int y = 0; y < id.height; ++y)
    for (int x = 0; x < id.width; ++x) {
      if (id.at(x, y)[0] != 0.0f || mask.at(x, y)[0] < 0.5f) continue;  // cut (0.5 or more)
      ++wall;
      ASSERT_GT(outerHits.depth.at(x, y)[0], 0.0f)
          << "a wall pixel off the hull at " << x << "," << y;
      const glm::vec3 hit =
          outerHits.point[std::size_t(y) * std::size_t(id.width) + std::size_t(x)];
      off += glm::length(glm::make_vec3(position.at(x, y)) - hit) > 1e-3f;
    }
  EXPECT_GT(wall, 30);
  EXPECT_LE(off, wall / 50) << off << " of " << wall << " wall pixels off the outer hull";
}
