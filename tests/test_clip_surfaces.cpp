// Trapp13: the clip-surface function (eqs. 1–3) against closed forms and against the GPU on
// dumped world positions, offset maps and their derived maps, volumetric depth sprites
// (depth complexity of known shapes) and the volumetric parity test against ray parity on the
// mesh, and caps that cover exactly the cut.
#include <gtest/gtest.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <random>
#include <sstream>

#include "cutaway/core/error.hpp"
#include "cutaway/cutters/clip_surfaces.hpp"
#include "cutaway/io/mesh_import.hpp"
#include "cutaway/render/renderer.hpp"
#include "cutaway/render/techniques.hpp"
#include "cutters/clip_surfaces/clip_surfaces.hpp"
#include "expect_error.hpp"
#include "gl_test_context.hpp"
#include "mismatches.hpp"
#include "render_aovs.hpp"
#include "run_command.hpp"

using namespace cutaway;
using test::aov;
using test::expectError;
using test::renderAovs;

namespace {

const std::string kData = CUTAWAY_TEST_DATA;
const std::string kSource = CUTAWAY_SOURCE_DIR;

// A torus around z (major radius 1, minor 0.35), closed and consistently oriented.
Mesh torus(int major = 64, int minor = 32) {
  Mesh m;
  for (int i = 0; i < major; ++i)
    for (int j = 0; j < minor; ++j) {
      const float a = 2.0f * 3.14159265f * float(i) / float(major);
      const float b = 2.0f * 3.14159265f * float(j) / float(minor);
      const float rr = 1.0f + 0.35f * std::cos(b);
      m.positions.emplace_back(rr * std::cos(a), rr * std::sin(a), 0.35f * std::sin(b));
    }
  for (int i = 0; i < major; ++i)
    for (int j = 0; j < minor; ++j) {
      const auto at = [&](int p, int q) { return unsigned(((p % major) * minor) + (q % minor)); };
      m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  computeVertexNormals(m);
  analyzeTopology(m);
  return m;
}

Mesh sphere(int rings = 32, int sectors = 64) {
  Mesh m;
  m.positions.emplace_back(0, 0, 1);
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      const float t = 3.14159265f * float(i) / float(rings),
                  p = 2.0f * 3.14159265f * float(j) / float(sectors);
      m.positions.emplace_back(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
    }
  m.positions.emplace_back(0, 0, -1);
  const auto ring = [&](int i, int j) { return unsigned(1 + (i - 1) * sectors + (j % sectors)); };
  const unsigned south = unsigned(m.positions.size() - 1);
  for (int j = 0; j < sectors; ++j) {
    m.triangles.emplace_back(0u, ring(1, j), ring(1, j + 1));
    m.triangles.emplace_back(south, ring(rings - 1, j + 1), ring(rings - 1, j));
    for (int i = 1; i + 1 < rings; ++i) {
      m.triangles.emplace_back(ring(i, j), ring(i + 1, j), ring(i + 1, j + 1));
      m.triangles.emplace_back(ring(i, j), ring(i + 1, j + 1), ring(i, j + 1));
    }
  }
  computeVertexNormals(m);
  analyzeTopology(m);
  return m;
}

Mesh transformed(const Mesh& mesh, const glm::mat4& m) {
  Mesh out;
  out.append(mesh, m);
  analyzeTopology(out);
  return out;
}

// A texture read as GL_LINEAR with GL_REPEAT does: texel (x, y) of a w × h image at texture
// coordinates ((x + ½)/w, (y + ½)/h), row 0 at t = 0.
template <class Texel>
auto bilinearRepeat(int w, int h, glm::vec2 uv, Texel texel) {
  const glm::vec2 at = uv * glm::vec2(w, h) - 0.5f;
  const glm::ivec2 i(glm::floor(at));
  const glm::vec2 f = at - glm::vec2(i);
  const auto wrapped = [&](int x, int y) { return texel(((x % w) + w) % w, ((y % h) + h) % h); };
  return glm::mix(glm::mix(wrapped(i.x, i.y), wrapped(i.x + 1, i.y), f.x),
                  glm::mix(wrapped(i.x, i.y + 1), wrapped(i.x + 1, i.y + 1), f.x), f.y);
}

Mesh hollowBox() {
  return importMeshNodes(kSource + "/examples/data/hollow-box.obj").at(0).mesh;
}

VolumetricDepthSprite spriteOf(const Mesh& mesh, int resolution) {
  (void)test::glContext();
  const GpuMesh gpu(mesh);
  const gl::Program peel = buildDepthPeelProgram();
  return buildDepthSprite(peel.id(), gpu,
                          depthSpriteFrame(mesh.bounds(), glm::mat3(1.0f), resolution), resolution,
                          true)
      .sprite;
}

}  // namespace

TEST(ClipSurface, FlatMapIsThePlaneAndTexCoordsFollowEq2) {
  ClipSurface cs{.origin = {1, 2, 3}, .u = {0, 4, 0}, .v = {0, 0, 2}, .scale = {2, 3, 0.5f}};
  cs.offsetMap = makeOffsetMap({.pattern = OffsetPattern::Flat, .size = 4});
  // N = Û × V̂ = ŷ × ẑ = x̂: eq. 1 is the signed distance to the plane x = 1.
  EXPECT_NEAR(glm::length(cs.normal() - glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(clipSurfaceFunction(cs, {3.5f, 0, 0}), 2.5f, 1e-6f);
  EXPECT_NEAR(clipSurfaceFunction(cs, {0.25f, 9, -4}), -0.75f, 1e-6f);
  // Eq. 2: ((P_N − O)·Û / |U| · S_x, (P_N − O)·V̂ / |V| · S_y).
  const glm::vec2 t = clipSurfaceTexCoord(cs, {7, 4, 4});
  EXPECT_NEAR(t.x, 2.0f / 4.0f * 2.0f, 1e-6f);
  EXPECT_NEAR(t.y, 1.0f / 2.0f * 3.0f, 1e-6f);
}

TEST(ClipSurface, OffsetShiftsTheSurfaceBySz) {
  // A constant map of 0.6 with S_z = 0.5 moves the boundary to x = 1 − 0.3 (eq. 1: P·N − N·O +
  // h·S_z = 0).
  ClipSurface cs{.origin = {1, 0, 0}, .u = {0, 1, 0}, .v = {0, 0, 1}, .scale = {1, 1, 0.5f}};
  cs.offsetMap = FloatImage(2, 2, 1);
  for (float& h : cs.offsetMap.data) h = 0.6f;
  EXPECT_NEAR(clipSurfaceFunction(cs, {0.7f, 0.3f, 0.8f}), 0.0f, 1e-6f);
  ClipSurfaceOptions options{.surfaces = {cs}};
  EXPECT_TRUE(clippedBySurfaces(options, {0.6f, 0, 0}));
  EXPECT_FALSE(clippedBySurfaces(options, {0.8f, 0, 0}));
  // Two surfaces: union clips what either clips, intersection what both clip.
  ClipSurface other = cs;
  other.origin = {0, 0, 0};
  other.u = {0, 0, 1};
  other.v = {1, 0, 0};  // N = ẑ × x̂ = ŷ: clips y < −0.3
  options.surfaces.push_back(other);
  EXPECT_TRUE(clippedBySurfaces(options, {0.6f, 5, 0}));
  options.combine = ClipSurfaceOptions::Combine::Intersection;
  EXPECT_FALSE(clippedBySurfaces(options, {0.6f, 5, 0}));
  EXPECT_TRUE(clippedBySurfaces(options, {0.6f, -5, 0}));
  options.surfaces[1].enabled = false;
  EXPECT_TRUE(clippedBySurfaces(options, {0.6f, 5, 0}));
}

// The renderer draws an object whose box the surfaces keep whole without the clip test
// (clipSurfacesKeepBox), and of an object one surface decides the part beyond its slab's kept
// plane without it and the part beyond its removed plane not at all (clipSurfacesSlab): no
// point may lie on the wrong side, for random surfaces with reliefs, random boxes and both
// combination rules; and the bounds must not be vacuous.
TEST(ClipSurface, ABoxKeptWholeOrSlabbedHoldsNoPointOnTheWrongSide) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), fraction(0.0f, 1.0f);
  const auto direction = [&] {
    glm::vec3 d(unit(random), unit(random), unit(random));
    return glm::length(d) > 0.1f ? glm::normalize(d) : glm::vec3(0, 0, 1);
  };
  int kept = 0, notKept = 0, slabbed = 0;
  for (int trial = 0; trial < 300; ++trial) {
    ClipSurfaceOptions options;
    options.combine =
        trial % 2 ? ClipSurfaceOptions::Combine::Intersection : ClipSurfaceOptions::Combine::Union;
    std::vector<glm::vec2> heights;
    for (int k = 0; k < 1 + trial % 3; ++k) {
      const glm::vec3 u = direction() * (0.5f + 2.0f * fraction(random));
      const glm::vec3 v =
          glm::normalize(glm::cross(u, direction())) * (0.5f + 2.0f * fraction(random));
      ClipSurface cs{.origin = 2.0f * glm::vec3(unit(random), unit(random), unit(random)),
                     .u = u,
                     .v = v,
                     .scale = {1.0f + 3.0f * fraction(random), 1.0f + 3.0f * fraction(random),
                               fraction(random)}};
      cs.offsetMap = makeOffsetMap(
          {.pattern = OffsetPattern::Ridged, .size = 32, .frequency = 2, .seed = unsigned(trial)});
      cs.enabled = (trial + k) % 5 != 0;
      const auto [low, high] =
          std::minmax_element(cs.offsetMap.data.begin(), cs.offsetMap.data.end());
      heights.emplace_back(*low, *high);
      options.surfaces.push_back(std::move(cs));
    }
    const glm::vec3 center = 3.0f * glm::vec3(unit(random), unit(random), unit(random));
    const glm::vec3 half = 1.5f * glm::vec3(fraction(random), fraction(random), fraction(random));
    const Bounds box{.min = center - half, .max = center + half};
    const std::optional<ClipSurfaceSlab> slab = clipSurfacesSlab(options, heights, box);
    bool clipped = false;
    for (int i = 0; i < 400; ++i) {
      const glm::vec3 p =
          glm::mix(box.min, box.max,
                   i < 8 ? glm::vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1)
                         : glm::vec3(fraction(random), fraction(random), fraction(random)));
      const bool c = clippedBySurfaces(options, p);
      clipped |= c;
      // The mesh kind draws the slab's kept side without the clip test and leaves out its
      // removed side.
      if (slab && glm::dot(slab->kept, glm::vec4(p, 1.0f)) >= 0.0f) EXPECT_FALSE(c) << trial;
      if (slab && glm::dot(slab->removed, glm::vec4(p, 1.0f)) < 0.0f) EXPECT_TRUE(c) << trial;
      slabbed += slab ? 1 : 0;
    }
    if (clipSurfacesKeepBox(options, heights, box)) {
      ++kept;
      EXPECT_FALSE(clipped) << "trial " << trial;
    } else {
      ++notKept;
    }
  }
  EXPECT_GT(kept, 60);
  EXPECT_GT(notKept, 60);
  EXPECT_GT(slabbed, 400 * 30);
  // The plane x = 0 under a flat map (N = x̂): kept exactly where the box lies beyond it.
  ClipSurface plane{.origin = {0, 0, 0}, .u = {0, 1, 0}, .v = {0, 0, 1}, .scale = {1, 1, 0}};
  plane.offsetMap = makeOffsetMap({.pattern = OffsetPattern::Flat, .size = 4});
  const ClipSurfaceOptions one{.surfaces = {plane}};
  EXPECT_TRUE(clipSurfacesKeepBox(one, {{0, 0}}, {.min = {0.01f, -5, -5}, .max = {3, 5, 5}}));
  EXPECT_FALSE(clipSurfacesKeepBox(one, {{0, 0}}, {.min = {-0.01f, -5, -5}, .max = {3, 5, 5}}));
  // A relief lifting the surface by S_z·h: h ∈ [0.2, 0.4] with S_z = 1 keeps x > −0.2 − margin.
  ClipSurfaceOptions lifted = one;
  lifted.surfaces[0].scale.z = 1.0f;
  EXPECT_TRUE(
      clipSurfacesKeepBox(lifted, {{0.2f, 0.4f}}, {.min = {-0.19f, 0, 0}, .max = {1, 1, 1}}));
  EXPECT_FALSE(
      clipSurfacesKeepBox(lifted, {{0.2f, 0.4f}}, {.min = {-0.21f, 0, 0}, .max = {1, 1, 1}}));
  // Its slab: the plane lifted by S_z·h_min (kept beyond it) and by S_z·h_max.
  const Bounds near{.min = {-1, 0, 0}, .max = {1, 1, 1}};
  const auto slab = clipSurfacesSlab(lifted, {{0.2f, 0.4f}}, near);
  ASSERT_TRUE(slab);
  EXPECT_NEAR(glm::length(slab->kept - glm::vec4(1, 0, 0, 0.2f)), 0.0f, 1e-4f);
  EXPECT_NEAR(glm::length(slab->removed - glm::vec4(1, 0, 0, 0.4f)), 0.0f, 1e-4f);
  // Two surfaces that both reach the box, or an intersection: no single slab.
  ClipSurfaceOptions two = lifted;
  two.surfaces.push_back(plane);
  EXPECT_FALSE(clipSurfacesSlab(two, {{0.2f, 0.4f}, {0, 0}}, near));
  two.surfaces[1].origin.x = -5;  // reaches it no more: the first alone decides
  EXPECT_TRUE(clipSurfacesSlab(two, {{0.2f, 0.4f}, {0, 0}}, near));
  two.combine = ClipSurfaceOptions::Combine::Intersection;
  EXPECT_FALSE(clipSurfacesSlab(two, {{0.2f, 0.4f}, {0, 0}}, near));
  // No surface enabled: nothing is clipped.
  lifted.surfaces[0].enabled = false;
  EXPECT_TRUE(clipSurfacesKeepBox(lifted, {{0.2f, 0.4f}}, {.min = {-9, -9, -9}, .max = {9, 9, 9}}));
}

TEST(OffsetMap, PatternsTileStayInRangeAndBlend) {
  for (auto pattern : {OffsetPattern::Sawtooth, OffsetPattern::Noise, OffsetPattern::Ridged}) {
    const FloatImage m = makeOffsetMap({.pattern = pattern, .size = 64, .frequency = 4});
    float worstSeam = 0, meanStep = 0;
    for (int y = 0; y < 64; ++y) {
      worstSeam = std::max(worstSeam, std::abs(m.at(63, y)[0] - m.at(0, y)[0]));
      for (int x = 0; x + 1 < 64; ++x)
        meanStep = std::max(meanStep, std::abs(m.at(x + 1, y)[0] - m.at(x, y)[0]));
    }
    for (float h : m.data) ASSERT_TRUE(h >= 0.0f && h <= 1.0f);
    // Across the wrap the map steps no more than between any two neighbours inside it.
    EXPECT_LE(worstSeam, meanStep + 1e-6f) << int(pattern);
  }
  FloatImage a(2, 2, 1), b(4, 4, 1);
  for (float& h : a.data) h = 0.25f;
  for (float& h : b.data) h = 0.5f;
  EXPECT_EQ(blendOffsetMaps(a, b, OffsetBlend::Add).width, 4);
  EXPECT_FLOAT_EQ(blendOffsetMaps(a, b, OffsetBlend::Add).data[5], 0.75f);
  EXPECT_FLOAT_EQ(blendOffsetMaps(a, b, OffsetBlend::Multiply).data[5], 0.125f);
  EXPECT_FLOAT_EQ(blendOffsetMaps(a, b, OffsetBlend::Max).data[5], 0.5f);
  EXPECT_FLOAT_EQ(blendOffsetMaps(a, b, OffsetBlend::Min).data[5], 0.25f);
  EXPECT_FLOAT_EQ(blendOffsetMaps(a, b, OffsetBlend::Mix, 0.25f).data[5], 0.3125f);
  EXPECT_FLOAT_EQ(blendOffsetMaps(a, b, OffsetBlend::Screen).data[5], 0.625f);
}

TEST(OffsetMap, DerivedGradientsAndOcclusion) {
  ClipSurface cs{.u = {2, 0, 0}, .v = {0, 2, 0}, .scale = {1, 1, 0.1f}};
  // The zig-zag h = 1 − |2 fract(4u) − 1| has slope ±8 per unit of u, none along v.
  cs.offsetMap = makeOffsetMap({.pattern = OffsetPattern::Sawtooth, .size = 64, .frequency = 4});
  const FloatImage relief = deriveReliefMaps(cs);
  EXPECT_NEAR(std::abs(relief.at(3, 10)[1]), 8.0f, 1e-3f);
  EXPECT_NEAR(relief.at(3, 10)[2], 0.0f, 1e-6f);
  // Occlusion: the valleys (h = 0) see the ridges and are darker than the ridges (h = 1).
  EXPECT_LT(relief.at(0, 5)[3], relief.at(8, 5)[3]);
  EXPECT_NEAR(relief.at(8, 5)[3], 1.0f, 1e-6f);
  cs.offsetMap = makeOffsetMap({.pattern = OffsetPattern::Flat, .size = 8});
  for (int i = 0; i < 64; ++i) EXPECT_EQ(deriveReliefMaps(cs).data[std::size_t(i) * 4 + 3], 1.0f);
}

// deriveReliefMaps against the per-texel definition, written out plainly (every tap wrapped):
// bit for bit at the edges, inside and in the rows other threads take.
TEST(OffsetMap, DerivedMapsAreThePerTexelDefinitionEverywhere) {
  ClipSurface cs{.u = {3, 0, 0}, .v = {0, 2, 0}, .scale = {2, 1, 0.3f}};
  cs.offsetMap = FloatImage(150, 131, 1);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> level(0.0f, 1.0f);
  for (float& h : cs.offsetMap.data) h = level(random);
  const FloatImage& h = cs.offsetMap;
  const auto at = [&](int x, int y) {
    return h.at(((x % h.width) + h.width) % h.width, ((y % h.height) + h.height) % h.height)[0];
  };
  const float texelU = glm::length(cs.u) / (cs.scale.x * float(h.width));
  const float texelV = glm::length(cs.v) / (cs.scale.y * float(h.height));
  const FloatImage relief = deriveReliefMaps(cs);
  int checked = 0;
  for (int y = 0; y < h.height; ++y)
    for (int x = 0; x < h.width; ++x) {
      const float centre = at(x, y);
      float occlusion = 0.0f;
      for (int d = 0; d < 8; ++d) {
        const float angle = 2.0f * 3.14159265f * float(d) / 8.0f;
        float steepest = 0.0f;
        for (int s = 1; s <= 12; ++s) {
          const int qx = x + int(std::lround(std::cos(angle) * float(s))),
                    qy = y + int(std::lround(std::sin(angle) * float(s)));
          const float dx = float(qx - x) * texelU, dy = float(qy - y) * texelV;
          const float run = std::sqrt(dx * dx + dy * dy);
          steepest = std::max(steepest, (at(qx, qy) - centre) * cs.scale.z / run);
        }
        occlusion += steepest / std::sqrt(1.0f + steepest * steepest);
      }
      const float* r = relief.at(x, y);
      ASSERT_EQ(r[0], centre) << x << ", " << y;
      ASSERT_EQ(r[1], (at(x + 1, y) - at(x - 1, y)) * float(h.width) * 0.5f) << x << ", " << y;
      ASSERT_EQ(r[2], (at(x, y + 1) - at(x, y - 1)) * float(h.height) * 0.5f) << x << ", " << y;
      ASSERT_EQ(r[3], 1.0f - occlusion / 8.0f) << x << ", " << y;
      ++checked;
    }
  EXPECT_EQ(checked, 150 * 131);
}

TEST(OffsetMap, SixteenBitPngKeepsItsLevels) {
  const std::filesystem::path file = test::scratchPath("clip", "offset16.png");
  std::vector<std::uint16_t> levels{0, 1, 257, 65535, 40000, 12345};
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = 3;
  png.height = 2;
  png.format = PNG_FORMAT_LINEAR_Y;
  ASSERT_TRUE(png_image_write_to_file(&png, file.c_str(), 0, levels.data(), 0, nullptr));
  const FloatImage m = readPngGray(file);
  ASSERT_EQ(m.width, 3);
  for (std::size_t i = 0; i < levels.size(); ++i)
    EXPECT_NEAR(m.data[i], float(levels[i]) / 65535.0f, 1e-7f) << i;
  std::filesystem::remove(file);
}

namespace {

// An 8-bit grey PNG of w × h pixels, encoded in memory.
std::vector<std::uint8_t> grayPng(int w, int h, const std::uint8_t* pixels) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = png_uint_32(w), png.height = png_uint_32(h);
  png.format = PNG_FORMAT_GRAY;
  png_alloc_size_t size = 0;
  EXPECT_TRUE(png_image_write_to_memory(&png, nullptr, &size, 0, pixels, 0, nullptr));
  std::vector<std::uint8_t> bytes(size);
  EXPECT_TRUE(png_image_write_to_memory(&png, bytes.data(), &size, 0, pixels, 0, nullptr));
  return bytes;
}

}  // namespace

// A header may claim any size; a 1 × 1 PNG whose header says 46000 × 46000 (its CRC made
// good) is refused before its pixels are allocated, not after 2 GB.
TEST(OffsetMap, APngHeaderClaimingMoreThanItsFileHoldsIsRefused) {
  const std::filesystem::path file = test::scratchPath("clip", "claims.png");
  const std::uint8_t pixel = 7;
  std::vector<std::uint8_t> bytes = grayPng(1, 1, &pixel);
  // IHDR's data starts at byte 16 (signature 8, length 4, type 4): width, height big-endian;
  // its CRC (over type and data) follows the 13 data bytes.
  const auto put = [&](std::size_t at, std::uint32_t v) {
    for (int k = 0; k < 4; ++k) bytes[at + std::size_t(k)] = std::uint8_t(v >> (24 - 8 * k));
  };
  put(16, 46000);
  put(20, 46000);
  std::uint32_t crc = 0xffffffffu;
  for (std::size_t i = 12; i < 29; ++i) {
    crc ^= bytes[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  put(29, ~crc);
  std::ofstream(file, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  expectError([&] { (void)readPngGray(file); },
              {"claims.png", "the header claims 46000 × 46000 pixels, more than a file of " +
                                 std::to_string(bytes.size()) + " bytes can hold"});
  std::filesystem::remove(file);
}

// libpng's "Read Error" said plainly: an empty file, one that ends within the signature, one
// that is no PNG, and a PNG cut off in its image data.
TEST(OffsetMap, EmptyShortForeignAndTruncatedFilesSayWhat) {
  const std::filesystem::path file = test::scratchPath("clip", "broken.png");
  std::vector<std::uint8_t> pixels(64 * 64);
  for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = std::uint8_t(i * 37 % 251);
  const std::vector<std::uint8_t> bytes = grayPng(64, 64, pixels.data());
  const std::string foreign = "v 0 0 0\nv 1 0 0\n";
  for (const auto& [content, reason] :
       {std::pair{std::string(), "cannot read PNG: the file is empty"},
        std::pair{std::string(reinterpret_cast<const char*>(bytes.data()), 5),
                  "cannot read PNG: the file ends within its signature"},
        std::pair{foreign, "cannot read PNG: not a PNG file (no PNG signature)"},
        std::pair{std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size() / 2),
                  "the file ends early (truncated)"}}) {
    std::ofstream(file, std::ios::binary | std::ios::trunc) << content;
    expectError([&] { (void)readPngGray(file); }, {"broken.png", reason});
  }
  std::filesystem::remove(file);
}

// Trapp13 §5.1 drawn where it can be: the tiles capTiles keeps for a torus (axis ẑ, tube 0.35
// around radius 1) cut by a surface through z = 0 with a relief up to S_z = 0.1 below it. The
// cut is the annulus 1 − √(0.35² − z²) ≤ ρ ≤ 1 + √(0.35² − z²) for z ∈ [−0.1, 0]: every tile
// that meets it is kept, while the tiles of the hole and the far corners, more than the
// margin (0.01) and a triangle's extent away from it, are not.
TEST(CapTiles, EveryTileTheCutMeetsIsKeptAndTheHoleAndCornersAreNot) {
  const Mesh mesh = torus();
  ClipSurface cs;
  cs.origin = {-1.5f, -1.5f, 0.0f}, cs.u = {3, 0, 0}, cs.v = {0, 3, 0}, cs.scale = {1, 1, 0.1f};
  constexpr int kTiles = 24;  // 0.125 each
  for (const glm::vec2 relief : {glm::vec2(0.0f), glm::vec2(0.0f, 1.0f)}) {
    const std::vector<std::uint8_t> keep =
        capTiles(mesh, glm::mat4(1.0f), cs, relief, {0, 0, 1, 1}, {kTiles, kTiles}, 0.01f);
    ASSERT_EQ(keep.size(), std::size_t(kTiles * kTiles));
    const float inner = 1.0f - std::sqrt(0.35f * 0.35f - 0.01f * relief.y), outer = 1.0f + 0.35f;
    const float margin = 0.01f + 0.15f;  // the margin, a triangle
    int kept = 0, farTiles = 0;
    test::Mismatches wrong;  // tiles (column, row): 1 drawn, 0 dropped
    for (int y = 0; y < kTiles; ++y)
      for (int x = 0; x < kTiles; ++x) {
        const glm::vec2 lo(-1.5f + 0.125f * float(x), -1.5f + 0.125f * float(y)), hi = lo + 0.125f;
        const float nearest = glm::length(glm::clamp(glm::vec2(0.0f), lo, hi));
        const float farthest = glm::length(glm::max(glm::abs(lo), glm::abs(hi)));
        const bool meets = nearest <= outer && farthest >= std::min(inner, 0.65f);
        const bool far = nearest > outer + margin || farthest < 0.65f - margin;
        const bool k = keep[std::size_t(y * kTiles + x)] != 0;
        kept += k, farTiles += far;
        if ((meets && !k) || (far && k)) wrong.add(x, y, meets, k);
      }
    EXPECT_EQ(wrong.count(), 0) << "relief " << relief.y << ": " << wrong;
    EXPECT_GE(farTiles, 50);  // the hole and the corners, all dropped
    EXPECT_GT(kept, 300);
  }
}

// A cap prism's lift range (§5.1 with §7's relief mapping): over random rectangles of texture
// coordinates, some past the map's edge (repeats) and some wider than it, the range holds every
// bilinear sample inside (dense sampleRepeat), and is no wider than the texels those samples
// read: its ends are samples at the texel centres inside, or at most a texel's reach outside.
TEST(ClipSurface, AReliefRangeHoldsEverySampleOverItsRectangle) {
  const FloatImage map =
      makeOffsetMap({.pattern = OffsetPattern::Ridged, .size = 32, .frequency = 4});
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> at(-2.0f, 3.0f), extent(0.0f, 0.4f);
  for (int k = 0; k < 300; ++k) {
    const glm::vec2 lo(at(rng), at(rng)),
        hi = lo + glm::vec2(extent(rng), k % 50 == 0 ? 1.5f : extent(rng));
    const glm::vec2 range = reliefRangeOver(map, lo, hi);
    float least = 1e30f, greatest = -1e30f;
    for (int j = 0; j <= 64; ++j)
      for (int i = 0; i <= 64; ++i) {
        const float h =
            sampleRepeat(map, glm::mix(lo.x, hi.x, i / 64.0f), glm::mix(lo.y, hi.y, j / 64.0f));
        least = std::min(least, h), greatest = std::max(greatest, h);
      }
    EXPECT_LE(range.x, least + 1e-6f) << k;
    EXPECT_GE(range.y, greatest - 1e-6f) << k;
    // No wider than the texels a rectangle grown by a texel all round reads at their centres.
    const glm::vec2 texel(1.0f / float(map.width), 1.0f / float(map.height));
    float wideLeast = 1e30f, wideGreatest = -1e30f;
    for (float v = std::floor(lo.y * map.height - 1.5f); v <= hi.y * map.height + 1.5f; ++v)
      for (float u = std::floor(lo.x * map.width - 1.5f); u <= hi.x * map.width + 1.5f; ++u) {
        const float h = sampleRepeat(map, (u + 0.5f) * texel.x, (v + 0.5f) * texel.y);
        wideLeast = std::min(wideLeast, h), wideGreatest = std::max(wideGreatest, h);
      }
    EXPECT_GE(range.x, wideLeast - 1e-6f) << k;
    EXPECT_LE(range.y, wideGreatest + 1e-6f) << k;
  }
}

// Trapp13 §5.2: the depth complexity counted by peeling.
TEST(DepthSprite, DepthComplexityOfKnownShapes) {
  EXPECT_EQ(spriteOf(sphere(), 128).depthComplexity, 2);
  EXPECT_EQ(spriteOf(torus(), 128).depthComplexity, 2);  // seen along its axis
  const glm::mat4 edgeOn = glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1, 0, 0));
  EXPECT_EQ(spriteOf(transformed(torus(), edgeOn), 128).depthComplexity, 4);
  EXPECT_EQ(spriteOf(hollowBox(), 64).depthComplexity, 4);
}

// Trapp13 §5.3: the parity test on the GPU-built sprite against ray parity on the triangles,
// on thousands of random points, for non-convex watertight meshes.
TEST(DepthSprite, ParityMatchesRayParityOnRandomPoints) {
  const glm::mat4 tilt = glm::rotate(glm::mat4(1.0f), 0.6f, glm::normalize(glm::vec3(1, 1, 0)));
  for (const Mesh& mesh : std::vector<Mesh>{transformed(torus(), tilt), hollowBox()}) {
    ASSERT_TRUE(mesh.report.watertight);
    const VolumetricDepthSprite vds = spriteOf(mesh, 256);
    const Bounds b = mesh.bounds();
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int inside = 0, wrong = 0;
    std::ostringstream firstWrong;  // the first few, with both answers
    constexpr int kPoints = 5000;
    for (int i = 0; i < kPoints; ++i) {
      const glm::vec3 p = b.min + (b.max - b.min) * glm::vec3(u(rng), u(rng), u(rng));
      const bool reference = insideMesh(mesh, p);
      inside += reference;
      if (volumetricParityTest(vds, p) == reference) continue;
      if (++wrong <= 5)
        firstWrong << "; (" << p.x << ", " << p.y << ", " << p.z << ") expected "
                   << (reference ? "inside" : "outside") << ", got the other";
    }
    EXPECT_GT(inside, kPoints / 20);
    // Only points within a texel of the surface may land on the wrong side.
    EXPECT_LE(wrong, kPoints / 200) << wrong << " of " << kPoints << firstWrong.str();
    std::printf("%d of %d points on the wrong side\n", wrong, kPoints);
  }
}

namespace {

// Where writeTorus writes the torus: this test process's own file, as tests run in parallel.
std::filesystem::path torusFile() {
  return test::scratchPath("clip", "torus.obj");
}

// A torus (watertight, non-convex) clipped by a surface through its middle, seen from above.
std::string torusScene(const std::string& surface, bool caps) {
  return R"({"resolution": [128, 96], "samples": 1, "style": {"name": "gooch", "lines": false},
    "camera": {"eye": [0.4, -2.2, 2.6], "target": [0, 0, 0], "up": [0, 0, 1], "fov": 45},
    "objects": [{"name": "torus", "file": ")" +
         torusFile().string() + R"("}],
    "cutters": {"clipSurfaces": {"caps": )" +
         (caps ? "true" : "false") + R"(, "surfaces": [)" + surface + "]}}}";
}

void writeTorus() {
  const Mesh m = torus();
  std::FILE* f = std::fopen(torusFile().c_str(), "w");
  for (const auto& p : m.positions) std::fprintf(f, "v %.7g %.7g %.7g\n", p.x, p.y, p.z);
  for (const auto& t : m.triangles) std::fprintf(f, "f %u %u %u\n", t.x + 1, t.y + 1, t.z + 1);
  std::fclose(f);
}

// A surface through z ≈ 0.05 clipping the upper half (N = −ẑ: clipped where z > o + h·S_z).
const std::string kNoisySurface =
    R"({"origin": [-1.5, -1.5, 0.05], "u": [0, 3, 0], "v": [3, 0, 0], "scale": [2, 2, 0.1],
        "offsetMap": {"pattern": "noise", "frequency": 3, "size": 64}})";
const std::string kFlatSurface =
    R"({"origin": [-1.5, -1.5, 0.05], "u": [0, 3, 0], "v": [3, 0, 0], "scale": [1, 1, 0]})";

// Where the view ray through the centre of pixel (x, y) of `image` (rows top down) meets
// kFlatSurface's plane z = 0.05; `inverse`: the inverse view-projection.
glm::vec3 onFlatSurface(const glm::mat4& inverse, const FloatImage& image, int x, int y) {
  const glm::vec2 ndc((x + 0.5f) / image.width * 2 - 1, 1 - (y + 0.5f) / image.height * 2);
  const glm::vec4 a = inverse * glm::vec4(ndc, -1, 1), b = inverse * glm::vec4(ndc, 1, 1);
  const glm::vec3 from = glm::vec3(a) / a.w, to = glm::vec3(b) / b.w;
  return from + (0.05f - from.z) / (to.z - from.z) * (to - from);
}

}  // namespace

// The GPU's per-fragment test against clipSurfaceFunction on the plain frame's world
// positions: surface points the C++ form clips are gone, the others stay, pixel by pixel.
TEST(ClipSurface, SetOptionRefusesAnEntryPastTheSurfaces) {
  writeTorus();
  Scene scene = parseScene(torusScene(kNoisySurface, false), "torus.json", kData);
  setOption(scene, "cutters.clipSurfaces.surfaces.0.enabled", "false");
  EXPECT_FALSE(scene.cutters.find<ClipSurfaceOptions>()->surfaces[0].enabled);
  // The write would be lost: the scene has one surface.
  expectError([&] { setOption(scene, "cutters.clipSurfaces.surfaces.3.position", "5"); },
              {"cutters.clipSurfaces.surfaces.3.position", "no entry 3: \"surfaces\" has 1 entry"});
  scene.cutters.erase(ClipSurfaceOptions::kKey);
  expectError([&] { setOption(scene, "cutters.clipSurfaces.surfaces.0.position", "5"); },
              {"no entry 0: \"surfaces\" has 0 entries"});
}

TEST(ClipSurfaceGpu, RemovesExactlyWhatTheCppFunctionClips) {
  writeTorus();
  const Scene clipped = parseScene(torusScene(kNoisySurface, false), "torus.json", kData);
  Scene plain = clipped;
  plain.cutters.disable<ClipSurfaceOptions>();
  const auto a = renderAovs(plain), b = renderAovs(clipped);
  const FloatImage &plainId = aov(a, "objectId"), &plainPos = aov(a, "position"),
                   &id = aov(b, "objectId"), &pos = aov(b, "position"), &mask = aov(b, "clipMask");
  const ClipSurface& cs = clipped.cutters.find<ClipSurfaceOptions>()->surfaces[0];
  int removed = 0, kept = 0, visible = 0;
  test::Mismatches wrong;  // 1 removed (and in the clip mask), 0 kept
  for (int y = 0; y < plainId.height; ++y)
    for (int x = 0; x < plainId.width; ++x) {
      if (id.at(x, y)[0] == 0.0f) {  // what the clipped frame shows is never clipped
        EXPECT_GE(clipSurfaceFunction(cs, glm::make_vec3(pos.at(x, y))), -1e-4f) << x << "," << y;
        ++visible;
      }
      if (plainId.at(x, y)[0] != 0.0f) continue;
      const glm::vec3 p = glm::make_vec3(plainPos.at(x, y));
      const float f = clipSurfaceFunction(cs, p);
      const bool same =
          id.at(x, y)[0] == 0.0f && glm::length(glm::make_vec3(pos.at(x, y)) - p) < 1e-5f;
      if (f < -1e-3f) ++removed;
      if (f > 1e-3f) ++kept;
      if (f < -1e-3f && (same || mask.at(x, y)[0] != 1.0f)) wrong.add(x, y, 1.0, !same);
      if (f > 1e-3f && !same) wrong.add(x, y, 0.0, 1.0);
    }
  EXPECT_EQ(wrong.count(), 0) << wrong;
  EXPECT_GT(removed, 500);
  EXPECT_GT(kept, 300);
  EXPECT_GT(visible, 500);
}

// Trapp13 eqs. 1–3 with a non-constant offset map, in closed form: a sawtooth relief (a triangle
// wave of frequency 3 along U, 64 texels) on the surface above the torus (N = −ẑ, O_z = 0.05,
// S = (2, 2, 0.1)). A surface point is clipped where z > O_z + S_z·h(T_x), h(u) = 1 − |2 frac(3u)
// − 1|, T_x = (y + 1.5)/3·S_x (eq. 2): written here from the equations, not from
// clipSurfaceFunction. Bilinear filtering of the texels is that wave exactly except within a
// texel of its peaks and troughs, which are left out, as are points within 1e-3 of the surface.
TEST(ClipSurfaceGpu, ASawtoothReliefClipsWhereItsTriangleWaveSays) {
  writeTorus();
  const Scene clipped =
      parseScene(torusScene(R"({"origin": [-1.5, -1.5, 0.05], "u": [0, 3, 0], "v": [3, 0, 0],
                     "scale": [2, 2, 0.1],
                     "offsetMap": {"pattern": "sawtooth", "frequency": 3, "size": 64}})",
                            false),
                 "torus.json", kData);
  Scene plain = clipped;
  plain.cutters.disable<ClipSurfaceOptions>();
  const auto a = renderAovs(plain), b = renderAovs(clipped);
  const FloatImage &plainId = aov(a, "objectId"), &plainPos = aov(a, "position"),
                   &id = aov(b, "objectId"), &pos = aov(b, "position");
  int removed = 0, kept = 0;
  test::Mismatches wrong;  // 1 removed, 0 kept
  for (int y = 0; y < plainId.height; ++y)
    for (int x = 0; x < plainId.width; ++x) {
      if (plainId.at(x, y)[0] != 0.0f) continue;
      const glm::vec3 p = glm::make_vec3(plainPos.at(x, y));
      const double u = (double(p.y) + 1.5) / 3.0 * 2.0, phase = 3.0 * u;
      // Peaks at whole phases, troughs at halves; a texel is 3/64 of a phase.
      const double toKink = std::abs(2.0 * phase - std::round(2.0 * phase)) / 2.0;
      if (toKink < 3.0 / 64.0) continue;
      const double h = 1.0 - std::abs(2.0 * (phase - std::floor(phase)) - 1.0);
      const double f = -double(p.z) + 0.05 + 0.1 * h;  // eq. 1 with N = −ẑ
      if (std::abs(f) < 1e-3) continue;
      const bool same =
          id.at(x, y)[0] == 0.0f && glm::length(glm::make_vec3(pos.at(x, y)) - p) < 1e-5f;
      f < 0.0 ? ++removed : ++kept;
      if ((f < 0.0) == same) wrong.add(x, y, f < 0.0, !same);
    }
  EXPECT_EQ(wrong.count(), 0) << wrong;
  EXPECT_GT(removed, 500);
  EXPECT_GT(kept, 300);
}

// Trapp13 §6.1, the caps' normal map: with "normalMap" on, a cap pixel's normal is the normal
// of the displaced surface X(s,t) = O + sU + tV − S_z·h(S_x s, S_y t)·N (eq. 1) at that
// point, facing the eye, here differentiated from the sawtooth's closed form (slope ±2f per
// map unit) rather than from the offset map the shader reads.
TEST(ClipSurfaceGpu, CapNormalsAreThoseOfTheDisplacedSurface) {
  writeTorus();
  std::string text = torusScene(R"({"origin": [-1.5, -1.5, 0.05], "u": [0, 3, 0], "v": [3, 0, 0],
                     "scale": [2, 2, 0.1],
                     "offsetMap": {"pattern": "sawtooth", "frequency": 3, "size": 64}})",
                                true);
  text.replace(text.find(R"("caps": true)"), 12,
               R"("caps": true, "capStyle": {"normalMap": true})");
  const Scene scene = parseScene(text, "torus.json", kData);
  const auto aovs = renderAovs(scene);
  const FloatImage &cap = aov(aovs, "capMask"), &normal = aov(aovs, "normal"),
                   &position = aov(aovs, "position");
  const glm::vec3 eye = scene.resolvedCamera(0.0f).eye;
  const glm::dvec3 U(0, 3, 0), V(3, 0, 0), N(0, 0, -1);  // N = normalize(U × V)
  int checked = 0, tilted = 0;
  double worst = 0;
  for (int y = 0; y < cap.height; ++y)
    for (int x = 0; x < cap.width; ++x) {
      if (cap.at(x, y)[0] != 1.0f) continue;
      const glm::dvec3 p = glm::make_vec3(position.at(x, y));
      const double s = (p.y + 1.5) / 3.0, phase = 3.0 * 2.0 * s;  // f·S_x·s
      // Two texels (3/64 of a phase each) from a kink the derived gradient blends both slopes.
      const double toKink = std::abs(2.0 * phase - std::round(2.0 * phase)) / 2.0;
      if (toKink < 6.0 / 64.0) continue;
      const double slope = phase - std::floor(phase) < 0.5 ? 6.0 : -6.0;  // dh/du, u = S_x s
      const glm::dvec3 ds = U - 0.1 * 2.0 * slope * N;                    // ∂X/∂s
      glm::dvec3 expected = glm::normalize(glm::cross(ds, V));
      if (glm::dot(expected, glm::dvec3(eye) - p) < 0.0) expected = -expected;
      const glm::dvec3 got = glm::normalize(glm::dvec3(glm::make_vec3(normal.at(x, y))));
      const double degrees =
          glm::degrees(std::acos(std::clamp(glm::dot(got, expected), -1.0, 1.0)));
      worst = std::max(worst, degrees);
      ++checked;
      tilted += std::abs(got.y) > 0.3;  // 21.8° off the plane's normal
    }
  std::printf("cap normals: %d pixels, worst %.3f° from the displaced surface's\n", checked, worst);
  EXPECT_GT(checked, 300);
  EXPECT_GT(tilted, checked * 9 / 10);
  EXPECT_LT(worst, 1.0);
}

// Trapp13 §3: the edge-enhancement pass runs over the caps with the clipped meshes, so a
// cap's border with the mesh is outlined (a crease between the cap and the torus) and its flat
// inside is not: line pixels lie along the cap's border, and almost every border pixel has
// one beside it.
TEST(ClipSurfaceGpu, CapBordersAreOutlinedAndTheirInsidesAreNot) {
  writeTorus();
  std::string text = torusScene(kFlatSurface, true);
  text.replace(text.find(R"("lines": false)"), 14,
               R"("lines": {"creases": true, "creaseAngle": 45})");
  const auto aovs = renderAovs(parseScene(text, "torus.json", kData));
  const FloatImage &cap = aov(aovs, "capMask"), &lines = aov(aovs, "lines"),
                   &id = aov(aovs, "objectId");
  const auto isCap = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < cap.width && y < cap.height && cap.at(x, y)[0] == 1.0f;
  };
  const auto lineNear = [&](int x, int y, int r) {
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) {
        const int u = x + dx, v = y + dy;
        if (u >= 0 && v >= 0 && u < lines.width && v < lines.height && lines.at(u, v)[0] >= 0.5f)
          return true;
      }
    return false;
  };
  int border = 0, outlined = 0, inside = 0, linedInside = 0;
  for (int y = 2; y + 2 < cap.height; ++y)
    for (int x = 2; x + 2 < cap.width; ++x) {
      if (!isCap(x, y)) continue;
      bool edge = false, deep = true;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const bool neighbourCap = isCap(x + dx, y + dy);
          deep = deep && neighbourCap;
          // A 4-neighbour of the torus (not the background): the cap's border with the mesh.
          if (std::abs(dx) + std::abs(dy) == 1 && !neighbourCap && id.at(x + dx, y + dy)[0] == 0.0f)
            edge = true;
        }
      if (edge) ++border, outlined += lineNear(x, y, 1);
      if (deep) ++inside, linedInside += lines.at(x, y)[0] >= 0.5f;
    }
  EXPECT_GT(border, 100);
  EXPECT_GT(inside, 500);
  EXPECT_GE(outlined, border * 95 / 100) << outlined << " of " << border;
  EXPECT_EQ(linedInside, 0);
}

// Trapp13 §5.4 with a relief: the cap mesh X(s, t) = O + sU + tV − S_z h(s S_x, t S_y) N is
// displaced by the noisy offset map, so every cap pixel's position lies on the surface of eq. 1
// (f = 0), the map sampled bilinearly there (C++), within the cap grid's interpolation.
TEST(ClipSurfaceGpu, CapsOnAReliefLieOnItsSurface) {
  writeTorus();
  const Scene scene = parseScene(torusScene(kNoisySurface, true), "torus.json", kData);
  const auto aovs = renderAovs(scene);
  const FloatImage &cap = aov(aovs, "capMask"), &pos = aov(aovs, "position");
  const ClipSurface& cs = scene.cutters.find<ClipSurfaceOptions>()->surfaces[0];
  int caps = 0, off = 0, raised = 0;
  double worst = 0.0;
  for (int y = 0; y < cap.height; ++y)
    for (int x = 0; x < cap.width; ++x) {
      if (cap.at(x, y)[0] != 1.0f) continue;
      ++caps;
      const glm::vec3 q = glm::make_vec3(pos.at(x, y));
      const double f = std::abs(clipSurfaceFunction(cs, q));
      worst = std::max(worst, f);
      off += f > 2e-3;
      raised += std::abs(q.z - 0.05f) > 0.01f;  // the relief moves it off the base plane
    }
  EXPECT_GT(caps, 1000);
  EXPECT_EQ(off, 0) << "worst |f| " << worst << " (S_z = 0.1)";
  EXPECT_GT(raised, caps / 4);
}

// Trapp13 §4.5, several surfaces at once on the GPU: a noisy horizontal surface and a vertical
// plane through the torus, under union (clipped where either clips) and intersection (where
// both do), against the C++ functions of each surface on the plain frame's positions; with
// caps on, each cap pixel lies on its surface where the other leaves the cut open (union) or
// clips too (intersection).
TEST(ClipSurfaceGpu, SeveralSurfacesClipAsTheirUnionOrIntersection) {
  writeTorus();
  const std::string vertical =
      R"({"origin": [0.2, -1.5, -1.5], "u": [0, 3, 0], "v": [0, 0, 3], "scale": [1, 1, 0]})";
  for (const char* combine : {"union", "intersection"}) {
    const auto scene = [&](bool caps) {
      std::string text = torusScene(kNoisySurface + ", " + vertical, caps);
      text.replace(text.find("\"caps\""), 6,
                   std::string(R"("combine": ")") + combine + R"(", "caps")");
      return parseScene(text, "torus.json", kData);
    };
    const Scene clipped = scene(false), capped = scene(true);
    Scene plain = clipped;
    plain.cutters.disable<ClipSurfaceOptions>();
    const auto a = renderAovs(plain), b = renderAovs(clipped), c = renderAovs(capped);
    const FloatImage &plainId = aov(a, "objectId"), &plainPos = aov(a, "position"),
                     &id = aov(b, "objectId"), &pos = aov(b, "position"), &cap = aov(c, "capMask"),
                     &capPos = aov(c, "position");
    const ClipSurfaceOptions& o = *clipped.cutters.find<ClipSurfaceOptions>();
    ASSERT_EQ(o.surfaces.size(), 2u);
    const bool both = std::string(combine) == "intersection";
    int removed = 0, kept = 0, caps = 0;
    // Expected and got: 1 removed, 0 kept; for caps the distance to the nearer surface.
    test::Mismatches wrong, wrongCaps;
    for (int y = 0; y < plainId.height; ++y)
      for (int x = 0; x < plainId.width; ++x) {
        if (plainId.at(x, y)[0] == 0.0f) {
          const glm::vec3 p = glm::make_vec3(plainPos.at(x, y));
          const float f0 = clipSurfaceFunction(o.surfaces[0], p),
                      f1 = clipSurfaceFunction(o.surfaces[1], p);
          if (std::abs(f0) > 1e-3f && std::abs(f1) > 1e-3f) {  // clear of both boundaries
            const bool clip = both ? (f0 < 0.0f && f1 < 0.0f) : (f0 < 0.0f || f1 < 0.0f);
            EXPECT_EQ(clip, clippedBySurfaces(o, p));
            const bool same =
                id.at(x, y)[0] == 0.0f && glm::length(glm::make_vec3(pos.at(x, y)) - p) < 1e-5f;
            clip ? ++removed : ++kept;
            if (clip == same) wrong.add(x, y, clip, !same);
          }
        }
        if (cap.at(x, y)[0] != 1.0f) continue;
        ++caps;
        const glm::vec3 q = glm::make_vec3(capPos.at(x, y));
        const float g0 = clipSurfaceFunction(o.surfaces[0], q),
                    g1 = clipSurfaceFunction(o.surfaces[1], q);
        // On one surface (within the relief's sampling), and the other as the rule says.
        const bool on0 = std::abs(g0) < 2e-3f, on1 = std::abs(g1) < 2e-3f;
        const auto otherAgrees = [&](float other) { return both ? other < 2e-3f : other > -2e-3f; };
        if (!((on0 && otherAgrees(g1)) || (on1 && otherAgrees(g0))))
          wrongCaps.add(x, y, 0.0, std::min(std::abs(g0), std::abs(g1)));
      }
    EXPECT_EQ(wrong.count(), 0) << combine << ": " << wrong;
    EXPECT_GT(removed, 150) << combine;
    EXPECT_GT(kept, 150) << combine;
    EXPECT_GT(caps, 200) << combine;
    // Cap pixels on the seam of the two surfaces may belong to either.
    EXPECT_LE(wrongCaps.count(), caps / 100)
        << combine << ", of " << caps << " caps: " << wrongCaps;
  }
}

// Caps close the cut and nothing else: where the view ray meets the (flat) clip plane inside
// the torus, the cap shows; every cap pixel lies inside the torus.
TEST(ClipSurfaceGpu, CapsCoverExactlyTheCut) {
  writeTorus();
  const Scene scene = parseScene(torusScene(kFlatSurface, true), "torus.json", kData);
  const auto aovs = renderAovs(scene);
  const FloatImage &cap = aov(aovs, "capMask"), &pos = aov(aovs, "position"),
                   &parity = aov(aovs, "capParity");
  const Mesh mesh = torus();
  const Camera camera = scene.resolvedCamera();
  const glm::mat4 inverse = glm::inverse(
      camera.projectionMatrix(float(scene.width) / float(scene.height)) * camera.view());
  int expected = 0, covered = 0, outside = 0, capPixels = 0, tested = 0;
  for (int y = 0; y < cap.height; ++y)
    for (int x = 0; x < cap.width; ++x) {
      if (insideMesh(mesh, onFlatSurface(inverse, cap, x, y))) {
        ++expected;
        covered += cap.at(x, y)[0] == 1.0f;
      }
      if (cap.at(x, y)[0] == 1.0f) {
        ++capPixels;
        outside += !insideMesh(mesh, glm::make_vec3(pos.at(x, y)));
      }
      tested += parity.at(x, y)[0] > 0.0f;
    }
  EXPECT_GT(expected, 1000);
  // Pixels whose centre grazes the cross-section's outline may round either way.
  EXPECT_GE(covered, expected - expected / 50) << covered << " of " << expected;
  EXPECT_LE(outside, capPixels / 100) << outside << " of " << capPixels;
  EXPECT_GT(tested, capPixels) << "the cap grid spans more than the cut: parity discards the rest";
}

// A solid modelled inside another without a cavity: the torus inside a block. The two caps
// lie in one plane and both cover the torus's cross-section; the inner one must show there,
// at every size (the tie used to go either way, differently at each size). Against the
// torus's cross-section worked out on the CPU: its pixels show the torus's cap, and the
// block's cap shows around it.
TEST(ClipSurfaceGpu, TheCapOfASolidInsideAnotherShowsInItsCut) {
  writeTorus();
  for (const int width : {96, 128, 200, 320}) {
    SCOPED_TRACE(width);
    std::string json = torusScene(kFlatSurface, true);
    json.replace(json.find("[128, 96]"), 9,
                 "[" + std::to_string(width) + ", " + std::to_string(width * 3 / 4) + "]");
    const std::string block =
        R"({"name": "block", "file": "meshes/cube.obj",
            "transform": {"translate": [-1.6, -1.6, -0.6], "scale": [3.2, 3.2, 1.2]}}, )";
    json.insert(json.find("{\"name\": \"torus\""), block);
    const Scene scene = parseScene(json, "nested.json", kData);
    ASSERT_EQ(scene.objects.size(), 2u);
    const auto aovs = renderAovs(scene);
    const FloatImage &cap = aov(aovs, "capMask"), &ids = aov(aovs, "objectId");
    const Mesh mesh = torus();
    const Camera camera = scene.resolvedCamera();
    const glm::mat4 inverse = glm::inverse(
        camera.projectionMatrix(float(scene.width) / float(scene.height)) * camera.view());
    int inTorus = 0, torusCap = 0, blockCapInTorus = 0, blockCap = 0;
    for (int y = 0; y < cap.height; ++y)
      for (int x = 0; x < cap.width; ++x) {
        const bool inside = insideMesh(mesh, onFlatSurface(inverse, cap, x, y));
        const bool isCap = cap.at(x, y)[0] == 1.0f;
        const int id = int(ids.at(x, y)[0]);
        blockCap += isCap && id == 0;
        if (!inside) continue;
        ++inTorus;
        torusCap += isCap && id == 1;
        blockCapInTorus += isCap && id == 0;
      }
    EXPECT_GT(inTorus, cap.width * cap.height / 20);
    // Pixels whose centre grazes the cross-section's outline may round either way.
    EXPECT_GE(torusCap, inTorus - inTorus / 25) << torusCap << " of " << inTorus;
    EXPECT_LE(blockCapInTorus, inTorus / 25) << blockCapInTorus << " of " << inTorus;
    EXPECT_GT(blockCap, inTorus / 2);  // the block is capped around it
  }
}

// What each pixel of a relief-capped solid shows, against a CPU ray cast: along the pixel's
// view ray the first point inside the torus (between its entry and exit hits) that the
// surface keeps (eq. 1: f ≥ 0, found by steps of 1e-3 and bisection), or nothing where there is
// none. No pixel may show a point behind it or nothing (a pinhole in the cap at its rim, where
// a cap point parts from the bilinear relief, a ray misses the relief in the prism it crosses
// or the parity test read its texel's depth), nor one in front of it or where there is none (a
// cap outside the solid), at the small size where these showed as dotted cap outlines. Seen
// as the other tests see it, straight down, orthographically, and from an eye inside the
// relief's slab (z ∈ 0.05 + 0.1·[h_min, h_max]), whose rays graze the relief.
TEST(ClipSurfaceGpu, EachPixelOfARelievedCapShowsTheRayCastsFirstKeptPointInside) {
  writeTorus();
  const std::string
      base = torusScene(kNoisySurface, true),
      usual = R"({"eye": [0.4, -2.2, 2.6], "target": [0, 0, 0], "up": [0, 0, 1], "fov": 45})";
  const std::vector<std::pair<std::string, int>> views = {
      {usual, 1},
      {R"({"eye": [0.1, -0.3, 3], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 45})", 1},
      {R"({"projection": "orthographic", "eye": [1.2, -2, 2], "target": [0, 0, 0], "up": [0, 0, 1], "height": 3})",
       1},
      {R"({"eye": [0.3, -1.45, 0.1], "target": [0, 0, 0], "up": [0, 0, 1], "fov": 70})", 1},
      {usual, 4},
      // The eye inside the tube, on the clipped side, looking back up at the relief: the
      // derived near plane lies behind the eye plane, where orthographic rays start.
      {R"({"projection": "orthographic", "fit": false, "eye": [1.0, 0.05, 0.3], "target": [0.2, 0, -0.2], "up": [0, 0, 1], "height": 2})",
       1}};
  for (const auto& [view, count] : views) {
    const int samples = count;  // a structured binding, which clang 14's lambdas cannot capture
    SCOPED_TRACE(view + ", " + std::to_string(samples) + " samples");
    std::string text = base;
    text.replace(text.find(usual), usual.size(), view);
    text.replace(text.find("\"samples\": 1"), 12, "\"samples\": " + std::to_string(samples));
    const Scene scene = parseScene(text, "torus.json", kData);
    const auto aovs = renderAovs(scene);
    const FloatImage &pos = aov(aovs, "position"), &id = aov(aovs, "objectId");
    const ClipSurface& cs = scene.cutters.find<ClipSurfaceOptions>()->surfaces[0];
    const Mesh mesh = torus();
    const Camera camera = scene.resolvedCamera();
    const glm::mat4 inverse = glm::inverse(
        camera.projectionMatrix(float(scene.width) / float(scene.height)) * camera.view());
    // Per pixel: the ray's origin, direction and first kept point inside (−1: none).
    std::vector<glm::vec3> from(std::size_t(pos.width) * std::size_t(pos.height)), dir(from.size());
    std::vector<float> first(from.size(), -1.0f);
    for (int y = 0; y < pos.height; ++y)
      for (int x = 0; x < pos.width; ++x) {
        const std::size_t p = std::size_t(y) * std::size_t(pos.width) + std::size_t(x);
        const glm::vec2 ndc((x + 0.5f) / pos.width * 2 - 1, 1 - (y + 0.5f) / pos.height * 2);
        const glm::vec4 a = inverse * glm::vec4(ndc, -1, 1), b = inverse * glm::vec4(ndc, 1, 1);
        from[p] = glm::vec3(a) / a.w, dir[p] = glm::normalize(glm::vec3(b) / b.w - from[p]);
        std::vector<float> hits = rayHits(mesh, from[p], dir[p]);
        std::sort(hits.begin(), hits.end());
        for (std::size_t k = 0; k + 1 < hits.size() && first[p] < 0.0f; k += 2) {
          const auto kept = [&](float t) {
            return clipSurfaceFunction(cs, from[p] + t * dir[p]) >= 0.0f;
          };
          if (kept(hits[k])) {
            first[p] = hits[k];
            break;
          }
          // Steps of 1e-3 up to the exit, the exit included.
          for (float t = hits[k] + 1e-3f; t < hits[k + 1] + 1e-3f; t += 1e-3f) {
            const float at = std::min(t, hits[k + 1]);
            if (!kept(at)) continue;
            float lo = t - 1e-3f, hi = at;
            for (int i = 0; i < 20; ++i) (kept(0.5f * (lo + hi)) ? hi : lo) = 0.5f * (lo + hi);
            first[p] = hi;
            break;
          }
        }
      }
    // With several samples, a pixel whose samples see different surfaces resolves to one of
    // them: only pixels whose eight neighbours show the same surface within 0.05 count there.
    const auto counts = [&](int x, int y) {
      const float f = first[std::size_t(y) * std::size_t(pos.width) + std::size_t(x)];
      if (samples == 1) return true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = std::clamp(x + dx, 0, pos.width - 1),
                    ny = std::clamp(y + dy, 0, pos.height - 1);
          const float g = first[std::size_t(ny) * std::size_t(pos.width) + std::size_t(nx)];
          if ((f < 0.0f) != (g < 0.0f) || std::abs(f - g) > 0.05f) return false;
        }
      return true;
    };
    int seen = 0;
    test::Mismatches pinholes, specks;  // distances along the view ray; −1: nothing
    for (int y = 0; y < pos.height; ++y)
      for (int x = 0; x < pos.width; ++x) {
        if (!counts(x, y)) continue;
        const std::size_t p = std::size_t(y) * std::size_t(pos.width) + std::size_t(x);
        // Distances along the ray, −1 for nothing shown.
        const bool torus = id.at(x, y)[0] == 0.0f;
        const float shown =
            torus ? glm::dot(glm::make_vec3(pos.at(x, y)) - from[p], dir[p]) : -1.0f;
        seen += first[p] >= 0.0f;
        if (first[p] >= 0.0f && (!torus || shown > first[p] + 0.02f))
          pinholes.add(x, y, first[p], shown);
        if (torus && (first[p] < 0.0f || shown < first[p] - 0.02f))
          specks.add(x, y, first[p], shown);
      }
    EXPECT_GT(seen, 2500);
    EXPECT_EQ(pinholes.count(), 0) << "of " << seen << ": " << pinholes;
    EXPECT_EQ(specks.count(), 0) << "of " << seen << ": " << specks;
  }
}

TEST(ClipSurfaceGpu, PerFrameParityMatchesStaticParity) {
  writeTorus();
  Scene scene = parseScene(torusScene(kNoisySurface, true), "torus.json", kData);
  const FloatImage a = aov(renderAovs(scene), "capMask");
  scene.cutters.find<ClipSurfaceOptions>()->parity = ClipSurfaceOptions::Parity::PerFrame;
  const FloatImage b = aov(renderAovs(scene), "capMask");
  int differ = 0, caps = 0;
  for (std::size_t i = 0; i < a.data.size(); ++i)
    differ += a.data[i] != b.data[i], caps += a.data[i] == 1.0f;
  EXPECT_GT(caps, 1000);
  EXPECT_LE(differ, caps / 100) << differ << " of " << caps;
}

// §6.1: a diffuse map multiplies the cap colour where the cap shows, and nowhere else.
// A map wider than the device's largest texture would upload as nothing (a flat cut, no
// tint): refused, naming the map's place in the scene file, before its relief is derived.
TEST(ClipSurfaceGpu, MapsLargerThanTheDeviceTakesAreRefused) {
  const int wide = test::glContext().info().maxTextureSize + 1;
  writeTorus();
  Scene scene = parseScene(torusScene(kFlatSurface, true), "torus.json", kData);
  ClipSurface& cs = scene.cutters.find<ClipSurfaceOptions>()->surfaces[0];
  const FloatImage offsets = cs.offsetMap;
  cs.offsetMap = FloatImage(wide, 1, 1);
  expectError(
      [&] { Renderer(scene, test::glContext().info()); },
      {"torus.json", "/cutters/clipSurfaces/surfaces/0/offsetMap",
       "an offset map of " + std::to_string(wide) + "×1 texels exceeds the GPU's largest texture"});
  cs.offsetMap = offsets;
  cs.diffuseMap = Rgba8Image(1, wide);
  expectError([&] { Renderer(scene, test::glContext().info()); },
              {"/cutters/clipSurfaces/surfaces/0/diffuseMap",
               "a diffuse map of 1×" + std::to_string(wide)});
}

TEST(ClipSurfaceGpu, DiffuseMapTintsOnlyTheCaps) {
  writeTorus();
  const std::filesystem::path red = test::scratchPath("clip", "red.png");
  Rgba8Image img(2, 2);
  for (int i = 0; i < 4; ++i)
    img.pixels[std::size_t(i) * 4] = 255, img.pixels[std::size_t(i) * 4 + 3] = 255;
  writePng(red, img);
  const std::string surface = kFlatSurface.substr(0, kFlatSurface.size() - 1) +
                              R"(, "diffuseMap": ")" + red.string() + "\"}";
  const Scene plain = parseScene(torusScene(kFlatSurface, true), "torus.json", kData);
  const Scene tinted = parseScene(torusScene(surface, true), "torus.json", kData);
  Renderer a(plain, test::glContext().info()), b(tinted, test::glContext().info());
  a.render();
  b.render();
  const Rgba8Image ca = a.readColor(), cb = b.readColor();
  const FloatImage cap = aov(a.readAovs(), "capMask");
  int caps = 0, redder = 0, changedElsewhere = 0;
  for (int y = 0; y < cap.height; ++y)
    for (int x = 0; x < cap.width; ++x) {
      const auto* p = ca.at(x, y);
      const auto* q = cb.at(x, y);
      if (cap.at(x, y)[0] == 1.0f) {
        ++caps;
        redder += q[1] < p[1] && q[2] <= p[2];  // green (and blue) removed by the red map
      } else {
        changedElsewhere += p[0] != q[0] || p[1] != q[1] || p[2] != q[2];
      }
    }
  EXPECT_GT(caps, 1000);
  EXPECT_GE(redder, caps * 95 / 100);
  // Anti-aliased cap edges blend into their neighbours; nothing farther away changes.
  EXPECT_LE(changedElsewhere, caps / 10);
}

namespace {

// The torus (writeTorus) under one directional light towards −(0.3, 0.5, −1), seen from
// above at an angle, cut by clip surface `surface` with caps; `style` is the style's JSON,
// `object` and `clip` add keys to the object and the clip-surface options.
Scene litTorusScene(const std::string& style, const std::string& object, const std::string& clip,
                    const std::string& surface) {
  writeTorus();
  return parseScene(
      R"({"resolution": [128, 96], "samples": 1, "style": )" + style +
          R"(, "lights": [{"type": "directional", "direction": [0.3, 0.5, -1], "space": "world"}],
          "camera": {"eye": [0.4, -2.2, 2.6], "target": [0, 0, 0], "up": [0, 0, 1], "fov": 45},
          "objects": [{"name": "torus", )" +
          object + R"("file": ")" + torusFile().string() +
          R"("}], "cutters": {"clipSurfaces": {"caps": true, )" + clip + R"("surfaces": [)" +
          surface + "]}}}",
      "torus.json", kData);
}

// The light of litTorusScene, towards it.
const glm::vec3 kTowardsLight = -glm::normalize(glm::vec3(0.3f, 0.5f, -1.0f));

// A flat cap's Blinn-Phong under that light (ambient 0.1; the cap's normal +z, towards the
// eye, its specular weight 0.05 and shininess 16) at p, base colour kd.
glm::vec3 flatCapShading(const glm::vec3& kd, const glm::vec3& p, const glm::vec3& eye) {
  const glm::vec3 n(0.0f, 0.0f, 1.0f), l = kTowardsLight;
  const glm::vec3 h = glm::normalize(l + glm::normalize(eye - p));
  return 0.1f * kd + kd * std::max(glm::dot(n, l), 0.0f) +
         glm::vec3(0.05f * std::pow(std::max(glm::dot(n, h), 0.0f), 16.0f));
}

// The scene rendered; the largest difference in levels of 255 between each cap pixel away
// from the cap's anti-aliased rim and expected(world position), and how many there were.
template <class Expected>
std::pair<double, int> capPixelsAgainst(const Scene& scene, Expected expected) {
  Renderer renderer(scene, test::glContext().info());
  renderer.render();
  const Rgba8Image color = renderer.readColor();
  const auto aovs = renderer.readAovs();
  const FloatImage &cap = aov(aovs, "capMask"), &position = aov(aovs, "position");
  double worst = 0.0;
  int caps = 0;
  for (int y = 1; y + 1 < cap.height; ++y)
    for (int x = 1; x + 1 < cap.width; ++x) {
      bool inside = true;
      for (const auto& [dx, dy] : {std::pair{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}})
        inside = inside && cap.at(x + dx, y + dy)[0] == 1.0f;
      if (!inside) continue;
      ++caps;
      const glm::vec3 e = glm::clamp(expected(glm::make_vec3(position.at(x, y))), 0.0f, 1.0f);
      for (int k = 0; k < 3; ++k)
        worst = std::max(worst, std::abs(color.at(x, y)[k] - 255.0 * e[k]));
    }
  return {worst, caps};
}

}  // namespace

// Trapp13's caps are shaded by the style like any surface (their normal the flat surface's,
// turned to the eye; specular weight 0.05, shininess 16) and emphasised by the capped object's
// importance (Burns11 eqs. 3.1–3.4), each cap pixel against the formulas written out here:
// with importance 0 and full shading suppression the cap is its colour greyed by E_c whatever
// the light; otherwise Blinn-Phong of one directional light, then the equations.
TEST(ClipSurfaceGpu, CapsAreShadedByTheStyleAndEmphasisedByImportance) {
  const glm::vec3 kd(0.8f, 0.3f, 0.15f);
  struct Case {
    float importance, ec, es;
  };
  for (const Case c : {Case{0.0f, 0.5f, 1.0f}, Case{0.5f, 0.0f, 0.0f}, Case{0.25f, 0.6f, 0.5f}}) {
    char style[300];
    std::snprintf(style, sizeof style,
                  R"({"name": "blinn-phong", "lines": false, "blinnPhong": {"ambient": 0.1},
                      "emphasis": {"color": %g, "shading": %g}})",
                  c.ec, c.es);
    const std::string surface =
        kFlatSurface.substr(0, kFlatSurface.size() - 1) + R"(, "capColor": [0.8, 0.3, 0.15]})";
    const Scene scene = litTorusScene(
        style, R"("importance": )" + std::to_string(c.importance) + ", ", "", surface);
    const glm::vec3 eye = scene.resolvedCamera().eye;
    const auto [worst, caps] = capPixelsAgainst(scene, [&](const glm::vec3& p) {
      const glm::vec3 suppressed =
          glm::mix(flatCapShading(kd, p, eye), kd, c.es * (1.0f - c.importance));
      const float luma = glm::dot(suppressed, glm::vec3(0.2126f, 0.7152f, 0.0722f));
      return glm::mix(suppressed, glm::vec3(luma), c.ec * (1.0f - c.importance));
    });
    EXPECT_GT(caps, 1000) << "importance " << c.importance;
    // 8-bit rounding; the half-float normal does not enter (the cap's is exact).
    EXPECT_LE(worst, 1.0) << "importance " << c.importance << ", E_c " << c.ec << ", E_s " << c.es;
  }
}

// Trapp13 §6.1: the occlusion map darkens a cap's hollows. With the relief's normals off, a
// cap pixel is the flat cap's Blinn-Phong (as above) times mix(1, a, k): a, the derived map's
// occlusion (deriveReliefMaps' alpha), read bilinearly with repeat at the pixel's T (eq. 2,
// from its world position; S_x and S_y included), and k the strength; each pixel of the cap's
// inside against that, for k = 1 and 0.5.
TEST(ClipSurfaceGpu, TheOcclusionMapDarkensCapsByItsValueAtTheirTexel) {
  const glm::vec3 kd(0.8f, 0.6f, 0.4f);
  for (const float strength : {1.0f, 0.5f}) {
    const std::string surface =
        kNoisySurface.substr(0, kNoisySurface.size() - 1) + R"(, "capColor": [0.8, 0.6, 0.4]})";
    const Scene scene = litTorusScene(
        R"({"name": "blinn-phong", "lines": false, "blinnPhong": {"ambient": 0.1}})",
        R"("importance": 1, )",
        R"("capStyle": {"normalMap": false, "occlusion": )" + std::to_string(strength) + "}, ",
        surface);
    const ClipSurface& cs = scene.cutters.find<ClipSurfaceOptions>()->surfaces[0];
    const FloatImage relief = deriveReliefMaps(cs);
    const glm::vec3 eye = scene.resolvedCamera().eye;
    double darkest = 1.0;
    const auto [worst, caps] = capPixelsAgainst(scene, [&](const glm::vec3& p) {
      const float a = bilinearRepeat(relief.width, relief.height, clipSurfaceTexCoord(cs, p),
                                     [&](int x, int y) { return relief.at(x, y)[3]; });
      const float factor = glm::mix(1.0f, a, strength);
      darkest = std::min(darkest, double(factor));
      return flatCapShading(kd, p, eye) * factor;
    });
    std::printf("occlusion %.1f: %d cap pixels, factor down to %.3f, worst %.2f levels\n", strength,
                caps, darkest, worst);
    EXPECT_GT(caps, 1000);
    EXPECT_LT(darkest, 1.0 - 0.1 * strength);          // the relief has hollows to darken
    EXPECT_LE(worst, 1.0) << "strength " << strength;  // 8-bit rounding
  }
}

// Trapp13 §6.1 Fig. 11: the procedural solid texture is a property of the material, so it is
// anchored to world positions, not to the screen: two orthographic views straight down on a
// flat cap, the second moved by (7, 5) pixels, give every world point the same colour; and
// the texture is a factor in [0.55, 1.1] on the cap colour (from Blinn-Phong with the flat
// cap's normal), with veins: the factor spans over half that range.
TEST(ClipSurfaceGpu, TheSolidTextureStaysWithTheMaterialAsTheViewMoves) {
  writeTorus();
  const glm::vec3 kd(0.8f, 0.6f, 0.4f);
  const glm::vec3 l = -glm::normalize(glm::vec3(0.3f, 0.5f, -1.0f));
  const float pixel = 3.0f / 120.0f;  // an orthographic view 3 units high, 120 pixels
  const auto render = [&](glm::vec2 shift) {
    char camera[200];
    std::snprintf(camera, sizeof camera,
                  R"({"projection": "orthographic", "height": 3, "eye": [%.6f, %.6f, 5],
                      "target": [%.6f, %.6f, 0], "up": [0, 1, 0]})",
                  shift.x, shift.y, shift.x, shift.y);
    const std::string surface =
        kFlatSurface.substr(0, kFlatSurface.size() - 1) + R"(, "capColor": [0.8, 0.6, 0.4]})";
    const Scene scene = parseScene(std::string(R"({"resolution": [120, 120], "samples": 1,
            "style": {"name": "blinn-phong", "lines": false, "blinnPhong": {"ambient": 0.1}},
            "lights": [{"type": "directional", "direction": [0.3, 0.5, -1], "space": "world"}],
            "camera": )") + camera + R"(,
            "objects": [{"name": "torus", "importance": 1, "file": ")" +
                                       torusFile().string() +
                                       R"("}], "cutters": {"clipSurfaces": {"caps": true,
            "capStyle": {"solidTexture": true, "solidTextureScale": 6, "occlusion": 0},
            "surfaces": [)" + surface + "]}}}",
                                   "torus.json", kData);
    Renderer renderer(scene, test::glContext().info());
    renderer.render();
    return std::pair{renderer.readColor(), renderer.readAovs()};
  };
  const auto [a, aAovs] = render(glm::vec2(0.0f));
  const auto [b, bAovs] = render(glm::vec2(7.0f, 5.0f) * pixel);
  const FloatImage &capA = aov(aAovs, "capMask"), &capB = aov(bAovs, "capMask"),
                   &posA = aov(aAovs, "position"), &posB = aov(bAovs, "position");
  // Seen straight down: the cap's normal (0, 0, 1), the view (0, 0, 1).
  const glm::vec3 n(0.0f, 0.0f, 1.0f), h = glm::normalize(l + n);
  const float diffuse = 0.1f + std::max(glm::dot(n, l), 0.0f);
  const float specular = 0.05f * std::pow(std::max(glm::dot(n, h), 0.0f), 16.0f);
  int matched = 0, differ = 0, outOfRange = 0;
  float low = 2.0f, high = 0.0f;
  for (int y = 1; y + 1 < capA.height; ++y)
    for (int x = 1; x + 1 < capA.width; ++x) {
      bool inside = true;  // away from the cap's anti-aliased rim
      for (const auto& [dx, dy] : {std::pair{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}})
        inside = inside && capA.at(x + dx, y + dy)[0] == 1.0f;
      if (!inside) continue;
      // The factor, from the green channel (the largest of the cap colour's after red).
      const float factor = (a.at(x, y)[1] / 255.0f - specular) / (kd.y * diffuse);
      low = std::min(low, factor), high = std::max(high, factor);
      outOfRange += factor < 0.55f - 0.01f || factor > 1.1f + 0.01f;
      // The same world point in the moved view: 7 pixels left, 5 down (rows top down).
      const int bx = x - 7, by = y + 5;
      if (bx < 0 || by >= capB.height || capB.at(bx, by)[0] != 1.0f) continue;
      if (glm::length(glm::make_vec3(posA.at(x, y)) - glm::make_vec3(posB.at(bx, by))) > 1e-3f)
        continue;
      ++matched;
      for (int k = 0; k < 3; ++k) differ += std::abs(int(a.at(x, y)[k]) - int(b.at(bx, by)[k])) > 1;
    }
  std::printf("solid texture: %d points seen twice, factor %.3f to %.3f\n", matched, low, high);
  EXPECT_GT(matched, 1000);
  EXPECT_EQ(differ, 0) << "of " << matched;
  EXPECT_EQ(outOfRange, 0);
  EXPECT_GT(high - low, 0.3f);
}

// Trapp13 §6.1: a diffuse map tints the cap. Each pixel of a flat cap's inside is the
// Blinn-Phong of the cap colour times the map's colour, read bilinearly with repeat at the
// pixel's T (eq. 2), for a 4 × 3 map of unlike colours repeated 2 × 2 times.
TEST(ClipSurfaceGpu, TheDiffuseMapTintsEachCapPixelByItsTexel) {
  const std::filesystem::path file = test::scratchPath("clip", "diffuse-4x3.png");
  Rgba8Image map(4, 3);
  for (int i = 0; i < 12; ++i) {
    for (int k = 0; k < 3; ++k)
      map.pixels[std::size_t(i) * 4 + k] = std::uint8_t(60 + (i * 71 + k * 97) % 190);
    map.pixels[std::size_t(i) * 4 + 3] = 255;
  }
  writePng(file, map);
  const glm::vec3 color(0.9f, 0.85f, 0.8f);
  const Scene scene = litTorusScene(
      R"({"name": "blinn-phong", "lines": false, "blinnPhong": {"ambient": 0.1}})",
      R"("importance": 1, )", "",
      R"({"origin": [-1.5, -1.5, 0.05], "u": [0, 3, 0], "v": [3, 0, 0], "scale": [2, 2, 0],
          "capColor": [0.9, 0.85, 0.8], "diffuseMap": ")" +
          file.string() + R"("})");
  const ClipSurface& cs = scene.cutters.find<ClipSurfaceOptions>()->surfaces[0];
  const glm::vec3 eye = scene.resolvedCamera().eye;
  const auto [worst, caps] = capPixelsAgainst(scene, [&](const glm::vec3& p) {
    const glm::vec3 tint = bilinearRepeat(cs.diffuseMap.width, cs.diffuseMap.height,
                                          clipSurfaceTexCoord(cs, p), [&](int i, int j) {
                                            const std::uint8_t* t = cs.diffuseMap.at(i, j);
                                            return glm::vec3(t[0], t[1], t[2]) / 255.0f;
                                          });
    return flatCapShading(color * tint, p, eye);
  });
  std::printf("diffuse map: %d cap pixels, worst %.2f levels\n", caps, worst);
  EXPECT_GT(caps, 1000);
  // 8-bit rounding, and the GPU filtering an 8-bit map with 8-bit weights (1/256 of a texel
  // step of up to 0.75).
  EXPECT_LE(worst, 2.0);
}
