// The adaptive cutter (Burns08, Burns11 ch. 4–6): GPU passes against their CPU mirrors,
// perspective compensation against the world-space angle, clipping and cut surfaces.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <random>
#include <utility>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "cutaway/cutters/adaptive.hpp"
#include "cutaway/render/renderer.hpp"
#include "cutaway/render/techniques.hpp"
#include "gl_test_context.hpp"
#include "mismatches.hpp"
#include "render_aovs.hpp"
#include "styles/lines/line_pass.hpp"

using namespace cutaway;
using test::aov;
using test::renderAovs;

namespace {

const std::string kData = CUTAWAY_TEST_DATA;

// A scene of random interest boxes (invisible proxies) in front of a wall, so the seed image
// holds many overlapping rear hulls at different depths and angles.
std::string randomBoxesScene(unsigned seed, bool directional, bool orthographic, int buffer,
                             const std::string& variant = "jfa") {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::string proxies;
  for (int i = 0; i < 6; ++i) {
    const float x = 3.0f * u(rng), y = 2.0f * u(rng), z = 2.0f * u(rng),
                s = 0.3f + 0.3f * (u(rng) + 1.0f);
    char box[400];
    std::snprintf(box, sizeof box,
                  R"(%s{"name": "box%d", "box": {"min": [%g, %g, %g], "max": [%g, %g, %g]},
                      "params": {"cutawayAngle": %g}})",
                  i ? "," : "", i, x - s, y - s, z - s, x + s, y + s, z + s,
                  20.0f + 25.0f * (u(rng) + 1.0f));
    proxies += box;
  }
  return std::string(
             R"({"resolution": [96, 64], "samples": 1, "style": {"name": "gooch", "lines": false},
      "camera": {"projection": ")") +
         (orthographic ? "orthographic" : "perspective") +
         R"(", "eye": [2, 5, 14], "target": [0, 0, 0], "fov": 45, "height": 12, "near": 4, "far": 30},
      "cutters": {"adaptive": {"angle": 40, "bufferSize": )" +
         std::to_string(buffer) + R"(, "jumpFlooding": ")" + variant +
         R"(", "directionalConstraint": )" + (directional ? "true" : "false") +
         R"(, "ghostLines": false}},
      "objects": [{"name": "wall", "file": "render/plane.obj",
                   "transform": {"translate": [0, 0, -4]}}],
      "proxies": [)" +
         proxies + "]}";
}

}  // namespace

// The anchor pass (anchors.frag) against cutaway_function.cpp, and GPU jump flooding against
// fields::jumpFlooding, pixel by pixel, through the whole pipeline.
class GpuCpuCutaway : public ::testing::TestWithParam<std::tuple<unsigned, bool, bool>> {};

TEST_P(GpuCpuCutaway, CutawayDepthsAgree) {
  const auto [seed, directional, orthographic] = GetParam();
  Scene gpuScene =
      parseScene(randomBoxesScene(seed, directional, orthographic, 64), "boxes.json", kData);
  Scene cpuScene = gpuScene;
  gpuScene.cutters.find<AdaptiveCutawayOptions>()->compute = AdaptiveCutawayOptions::Compute::Gpu;
  cpuScene.cutters.find<AdaptiveCutawayOptions>()->compute = AdaptiveCutawayOptions::Compute::Cpu;
  const auto gpu = renderAovs(gpuScene);
  const auto cpu = renderAovs(cpuScene);
  const FloatImage& a = aov(gpu, "cutawayDepth");
  const FloatImage& b = aov(cpu, "cutawayDepth");
  ASSERT_EQ(a.data.size(), b.data.size());
  int seeded = 0, cut = 0, mismatched = 0;
  for (float s : aov(gpu, "seedDepth").data) seeded += s > 0.0f;
  for (std::size_t i = 0; i < a.data.size(); ++i) {
    cut += a.data[i] > 0.0f;
    // Float rounding only: the shader and the kernel evaluate the same cone in a different
    // order of operations (and near-ties may pick different anchors of equal depth); the
    // directional constraint's atan and tan add a few ulps more.
    if (std::abs(a.data[i] - b.data[i]) > (directional ? 1e-5f : 2e-6f)) {
      if (++mismatched <= 5)
        ADD_FAILURE() << "pixel " << i % 64 << "," << i / 64 << ": gpu " << a.data[i] << " cpu "
                      << b.data[i];
    }
  }
  EXPECT_EQ(mismatched, 0);
  EXPECT_GT(seeded, 20);
  EXPECT_GT(cut, seeded);  // the cones spread beyond the seeds
}

INSTANTIATE_TEST_SUITE_P(RandomSeeds, GpuCpuCutaway,
                         ::testing::Combine(::testing::Values(1u, 2u, 3u), ::testing::Bool(),
                                            ::testing::Bool()));

// Burns08 eq. 3 / Burns11 eq. 5.7: with perspective compensation the cutaway wall keeps the
// angle θ to the view ray in world space at any zoom; with a fixed screen-space slope it
// does not.
namespace {

// World-space angle (degrees) between the cutaway wall and the central view ray, measured on the
// centre row, right of a small seed box at the screen centre: perspective at camera distance
// `zoom`, or orthographic with a view `zoom` high.
double wallAngle(float zoom, bool compensation, float theta, bool orthographic = false) {
  const float distance = orthographic ? 10.0f : zoom;
  char view[200];
  if (orthographic)
    std::snprintf(view, sizeof view, R"("projection": "orthographic", "height": %g)", zoom);
  else
    std::snprintf(view, sizeof view, R"("fov": 40)");
  char json[1400];
  std::snprintf(
      json, sizeof json,
      R"({"resolution": [128, 128], "samples": 1, "style": {"name": "gooch", "lines": false},
      "camera": {"eye": [0, 0, %g], "target": [0, 0, 0], %s, "near": %g, "far": %g},
      "cutters": {"adaptive": {"angle": %g, "bufferSize": 256, "perspectiveCompensation": %s,
                               "edgeCompression": false, "ghostLines": false}},
      "objects": [{"name": "wall", "file": "render/plane.obj", "transform": {"translate": [0, 0, -2]}}],
      "proxies": [{"name": "seed", "box": {"min": [-0.05, -0.05, -0.5], "max": [0.05, 0.05, -0.4]}}]})",
      distance, view, distance * 0.25f, distance * 2.0f, theta, compensation ? "true" : "false");
  const Scene scene = parseScene(json, "angle.json", kData);
  const auto aovs = renderAovs(scene);
  const FloatImage& c = aov(aovs, "cutawayDepth");  // rows top to bottom
  const Camera camera = scene.resolvedCamera();
  const glm::mat4 inverse = glm::inverse(camera.projectionMatrix(1.0f));
  auto viewPoint = [&](int x) {
    const int y = c.height / 2;
    const glm::vec4 ndc((x + 0.5f) / c.width * 2 - 1, 1 - (y + 0.5f) / c.height * 2,
                        c.at(x, y)[0] * 2 - 1, 1);
    const glm::vec4 h = inverse * ndc;
    return glm::vec3(h) / h.w;
  };
  // Walk right from the seed until the wall leaves it; use the middle of that stretch.
  int first = c.width / 2;
  while (first < c.width - 1 && c.at(first, c.height / 2)[0] >= c.at(c.width / 2, c.height / 2)[0])
    ++first;
  int last = first;
  while (last < c.width - 1 && c.at(last + 1, c.height / 2)[0] > 0.0f) ++last;
  const int a = first + (last - first) / 4, b = first + 3 * (last - first) / 4;
  EXPECT_GT(b - a, 4) << "the wall is too short to measure at distance " << distance;
  const glm::vec3 wall = glm::normalize(viewPoint(b) - viewPoint(a));
  // The view ray at the screen centre, through the seed: the cone's axis.
  const glm::vec3 ray(0.0f, 0.0f, -1.0f);
  return glm::degrees(std::acos(std::abs(glm::dot(wall, ray))));
}

}  // namespace

TEST(PerspectiveCompensation, WallKeepsTheAngleAtEveryZoom) {
  for (float theta : {30.0f, 45.0f, 60.0f}) {
    double worstWithout = 0;
    for (float distance : {4.0f, 8.0f, 16.0f, 32.0f}) {
      const double with = wallAngle(distance, true, theta);
      EXPECT_NEAR(with, theta, 2.0) << "θ " << theta << ", camera distance " << distance;
      worstWithout = std::max(worstWithout, std::abs(wallAngle(distance, false, theta) - theta));
    }
    EXPECT_GT(worstWithout, 2.0) << "θ " << theta
                                 << ": without compensation the angle should drift";
  }
}

// Burns11 §5.2.2 for an orthographic view: the compensated slope |P₂₂|/tan θ keeps the wall
// at θ to the (parallel) view rays whatever the view's height; the screen-space slope does not.
TEST(PerspectiveCompensation, OrthographicWallKeepsTheAngleAtEveryHeight) {
  for (float theta : {30.0f, 45.0f, 60.0f}) {
    double worstWithout = 0;
    for (float height : {1.5f, 3.0f, 6.0f}) {
      EXPECT_NEAR(wallAngle(height, true, theta, true), theta, 2.0)
          << "θ " << theta << ", view height " << height;
      worstWithout =
          std::max(worstWithout, std::abs(wallAngle(height, false, theta, true) - theta));
    }
    EXPECT_GT(worstWithout, 2.0) << "θ " << theta
                                 << ": without compensation the angle should drift";
  }
}

// The wall (secondary) in front of an object of interest is cut away where it hides it, and
// kept elsewhere; the object of interest itself is never cut.
TEST(AdaptiveCutaway, ExposesTheObjectOfInterest) {
  const Scene scene = parseScene(
      R"({"resolution": [80, 60], "samples": 1, "style": {"name": "gooch", "lines": false},
      "camera": {"eye": [0, 0, 10], "target": [0, 0, 0], "fov": 40},
      "cutters": {"adaptive": {"angle": 30, "bufferSize": 128}},
      "objects": [
        {"name": "wall", "file": "render/plane.obj", "transform": {"translate": [0, 0, 2]}},
        {"name": "cube", "file": "meshes/cube.obj", "role": "interest",
         "transform": {"translate": [-0.5, -0.5, -0.5]}}]})",
      "expose.json", kData);
  const auto aovs = renderAovs(scene);
  const FloatImage& id = aov(aovs, "objectId");
  EXPECT_EQ(id.at(40, 30)[0], 1.0f);  // the cube, through the hole in the wall
  EXPECT_EQ(id.at(2, 2)[0], 0.0f);    // the wall, far from the cube
  EXPECT_EQ(id.at(77, 57)[0], 0.0f);
}

namespace {

// A watertight box around a small object of interest, seen from above and to the side: the
// camera and objects, the last keys of a scene file whose settings come before them.
const std::string kShellAroundACore =
    R"("camera": {"eye": [1, 2, 10], "target": [0, 0, 0], "fov": 40},
    "objects": [
      {"name": "shell", "file": "meshes/cube.obj", "transform": {"translate": [-2, -2, -2], "scale": 4}},
      {"name": "core", "file": "meshes/cube.obj", "role": "interest",
       "transform": {"translate": [-0.3, -0.3, -0.3], "scale": 0.6}}]})";

Scene shellAroundACore() {
  return parseScene(
      R"({"resolution": [80, 60], "samples": 1, "style": {"name": "gooch", "lines": false},
      "cutters": {"adaptive": {"angle": 35, "bufferSize": 128}}, )" +
          kShellAroundACore,
      "shell.json", kData);
}

}  // namespace

// Burns08 §4.1: the walls of a watertight box around the object of interest show cut
// surfaces (back faces seen through the cut), outlined (§4.2).
TEST(AdaptiveCutaway, WatertightWallsShowCutSurfaces) {
  const Scene scene = shellAroundACore();
  const auto aovs = renderAovs(scene);
  const FloatImage& mask = aov(aovs, "cutMask");
  const FloatImage& id = aov(aovs, "objectId");
  const FloatImage& outlines = aov(aovs, "cutOutlines");
  int cutPixels = 0, outlinePixels = 0;
  for (float m : mask.data) cutPixels += m > 0.5f;
  for (float o : outlines.data) outlinePixels += o > 0.5f;
  EXPECT_EQ(id.at(40, 30)[0], 1.0f);  // the core is exposed
  EXPECT_GT(cutPixels, 30);           // the shell's cut walls
  EXPECT_GT(outlinePixels, 10);
  // Every cut-surface pixel belongs to the shell, never to the object of interest.
  for (std::size_t i = 0; i < mask.data.size(); ++i)
    if (mask.data[i] > 0.5f) ASSERT_EQ(id.data[i], 0.0f) << i;
}

// A cut opens what lies behind the cut, whose back faces are the cut surfaces (§4.1): a cut
// object that is single-sided (doubleSided: false) shows them as a double-sided one does.
TEST(AdaptiveCutaway, ASingleSidedCutObjectStillShowsItsCutSurfaces) {
  const Scene doubleSided = shellAroundACore();
  Scene singleSided = doubleSided;
  singleSided.objects[0].params["doubleSided"] = false;
  const auto a = renderAovs(doubleSided), b = renderAovs(singleSided);
  int cutPixels = 0;
  for (float m : aov(a, "cutMask").data) cutPixels += m > 0.5f;
  EXPECT_GT(cutPixels, 30);
  for (const char* name : {"cutMask", "objectId", "normal"})
    EXPECT_EQ(aov(a, name).data, aov(b, name).data) << name;
}

// Burns08 §4.2: the cut outline is the border of the cut surfaces: a cut-surface pixel with a
// pixel outside them within the line width along a row or a column (the image's edge
// extends). Checked pixel by pixel against that rule evaluated on the dumped cut mask, at
// widths 1 and 3.
TEST(AdaptiveCutaway, CutOutlinesAreTheBorderOfTheCutSurfaces) {
  for (const int width : {1, 3}) {
    SCOPED_TRACE(width);
    Scene scene = shellAroundACore();
    scene.width = 160, scene.height = 120;
    scene.style.lines = LineStyle{};
    scene.style.lines->width = float(width);
    scene.style.lines->silhouettes = scene.style.lines->creases = false;
    const auto aovs = renderAovs(scene);
    const FloatImage &mask = aov(aovs, "cutMask"), &outlines = aov(aovs, "cutOutlines");
    const auto cut = [&](int x, int y) {
      return mask.at(std::clamp(x, 0, mask.width - 1), std::clamp(y, 0, mask.height - 1))[0] >=
             0.5f;
    };
    int expectedPixels = 0;
    test::Mismatches wrong;  // 1 an outline pixel, 0 not
    for (int y = 0; y < mask.height; ++y)
      for (int x = 0; x < mask.width; ++x) {
        bool border = false;
        for (int r = 1; r <= width && cut(x, y); ++r)
          border = border || !cut(x + r, y) || !cut(x - r, y) || !cut(x, y + r) || !cut(x, y - r);
        expectedPixels += border;
        if (border != (outlines.at(x, y)[0] == 1.0f)) wrong.add(x, y, border, outlines.at(x, y)[0]);
      }
    EXPECT_GT(expectedPixels, 40 * width);
    EXPECT_EQ(wrong.count(), 0) << "of " << expectedPixels << " outline pixels: " << wrong;
  }
}

// The line passes run lines.frag only at the pixels with an object or cut-mask sample
// (LinePass's skipEmpty, the pixels marked in `linePixels`): their coverage is the same, texel
// for texel, as the shader's at every pixel, for the feature lines, the cut outlines and the
// ghost lines, at one and four samples.
TEST(AdaptiveCutaway, LinePassesSkipOnlyPixelsWithoutLines) {
  for (const int samples : {1, 4}) {
    SCOPED_TRACE(samples);
    const Scene scene =
        parseScene(R"({"resolution": [160, 120], "samples": )" + std::to_string(samples) +
                       R"(, "style": {"name": "gooch", "lines": true},
        "cutters": {"adaptive": {"angle": 35, "bufferSize": 128, "ghostLines": {"distance": 4}}}, )" +
                       kShellAroundACore,
                   "lines.json", kData);
    Renderer renderer(scene, test::glContext().info());
    renderer.render();
    const Frame& frame = renderer.frame();
    int background = 0;
    for (const float id : frame.read("objectId", 1)) background += id < 0.0f;
    EXPECT_GT(background, scene.width * scene.height / 10);  // pixels to skip
    struct Lines {
      const char *normal, *objectId, *cutMask;
      std::vector<std::string> coverage;
    };
    for (const Lines& l :
         {Lines{"sceneNormal", "sceneObjectId", "sceneCutMask", {"lines", "cutOutlines"}},
          Lines{"ghostNormal", "ghostObjectId", nullptr, {"ghostLines"}}}) {
      SCOPED_TRACE(l.coverage[0]);
      const LinePass everywhere(l.cutMask != nullptr, samples);
      std::vector<gl::Texture> textures;
      const gl::Framebuffer framebuffer = gl::Framebuffer::create();
      const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
      for (std::size_t i = 0; i < l.coverage.size(); ++i) {
        textures.push_back(gl::Texture::create2D(GL_R16F, scene.width, scene.height));
        glNamedFramebufferTexture(framebuffer.id(), buffers[i], textures.back().id(), 0);
      }
      glNamedFramebufferDrawBuffers(framebuffer.id(), GLsizei(textures.size()), buffers);
      glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
      glViewport(0, 0, scene.width, scene.height);
      everywhere.draw(frame, frame.at(l.normal), frame.at(l.objectId),
                      l.cutMask ? std::optional(frame.at(l.cutMask)) : std::nullopt,
                      *scene.style.lines, true, false);
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      for (std::size_t i = 0; i < textures.size(); ++i) {
        std::vector<float> expected(std::size_t(scene.width) * std::size_t(scene.height));
        glGetTextureImage(textures[i].id(), 0, GL_RED, GL_FLOAT,
                          GLsizei(expected.size() * sizeof(float)), expected.data());
        const std::vector<float> skipped = frame.read(l.coverage[i], 1);
        int drawn = 0, wrong = 0;
        for (std::size_t p = 0; p < expected.size(); ++p)
          drawn += expected[p] > 0.0f, wrong += skipped[p] != expected[p];
        EXPECT_GT(drawn, 20) << l.coverage[i];
        EXPECT_EQ(wrong, 0) << l.coverage[i] << ": of " << drawn << " line pixels";
      }
    }
  }
}

// Burns08 §5.1: the seed is the rear hull of the objects of interest (the greater-than depth
// test), with each texel's local angle θ that of the object seen there (§5.3); each texel of
// the seed buffer against a CPU ray cast through its centre: the farthest hit of any object of
// interest, its window depth and its object's angle.
TEST(AdaptiveCutaway, SeedIsTheRearHullOfTheObjectsOfInterest) {
  const Scene scene = parseScene(
      R"({"resolution": [96, 96], "samples": 1, "style": {"name": "gooch", "lines": false},
      "camera": {"eye": [1.5, 2, 6], "target": [0, 0, 0], "fov": 40},
      "cutters": {"adaptive": {"angle": 30, "bufferSize": 96, "ghostLines": false}},
      "objects": [
        {"name": "wall", "file": "render/plane.obj", "transform": {"translate": [0, 0, 2]}},
        {"name": "cube", "file": "meshes/cube.obj", "role": "interest",
         "params": {"cutawayAngle": 50},
         "transform": {"translate": [-1.2, -0.5, -0.5], "rotate": {"axis": [0, 1, 0], "degrees": 30}}},
        {"name": "tetra", "file": "meshes/tetra.obj", "role": "interest",
         "transform": {"translate": [0.3, -0.2, -1], "scale": 1.2}}]})",
      "seed.json", kData);
  const auto aovs = renderAovs(scene);
  const FloatImage &seed = aov(aovs, "seedDepth"), &angle = aov(aovs, "seedAngle");
  ASSERT_EQ(seed.width, 96);
  const Camera camera = scene.resolvedCamera();
  const glm::mat4 viewProjection = camera.projectionMatrix(1.0f) * camera.view();
  const glm::mat4 inverse = glm::inverse(viewProjection);
  struct Interest {
    Mesh world;
    float theta;
  };
  std::vector<Interest> interest;
  for (const SceneObject& o : scene.objects) {
    if (o.role != Role::Interest) continue;
    Mesh m = *o.mesh;
    for (glm::vec3& p : m.positions) p = glm::vec3(o.transformAt(0.0f) * glm::vec4(p, 1.0f));
    interest.push_back({m, o.name == "cube" ? glm::radians(50.0f) : glm::radians(30.0f)});
  }
  int seeded = 0, grazing = 0;
  test::Mismatches wrongDepth, wrongAngle;
  for (int y = 0; y < seed.height; ++y)
    for (int x = 0; x < seed.width; ++x) {
      const glm::vec2 ndc((x + 0.5f) / seed.width * 2 - 1, 1 - (y + 0.5f) / seed.height * 2);
      const glm::vec4 a = inverse * glm::vec4(ndc, -1, 1), b = inverse * glm::vec4(ndc, 1, 1);
      const glm::vec3 from = glm::vec3(a) / a.w, dir = glm::vec3(b) / b.w - from;
      float farthest = -1.0f, theta = 0.0f;
      for (const Interest& i : interest)
        for (const float t : rayHits(i.world, from, dir))
          if (t > farthest) farthest = t, theta = i.theta;
      float expected = 0.0f;  // no seed
      if (farthest >= 0.0f) {
        const glm::vec4 h = viewProjection * glm::vec4(from + farthest * dir, 1.0f);
        expected = 0.5f * h.z / h.w + 0.5f;
      }
      const float got = seed.at(x, y)[0];
      seeded += got > 0.0f;
      // A texel whose centre grazes a silhouette may round either way.
      if ((got > 0.0f) != (expected > 0.0f)) {
        ++grazing;
        continue;
      }
      if (expected == 0.0f) continue;
      if (std::abs(got - expected) > 1e-5f) wrongDepth.add(x, y, expected, got);
      if (std::abs(angle.at(x, y)[0] - theta) > 1e-4f)
        wrongAngle.add(x, y, theta, angle.at(x, y)[0]);
    }
  EXPECT_GT(seeded, 800);
  EXPECT_LE(grazing, seeded / 50);
  EXPECT_LE(wrongDepth.count(), seeded / 100) << "window depth: " << wrongDepth;
  EXPECT_LE(wrongAngle.count(), seeded / 100) << "θ (radians): " << wrongAngle;
}

// Burns08 §4.3: a ghost line's weight fades with the removed surface's distance in front of
// the cutaway surface, fade = clamp(1 − (C − z)/d, 0, 1) in view depth (C the cutaway's,
// z the surface's, d the ghost distance); every ghost sample of a removed plate against it,
// the cutaway depth read from its buffer at the pixel (buffer and image of one size).
TEST(AdaptiveCutaway, GhostLinesFadeWithTheirDistanceInFrontOfTheCut) {
  const float distance = 4.0f;
  const Scene scene = parseScene(
      R"({"resolution": [96, 96], "samples": 1, "style": {"name": "gooch", "lines": false},
      "camera": {"eye": [0, 0, 10], "target": [0, 0, 0], "fov": 40},
      "cutters": {"adaptive": {"angle": 30, "bufferSize": 96, "ghostLines": {"distance": 4}}},
      "objects": [
        {"name": "plate", "file": "meshes/cube.obj",
         "transform": {"translate": [-0.4, -0.4, 1.5], "rotate": {"axis": [1, 0, 0], "degrees": 25},
                       "scale": 0.8}},
        {"name": "cube", "file": "meshes/cube.obj", "role": "interest",
         "transform": {"translate": [-0.5, -0.5, -0.5]}}]})",
      "fade.json", kData);
  Renderer renderer(scene, test::glContext().info());
  renderer.render();
  const Frame& frame = renderer.frame();
  // Rows bottom to top, the image's and the buffer's alike.
  const std::vector<float> cut = frame.read("cutawayDepth", 1);
  // The fade is the line weight, the top 8 bits of the packed normal (frame/normal_weight.glsl).
  std::vector<GLuint> normal(cut.size());
  glGetTextureImage(frame.texture("ghostNormal").id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                    GLsizei(normal.size() * sizeof(GLuint)), normal.data());
  const std::vector<GLint> idDepth = frame.readIntegers("ghostObjectId", 2);  // id, view depth
  const glm::mat4 inverse = glm::inverse(scene.resolvedCamera().projectionMatrix(1.0f));
  int faded = 0, partial = 0;
  double worst = 0.0;
  for (std::size_t i = 0; i < cut.size(); ++i) {
    const float fade = float(normal[i] >> 24) / 255.0f;
    if (idDepth[2 * i] != 0 || fade <= 0.0f) continue;  // the plate's removed front faces
    const glm::vec4 h = inverse * glm::vec4(0.0f, 0.0f, 2.0f * cut[i] - 1.0f, 1.0f);
    const float c = -h.z / h.w, z = std::bit_cast<float>(idDepth[2 * i + 1]);
    const float expected = std::clamp(1.0f - (c - z) / distance, 0.0f, 1.0f);
    worst = std::max(worst, double(std::abs(fade - expected)));
    ++faded, partial += expected > 0.05f && expected < 0.95f;
  }
  EXPECT_GT(faded, 150);
  EXPECT_GT(partial, 150);  // the tilted plate spans the fade, not its ends
  EXPECT_LE(worst, 0.5 / 255.0 + 1e-4) << "the fade is stored in 8 bits";
}

// The composite pass (frame/composite.frag) against a CPU composition of the dumped buffers:
// at one sample the final colour is the G-buffer's colour with the overlays blended over it
// in order, the feature lines in their colour by their coverage, then the cut outlines in
// theirs (Burns08 §4.2): c ← mix(c, colour, opacity · coverage).
TEST(Renderer, TheCompositeIsTheColourWithItsOverlaysBlendedInOrder) {
  const Scene scene = parseScene(
      R"({"resolution": [80, 60], "samples": 1,
      "style": {"name": "gooch", "lines": {"color": [0.2, 0.1, 0.6]}},
      "cutters": {"adaptive": {"angle": 35, "bufferSize": 128, "outlineColor": [0.9, 0.6, 0.1]}}, )" +
          kShellAroundACore,
      "composite.json", kData);
  Renderer renderer(scene, test::glContext().info());
  renderer.render();
  const Frame& frame = renderer.frame();
  // Rows bottom to top, as OpenGL stores them: the same for all four.
  const std::vector<float> color = frame.read("sceneColor", 3), lines = frame.read("lines", 1),
                           outlines = frame.read("cutOutlines", 1), final = frame.read("color", 3);
  const glm::vec3 lineColor(0.2f, 0.1f, 0.6f), outlineColor(0.9f, 0.6f, 0.1f);
  int lined = 0, outlined = 0;
  test::Mismatches wrong;  // in levels of 255, per channel
  for (std::size_t i = 0; i < lines.size(); ++i) {
    glm::vec3 c = glm::make_vec3(&color[3 * i]);
    c = glm::mix(c, lineColor, lines[i]);
    c = glm::mix(c, outlineColor, outlines[i]);
    lined += lines[i] > 0.5f, outlined += outlines[i] > 0.5f;
    // The final colour is 8-bit: half a level, and the R16F coverages' rounding.
    for (int k = 0; k < 3; ++k)
      if (std::abs(final[3 * i + k] - c[k]) * 255.0f > 0.75f)
        wrong.add(int(i) % scene.width, int(i) / scene.width, 255.0 * c[k],
                  255.0 * final[3 * i + k]);
  }
  EXPECT_GT(lined, 30);
  EXPECT_GT(outlined, 10);
  EXPECT_EQ(wrong.count(), 0) << "(rows bottom up) " << wrong;
}

namespace {

// A 4-unit watertight cube shell (`shell`: extra keys of it) around a point-like proxy seed at
// depth −0.5, seen orthographically down −z (160², 4.4 units high); `adaptive`: the cutter's
// keys besides those that keep the cone exact (512² buffer, no edge compression or ghosts).
Scene pointSeedInAShell(const std::string& adaptive, const std::string& shell,
                        const glm::vec2& seedHalfSide = glm::vec2(0.01f)) {
  const std::string x = std::to_string(seedHalfSide.x), y = std::to_string(seedHalfSide.y);
  return parseScene(
      R"({"resolution": [160, 160], "samples": 1, "style": {"name": "gooch", "lines": false},
        "camera": {"projection": "orthographic", "height": 4.4, "eye": [0, 0, 10],
                   "target": [0, 0, 0]},
        "cutters": {"adaptive": {"bufferSize": 512, "edgeCompression": false,
                                 "ghostLines": false, )" +
          adaptive + R"(}},
        "objects": [{"name": "shell", "file": "meshes/cube.obj", )" +
          shell + R"("transform": {"translate": [-2, -2, -2], "scale": 4}}],
        "proxies": [{"name": "seed", "box": {"min": [-)" +
          x + ", -" + y + R"(, -0.52], "max": [)" + x + ", " + y + R"(, -0.5]}}]})",
      "cone.json", kData);
}

// Degrees between `normal` and the inner normal (−cos θ ρ̂, sin θ) at p of the cone of
// half-angle θ about the view axis.
double degreesFromConeNormal(const glm::vec3& normal, const glm::vec3& p, float theta,
                             const glm::vec2& seedHalfSide = glm::vec2(0.0f)) {
  // From the nearest point of the seed's footprint: a cone about a point, a wedge along a side.
  const glm::vec2 out =
      glm::normalize(glm::vec2(p) - glm::clamp(glm::vec2(p), -seedHalfSide, seedHalfSide));
  const glm::vec3 expected(-std::cos(theta) * out, std::sin(theta));
  return glm::degrees(
      std::acos(std::clamp(double(glm::dot(glm::normalize(normal), expected)), -1.0, 1.0)));
}

}  // namespace

// Burns08 §4.1 / Burns11 §5.2.4.1: the cut surface is shaded with the normal of the cutaway
// surface. Seen orthographically down −z with a point-like seed at depth −0.5, that surface is
// the cone of half-angle θ about the view axis with its apex at the seed, whose inner normal
// at radius ρ is (−cos θ ρ̂, sin θ); every cut pixel of a watertight shell around the seed
// against it.
TEST(AdaptiveCutaway, CutSurfaceNormalsAreTheConesNormal) {
  for (const float theta : {30.0f, 45.0f}) {
    const Scene scene = pointSeedInAShell(R"("angle": )" + std::to_string(theta), "");
    const auto aovs = renderAovs(scene);
    const FloatImage &mask = aov(aovs, "cutMask"), &normal = aov(aovs, "normal"),
                     &position = aov(aovs, "position");
    const float t = glm::radians(theta);
    int compared = 0;
    double worst = 0.0;
    for (int y = 0; y < mask.height; ++y)
      for (int x = 0; x < mask.width; ++x) {
        if (mask.at(x, y)[0] < 0.5f) continue;
        const glm::vec3 p = glm::make_vec3(position.at(x, y));
        const float rho = glm::length(glm::vec2(p));
        // Away from the apex (the seed's own footprint) and from the shell's walls.
        if (rho < 0.25f || std::max(std::abs(p.x), std::abs(p.y)) > 1.9f) continue;
        worst = std::max(worst, degreesFromConeNormal(glm::make_vec3(normal.at(x, y)), p, t));
        ++compared;
        // The cut point lies on the cone too, at height ρ / tan θ over the apex, brought out by
        // the seed's footprint (a 0.01 half-side) and the dilation (one of 512 texels over 4.4
        // units): at most 0.03 in ρ.
        EXPECT_LE(p.z, -0.5f + rho / std::tan(t) + 1e-3f) << x << "," << y;
        EXPECT_GE(p.z, -0.5f + (rho - 0.03f) / std::tan(t) - 1e-3f) << x << "," << y;
      }
    EXPECT_GT(compared, 2000) << "θ " << theta;
    // The normal comes from the cutaway-depth buffer's neighbouring texels.
    EXPECT_LE(worst, 2.0) << "θ " << theta;
    std::printf("θ %g: worst cut normal %.3f°\n", theta, worst);
  }
}

// Burns08 §5.3 local angles: two point seeds in one shell, at x = −1 with the object's own
// cutawayAngle of 25° and at x = +1 with the cutter's 45°. The cutaway surface is the lower of
// the two cones z = z₀ + ρᵢ/tan θᵢ; each cut pixel's normal is that cone's (its wall meets the
// view axis at its own θ) within 2°, away from the ridge where the two meet.
TEST(AdaptiveCutaway, ALocalAngleSetsItsOwnConesWallOnly) {
  const Scene scene = parseScene(
      R"({"resolution": [160, 160], "samples": 1, "style": {"name": "gooch", "lines": false},
        "camera": {"projection": "orthographic", "height": 4.4, "eye": [0, 0, 10],
                   "target": [0, 0, 0]},
        "cutters": {"adaptive": {"angle": 45, "bufferSize": 512, "edgeCompression": false,
                                 "ghostLines": false}},
        "objects": [{"name": "shell", "file": "meshes/cube.obj",
                     "transform": {"translate": [-2, -2, -2], "scale": 4}}],
        "proxies": [
          {"name": "narrow", "box": {"min": [-1.01, -0.01, -0.52], "max": [-0.99, 0.01, -0.5]},
           "params": {"cutawayAngle": 25}},
          {"name": "wide", "box": {"min": [0.99, -0.01, -0.52], "max": [1.01, 0.01, -0.5]}}]})",
      "local.json", kData);
  const auto aovs = renderAovs(scene);
  const FloatImage &mask = aov(aovs, "cutMask"), &normal = aov(aovs, "normal"),
                   &position = aov(aovs, "position");
  const glm::vec2 apex[2] = {{-1.0f, 0.0f}, {1.0f, 0.0f}};
  const float theta[2] = {glm::radians(25.0f), glm::radians(45.0f)};
  int compared[2] = {0, 0};
  double worst[2] = {0.0, 0.0};
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x) {
      if (mask.at(x, y)[0] < 0.5f) continue;
      const glm::vec3 p = glm::make_vec3(position.at(x, y));
      if (std::max(std::abs(p.x), std::abs(p.y)) > 1.9f) continue;
      float height[2], rho[2];
      for (int i = 0; i < 2; ++i) {
        rho[i] = glm::length(glm::vec2(p) - apex[i]);
        height[i] = -0.5f + rho[i] / std::tan(theta[i]);
      }
      const int i = height[0] < height[1] ? 0 : 1;
      if (rho[i] < 0.25f || std::abs(height[0] - height[1]) < 0.1f) continue;
      const glm::vec3 local = p - glm::vec3(apex[i], 0.0f);
      worst[i] = std::max(worst[i],
                          degreesFromConeNormal(glm::make_vec3(normal.at(x, y)), local, theta[i]));
      ++compared[i];
    }
  std::printf("25° cone: %d pixels, worst %.3f°; 45° cone: %d pixels, worst %.3f°\n", compared[0],
              worst[0], compared[1], worst[1]);
  for (int i = 0; i < 2; ++i) {
    EXPECT_GT(compared[i], 1000) << i;
    EXPECT_LE(worst[i], 2.0) << i;
  }
}

// The same for a box seed of footprint 1.2 × 0.6: its cutaway surface z₀ + d(p)/tan θ, d the
// distance to the footprint, is a wedge of inner normal (−cos θ n̂, sin θ) along each side (n̂
// the side's outward normal) and a cone about each corner, joined smoothly.
TEST(AdaptiveCutaway, CutSurfaceNormalsOfABoxSeedAreItsWedgesAndCornerCones) {
  const glm::vec2 half(0.6f, 0.3f);
  for (const float theta : {30.0f, 45.0f}) {
    const Scene scene = pointSeedInAShell(R"("angle": )" + std::to_string(theta), "", half);
    const auto aovs = renderAovs(scene);
    const FloatImage &mask = aov(aovs, "cutMask"), &normal = aov(aovs, "normal"),
                     &position = aov(aovs, "position");
    const float t = glm::radians(theta);
    int compared = 0, corners = 0;
    double worst = 0.0;
    for (int y = 0; y < mask.height; ++y)
      for (int x = 0; x < mask.width; ++x) {
        if (mask.at(x, y)[0] < 0.5f) continue;
        const glm::vec3 p = glm::make_vec3(position.at(x, y));
        const glm::vec2 out = glm::vec2(p) - glm::clamp(glm::vec2(p), -half, half);
        const float d = glm::length(out);
        if (d < 0.25f || std::max(std::abs(p.x), std::abs(p.y)) > 1.9f) continue;
        const double error = degreesFromConeNormal(glm::make_vec3(normal.at(x, y)), p, t, half);
        if (error > worst) worst = error;
        ++compared;
        corners += std::abs(p.x) > half.x && std::abs(p.y) > half.y;
        EXPECT_LE(p.z, -0.5f + d / std::tan(t) + 1e-3f) << x << "," << y;
        EXPECT_GE(p.z, -0.5f + (d - 0.03f) / std::tan(t) - 1e-3f) << x << "," << y;
      }
    EXPECT_GT(compared, 2000) << "θ " << theta;
    EXPECT_GT(corners, 500) << "θ " << theta;
    EXPECT_LE(worst, 2.0) << "θ " << theta;
    std::printf("box seed, θ %g: %d cut pixels (%d by the corners), worst cut normal %.3f°\n",
                theta, compared, corners, worst);
  }
}

// Burns11 eq. 5.8: a seed's angle shrinks to zero in a border region of width r, by the
// product of its distances from the x and y borders. Each seeded texel's slope (anchorCone's
// mE; Burns08 §3's screen-space slope P₁₁/tan θ_e, no compensation) against the closed form at
// the texel's centre: seeds fill the view's top-right corner (both factors) and its centre.
TEST(AdaptiveCutaway, EdgeCompressionShrinksTheAngleAsEquationFivePointEight) {
  const float theta = 40.0f, r = 0.2f;
  const Scene scene = parseScene(
      R"({"resolution": [128, 128], "samples": 1, "style": {"name": "gooch", "lines": false},
      "camera": {"eye": [0, 0, 10], "target": [0, 0, 0], "fov": 40},
      "cutters": {"adaptive": {"angle": 40, "bufferSize": 128, "edgeCompression": 0.2, "compute": "gpu",
                               "perspectiveCompensation": false, "ghostLines": false}},
      "objects": [{"name": "wall", "file": "render/plane.obj", "transform": {"translate": [0, 0, -2]}}],
      "proxies": [{"name": "corner", "box": {"min": [2, 2, -0.5], "max": [6, 6, 0]}},
                  {"name": "centre", "box": {"min": [-1, -0.3, -0.5], "max": [1, 0.3, 0]}}]})",
      "edge.json", kData);
  const auto aovs = renderAovs(scene);
  const FloatImage& cone = aov(aovs, "anchorCone");  // z (−1: not seeded), mE, mF
  ASSERT_EQ(cone.width, 128);
  const float p11 = 1.0f / std::tan(glm::radians(20.0f));
  const auto factor = [&](float ndc) { return std::clamp((1.0f - std::abs(ndc)) / r, 0.0f, 1.0f); };
  int full = 0, compressed = 0, both = 0, wrong = 0;
  for (int y = 0; y < cone.height; ++y)
    for (int x = 0; x < cone.width; ++x) {
      const float* c = cone.at(x, y);
      if (c[0] <= -1.0f) continue;
      // |NDC| is the same whichever way the rows run.
      const float nx = (float(x) + 0.5f) / 64.0f - 1.0f, ny = (float(y) + 0.5f) / 64.0f - 1.0f;
      const float thetaE = glm::radians(theta) * factor(nx) * factor(ny);
      const float expected =
          p11 / std::tan(std::clamp(thetaE, 1e-4f, glm::half_pi<float>() - 1e-4f));
      full += factor(nx) == 1.0f && factor(ny) == 1.0f;
      compressed += factor(nx) < 1.0f || factor(ny) < 1.0f;
      both += factor(nx) < 1.0f && factor(ny) < 1.0f && factor(nx) > 0.0f && factor(ny) > 0.0f;
      if (std::abs(c[1] - expected) > 1e-4f * expected && ++wrong <= 5)
        ADD_FAILURE() << "texel " << x << "," << y << " (NDC " << nx << ", " << ny << "): mE "
                      << c[1] << ", eq. 5.8 gives " << expected;
    }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(full, 100);
  EXPECT_GT(compressed, 100);
  EXPECT_GT(both, 50);
  // The CPU path's cones (anchorCone) on a grid over the view, against the same closed form.
  const AdaptiveCutawayOptions& options = *scene.cutters.find<AdaptiveCutawayOptions>();
  const CutawayProjection projection = cutawayProjection(scene.resolvedCamera(), 1.0f);
  for (float nx = -1.0f; nx <= 1.0f; nx += 0.05f)
    for (float ny = -1.0f; ny <= 1.0f; ny += 0.05f) {
      const float thetaE = glm::radians(theta) * factor(nx) * factor(ny);
      const float expected =
          p11 / std::tan(std::clamp(thetaE, 1e-4f, glm::half_pi<float>() - 1e-4f));
      EXPECT_NEAR(anchorCone({nx, ny, 0.5f}, glm::radians(theta), options, projection).slopeE,
                  expected, 1e-5f * expected)
          << "NDC " << nx << ", " << ny;
    }
}

// Burns11 eqs. 6.1–6.2 worked by hand: a seed at the origin seen from an eye at elevation β
// over a floor with normal +y. v̂ (to the eye) makes n̂·v̂ = sin β, so φ = asin(n̂·v̂) = β (eq.
// 6.1), and θ_F = clamp(θ_e, 0, φ − 2°) + θ_e·smoothstep(0, 10°, −φ) (eq. 6.2 with the
// documented 2° margin): θ = 40° gives 18° at β = 20°, 40° (unclamped) at β = 60°, 0 at β = 0
// and 20° (half opened) at β = −5°. Each on the CPU path (anchorCone at the seed's NDC) and on
// the GPU path (the seed's texels in the anchorCone AOV), as Burns08 §3's slope P₁₁/tan θ_F.
TEST(AdaptiveCutaway, DirectionalConstraintClampsTheAngleAsEquationsSixPointOneAndTwo) {
  const float p11 = 1.0f / std::tan(glm::radians(20.0f));
  for (const auto& [beta, expected] : std::vector<std::pair<float, float>>{
           {20.0f, 18.0f}, {60.0f, 40.0f}, {0.0f, 0.0f}, {-5.0f, 20.0f}}) {
    const glm::vec3 eye = 10.0f * glm::vec3(0.0f, std::sin(glm::radians(beta)), std::cos(glm::radians(beta)));
    char json[1200];
    std::snprintf(json, sizeof json,
                  R"({"resolution": [128, 128], "samples": 1, "style": {"name": "gooch", "lines": false},
      "camera": {"eye": [%g, %g, %g], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 40},
      "cutters": {"adaptive": {"angle": 40, "bufferSize": 128, "compute": "gpu", "edgeCompression": false,
                               "perspectiveCompensation": false, "ghostLines": false,
                               "floorNormal": [0, 1, 0]}},
      "objects": [{"name": "wall", "file": "render/plane.obj", "transform": {"translate": [0, 0, -3]}}],
      "proxies": [{"name": "seed", "box": {"min": [-0.1, -0.1, -0.1], "max": [0.1, 0.1, 0.1]}}]})",
                  eye.x, eye.y, eye.z);
    const Scene scene = parseScene(json, "floor.json", kData);
    // θ_F from a slope, in degrees (θ_F = 0 is kept a sliver, 1e-4 rad, away from zero).
    const auto angle = [&](float slope) { return glm::degrees(std::atan(p11 / slope)); };
    const CutawayProjection projection = cutawayProjection(scene.resolvedCamera(), 1.0f);
    const AnchorCone cpu = anchorCone({0.0f, 0.0f, 0.5f}, glm::radians(40.0f),
                                      *scene.cutters.find<AdaptiveCutawayOptions>(), projection);
    EXPECT_NEAR(angle(cpu.slopeF), expected, 0.01) << "β " << beta;
    EXPECT_NEAR(angle(cpu.slopeE), 40.0, 0.01) << "β " << beta;
    // On the GPU the seed's texels lie near the centre: the same hand-worked steps at each
    // texel's own point (its NDC and z unprojected), where φ is within a degree of β.
    const auto aovs = renderAovs(scene);
    const FloatImage& cone = aov(aovs, "anchorCone");  // rows top to bottom
    const glm::mat4 inverse = glm::inverse(projection.projection);
    const glm::vec3 n = projection.viewRotation * glm::vec3(0.0f, 1.0f, 0.0f);
    int seeded = 0;
    for (int y = 0; y < cone.height; ++y)
      for (int x = 0; x < cone.width; ++x) {
        const float* c = cone.at(x, y);
        if (c[0] <= -1.0f) continue;
        ++seeded;
        const glm::vec4 h = inverse * glm::vec4((float(x) + 0.5f) / 64.0f - 1.0f,
                                                1.0f - (float(y) + 0.5f) / 64.0f, c[0], 1.0f);
        const float phi = glm::degrees(std::asin(glm::dot(n, glm::normalize(-glm::vec3(h) / h.w))));
        const float s = std::clamp(-phi / 10.0f, 0.0f, 1.0f);
        const float thetaF = std::clamp(40.0f, 0.0f, std::max(phi - 2.0f, 0.0f)) + 40.0f * s * s * (3 - 2 * s);
        EXPECT_NEAR(phi, beta, 1.0f) << "texel " << x << "," << y;
        EXPECT_NEAR(angle(c[2]), thetaF, 0.02) << "β " << beta << ", texel " << x << "," << y;
      }
    EXPECT_GT(seeded, 0) << "β " << beta;
  }
}

// Burns11 eq. 6.2 down the screen: the wall of a seed resting on the floor stays above it. In
// perspective, eq. 5.7's slope for the floor's angle φ is the floor's own only on the view
// axis, so m_F is bounded by the floor plane's slope along n̂_proj. Against an independent
// result: the floor's NDC depth at a seed on it and a small step down the screen (along
// −n̂_proj), each where the pixel's view ray meets the floor plane, in double precision; m_F
// is at least their difference quotient times tan φ / tan(φ − 2°) (the documented margin),
// for seeds over the screen and three cameras, the fan room's among them
// (examples/fan-room-cutaway.json, whose wall was 2 % shallower than the floor and cut a notch
// into it): eq. 5.7 alone fell short at some seeds of each.
TEST(AdaptiveCutaway, TheFloorSideOfTheConeStaysAboveTheFloor) {
  struct View {
    glm::vec3 eye, target;
    float fov, near, far;
  };
  AdaptiveCutawayOptions options;
  options.directionalConstraint = true;
  options.edgeCompression = false;
  options.floorNormal = glm::vec3(0.0f, 0.0f, 1.0f);
  const float theta = glm::radians(40.0f), margin = glm::radians(2.0f);
  for (const View& v :
       {View{{2.7748f, -5.1238f, 6.369f}, {-2.7124f, 2.0096f, 1.4305f}, 45.0f, 6.0f, 14.5f},
        View{{0.0f, -6.0f, 5.0f}, {0.0f, 0.0f, 0.0f}, 60.0f, 1.0f, 30.0f},
        View{{4.0f, -3.0f, 2.5f}, {0.0f, 0.0f, 0.5f}, 70.0f, 0.5f, 20.0f}}) {
    SCOPED_TRACE(testing::Message() << "fov " << v.fov);
    Camera camera;
    camera.eye = v.eye, camera.target = v.target, camera.up = glm::vec3(0.0f, 0.0f, 1.0f);
    camera.fovY = v.fov, camera.near = v.near, camera.far = v.far;
    const CutawayProjection projection = cutawayProjection(camera, 4.0f / 3.0f);
    const glm::dmat4 P(projection.projection);
    const glm::dmat4 inverse = glm::inverse(
        P * glm::lookAt(glm::dvec3(v.eye), glm::dvec3(v.target), glm::dvec3(0.0, 0.0, 1.0)));
    // The NDC depth where the view ray through NDC (x, y) meets the floor z = 0; NaN if not
    // in front of the eye within the depth range.
    const auto floorDepth = [&](glm::dvec2 ndc) {
      const glm::dvec4 a = inverse * glm::dvec4(ndc, -1.0, 1.0),
                       b = inverse * glm::dvec4(ndc, 1.0, 1.0);
      const glm::dvec3 from = glm::dvec3(a) / a.w, to = glm::dvec3(b) / b.w;
      const double t = -from.z / (to.z - from.z);
      if (!(t > 0.0 && t < 1.0)) return std::nan("");
      const glm::dvec3 point = from + t * (to - from);
      const glm::dvec4 c =
          P * glm::lookAt(glm::dvec3(v.eye), glm::dvec3(v.target), glm::dvec3(0, 0, 1)) *
          glm::dvec4(point, 1.0);
      return c.z / c.w;
    };
    int seeds = 0, shortOfTheFloor = 0;
    for (double x = -0.9; x <= 0.91; x += 0.1)
      for (double y = -0.9; y <= 0.91; y += 0.1) {
        const double z = floorDepth({x, y});
        if (std::isnan(z)) continue;
        const AnchorCone cone = anchorCone(glm::vec3(x, y, z), theta, options, projection);
        // One step of 1e-3 view-plane units down the screen, in NDC.
        const glm::dvec2 step = -1e-3 * glm::dvec2(cone.floor) * glm::dvec2(P[0][0], P[1][1]);
        const double next = floorDepth(glm::dvec2(x, y) + step);
        if (std::isnan(next)) continue;
        const double floorSlope = (z - next) / 1e-3;
        // φ at the seed (eq. 6.1), from the floor point's direction to the eye.
        const glm::dvec4 h = glm::inverse(P) * glm::dvec4(x, y, z, 1.0);
        const glm::dvec3 toEye = -glm::normalize(glm::dvec3(h) / h.w);
        const glm::dvec3 n = glm::dmat3(projection.viewRotation) * glm::dvec3(0.0, 0.0, 1.0);
        const double phi = std::asin(glm::dot(n, toEye));
        if (phi <= margin + 1e-3) continue;
        ++seeds;
        const double needed = floorSlope * std::tan(phi) / std::tan(phi - margin);
        EXPECT_GE(cone.slopeF, needed * (1.0 - 1e-3)) << "seed at NDC " << x << "," << y;
        // Eq. 5.7 at φ − 2°, what m_F was without the bound.
        shortOfTheFloor += -(P[2][2] + z) / std::tan(phi - margin) < floorSlope;
      }
    EXPECT_GT(seeds, 100);
    EXPECT_GT(shortOfTheFloor, 0);
  }
}

// A floor normal given by its path (--set, the viewer, the bindings) turns the directional
// constraint on, as the scene file's key does; the constraint set off after it stays off.
TEST(AdaptiveCutaway, AFloorNormalSetByItsPathTurnsTheConstraintOn) {
  Scene scene;
  setOption(scene, "cutters.adaptive.floorNormal", "2,0,0");
  const AdaptiveCutawayOptions* o = scene.cutters.find<AdaptiveCutawayOptions>();
  ASSERT_NE(o, nullptr);
  EXPECT_TRUE(o->directionalConstraint);
  EXPECT_EQ(o->floorNormal, glm::vec3(1, 0, 0));
  setOption(scene, "cutters.adaptive.directionalConstraint", "false");
  EXPECT_FALSE(scene.cutters.find<AdaptiveCutawayOptions>()->directionalConstraint);
}

// Burns11 eq. 6.3's n̂_proj, the screen direction in which the floor's normal points at a seed:
// against the projections of the seed's point p and of p + ε·n̂ (view-plane units: NDC over
// P₀₀ and P₁₁), over a grid of seeds, for a camera looking down at the floor in perspective
// and in orthographic projection, and by hand for a level camera, where every vertical
// projects vertical: (0, 1) at every seed.
TEST(AdaptiveCutaway, FloorDirectionIsTheProjectedFloorNormal) {
  AdaptiveCutawayOptions options;
  options.directionalConstraint = true;
  options.floorNormal = glm::vec3(0.0f, 1.0f, 0.0f);
  for (const auto& [eye, orthographic] : std::vector<std::pair<glm::vec3, bool>>{
           {{3.0f, 5.0f, 8.0f}, false}, {{3.0f, 5.0f, 8.0f}, true}, {{0.0f, 0.0f, 9.0f}, false}}) {
    Camera camera;
    camera.eye = eye, camera.near = 0.5f, camera.far = 50.0f;
    if (orthographic) camera.setProjection(Projection::Orthographic);
    const CutawayProjection projection = cutawayProjection(camera, 4.0f / 3.0f);
    const glm::mat4& P = projection.projection;
    const glm::vec3 n = projection.viewRotation * options.floorNormal;
    for (float x = -0.9f; x <= 0.91f; x += 0.3f)
      for (float y = -0.9f; y <= 0.91f; y += 0.3f) {
        const glm::vec3 ndc(x, y, 0.3f);
        const glm::vec4 h = glm::inverse(P) * glm::vec4(ndc, 1.0f);
        const glm::vec3 p = glm::vec3(h) / h.w;
        const auto project = [&](const glm::vec3& q) {
          const glm::vec4 c = P * glm::vec4(q, 1.0f);
          return glm::dvec2(c.x / c.w, c.y / c.w);
        };
        const double eps = 1e-3 * glm::length(p);
        glm::dvec2 d = (project(p + float(eps) * n) - project(p)) / glm::dvec2(P[0][0], P[1][1]);
        d = glm::normalize(d);
        const glm::vec2 floor = anchorCone(ndc, glm::radians(40.0f), options, projection).floor;
        SCOPED_TRACE(testing::Message() << "eye " << eye.z << (orthographic ? " ortho" : "")
                                        << ", seed at " << x << "," << y);
        EXPECT_NEAR(floor.x, d.x, 2e-3);
        EXPECT_NEAR(floor.y, d.y, 2e-3);
        if (eye.y == 0.0f) {  // level: by hand
          EXPECT_NEAR(floor.x, 0.0f, 1e-5);
          EXPECT_NEAR(floor.y, 1.0f, 1e-5);
        }
      }
  }
}

// Burns08 §4.2: the dilated cutaway (used for back faces) is the minimum of the cutaway depth
// over each texel's 3×3 neighbourhood, edges clamped: against a CPU minimum filter of the
// dumped buffer, texel by texel.
TEST(AdaptiveCutaway, DilatedDepthIsTheThreeByThreeMinimumOfTheCutawayDepth) {
  const Scene scene = shellAroundACore();
  const auto aovs = renderAovs(scene);
  const FloatImage& c = aov(aovs, "cutawayDepth");
  const FloatImage& d = aov(aovs, "cutawayDilated");
  ASSERT_EQ(c.width, 128);
  ASSERT_EQ(d.width, c.width);
  ASSERT_EQ(d.height, c.height);
  int narrower = 0, wrong = 0;
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      float m = 1.0f;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          m = std::min(m, c.at(std::clamp(x + dx, 0, c.width - 1),
                               std::clamp(y + dy, 0, c.height - 1))[0]);
      narrower += m < c.at(x, y)[0];
      if (d.at(x, y)[0] != m && ++wrong <= 5)
        ADD_FAILURE() << "texel " << x << "," << y << ": dilated " << d.at(x, y)[0]
                      << ", 3x3 minimum " << m;
    }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(narrower, 100);  // the cone's slopes: the filter changed something
}

// Burns08 §4.3: ghost lines show the silhouettes of removed material near the cut, fading
// with distance in front of the cutaway surface; nothing is drawn for kept material.
TEST(AdaptiveCutaway, GhostLinesShowRemovedMaterialOnly) {
  auto ghostCoverage = [](float distance, bool plateLines = true) {
    char json[1200];
    std::snprintf(
        json, sizeof json,
        R"({"resolution": [80, 60], "samples": 1, "style": {"name": "gooch", "lines": false},
        "camera": {"eye": [0, 0, 10], "target": [0, 0, 0], "fov": 40},
        "cutters": {"adaptive": {"angle": 30, "bufferSize": 128, "ghostLines": {"distance": %g}}},
        "objects": [
          {"name": "plate", "file": "meshes/cube.obj", "transform": {"translate": [-0.3, -0.3, 3], "scale": 0.6},
           "params": {"lines": %s}},
          {"name": "cube", "file": "meshes/cube.obj", "role": "interest",
           "transform": {"translate": [-0.5, -0.5, -0.5]}}]})",
        distance, plateLines ? "true" : "false");
    const auto aovs = renderAovs(parseScene(json, "ghost.json", kData));
    double sum = 0;
    for (float g : aov(aovs, "ghostLines").data) sum += g;
    EXPECT_EQ(aov(aovs, "objectId").at(40, 30)[0], 1.0f);  // the small plate is removed
    return sum;
  };
  // The plate's front face lies ~2.5 units in front of the cutaway surface.
  EXPECT_EQ(ghostCoverage(0.5f), 0.0);  // beyond the ghost distance: no ghost
  const double near = ghostCoverage(5.0f), far = ghostCoverage(50.0f);
  EXPECT_GT(near, 1.0);
  EXPECT_GT(far, near);  // a longer distance fades less
  EXPECT_EQ(ghostCoverage(50.0f, false), 0.0);  // an object without lines has no ghost lines
}

// `cutSurfaces` (Burns08 §4.1): two shells around two objects of interest, a closed cube and
// the same cube with one face missing (its open side turned away). With "all" the cut walls
// of both show cut surfaces; with "watertight" only the closed one's, the open one's inside
// still seen through its cut but not as a cut surface; with "none", neither. Which shell is
// watertight is known by construction (meshes/cube.obj, meshes/open_cube.obj).
TEST(AdaptiveCutaway, CutSurfacesOnAllWatertightOrNoShells) {
  const auto cutPixels = [](const std::string& mode) {
    const Scene scene = parseScene(
        R"({"resolution": [120, 60], "samples": 1, "style": {"name": "gooch", "lines": false},
        "camera": {"eye": [0, 2, 14], "target": [0, 0, 0], "fov": 40},
        "cutters": {"adaptive": {"angle": 35, "bufferSize": 128, "cutSurfaces": ")" +
            mode + R"("}},
        "objects": [
          {"name": "closed", "file": "meshes/cube.obj", "transform": {"translate": [-4.5, -1.5, -1.5], "scale": 3}},
          {"name": "open", "file": "meshes/open_cube.obj",
           "transform": {"translate": [4.5, -1.5, 1.5], "rotate": [0, 180, 0], "scale": 3}},
          {"name": "left core", "file": "meshes/cube.obj", "role": "interest",
           "transform": {"translate": [-3.3, -0.3, -0.3], "scale": 0.6}},
          {"name": "right core", "file": "meshes/cube.obj", "role": "interest",
           "transform": {"translate": [2.7, -0.3, -0.3], "scale": 0.6}}]})",
        "shells.json", kData);
    EXPECT_TRUE(scene.objects[0].mesh->report.watertight);
    EXPECT_FALSE(scene.objects[1].mesh->report.watertight);
    const auto aovs = renderAovs(scene);
    const FloatImage &mask = aov(aovs, "cutMask"), &id = aov(aovs, "objectId");
    std::array<int, 2> counts{0, 0};  // per shell
    int inside = 0;  // the open shell's pixels where the plain frame shows its front
    for (std::size_t i = 0; i < mask.data.size(); ++i) {
      if (mask.data[i] > 0.5f && id.data[i] >= 0.0f && id.data[i] < 2.0f)
        ++counts[std::size_t(id.data[i])];
      inside += id.data[i] == 1.0f;
    }
    EXPECT_GT(inside, 100) << mode;  // the open shell stays in view either way
    return counts;
  };
  const auto all = cutPixels("all"), watertight = cutPixels("watertight"), none = cutPixels("none");
  EXPECT_GT(all[0], 30);
  EXPECT_GT(all[1], 30);
  EXPECT_EQ(watertight[0], all[0]);
  EXPECT_EQ(watertight[1], 0);
  EXPECT_EQ(none[0], 0);
  EXPECT_EQ(none[1], 0);
}

namespace {

// An open shell (meshes/open_cube.obj, its open side turned away) around an object of
// interest, `dummies` tiny open cubes inside the cut in front of it, then an open cup (the same
// mesh, its open side towards the eye) at `cup` (lower corner, 2 units wide), with or without
// the adaptive cutter computing C on `compute` ("gpu": every object drawn with the cutter's
// code; "cpu": those C leaves alone without it) and its `cutSurfaces`; 4 samples a pixel.
Scene openShellAndCup(const std::string& cup, int dummies, const std::string& compute,
                      bool cupDoubleSided, const std::string& cutSurfaces = "all") {
  std::string objects =
      R"({"name": "shell", "file": "meshes/open_cube.obj",
          "transform": {"translate": [1.5, -1.5, 1.5], "rotate": [0, 180, 0], "scale": 3}})";
  for (int i = 0; i < dummies; ++i)
    objects += R"(, {"name": "dummy )" + std::to_string(i) + R"(", "file": "meshes/open_cube.obj",
                     "transform": {"translate": [-0.05, -0.05, 1.0], "scale": 0.1}})";
  objects += R"(, {"name": "cup", "file": "meshes/open_cube.obj", "params": {"doubleSided": )" +
             std::string(cupDoubleSided ? "true" : "false") + R"(},
                  "transform": {"translate": )" +
             cup + R"(, "scale": 2}},
      {"name": "core", "file": "meshes/cube.obj", "role": "interest",
       "transform": {"translate": [-0.3, -0.3, -0.3], "scale": 0.6}})";
  return parseScene(
      R"({"resolution": [160, 90], "samples": 4, "style": {"name": "gooch", "lines": false},
      "camera": {"eye": [0, 3, 12], "target": [0, 0, -1], "fov": 40},)" +
          (compute.empty() ? ""
                           : R"("cutters": {"adaptive": {"angle": 35, "bufferSize": 128,
                                "compute": ")" +
                                 compute + R"(", "cutSurfaces": ")" + cutSurfaces + R"("}},)") +
          R"("objects": [)" + objects + "]}",
      "open.json", kData);
}

// Cut-surface pixels of object `id`.
int cutPixelsOf(const std::vector<Aov>& aovs, float id) {
  const FloatImage &mask = aov(aovs, "cutMask"), &ids = aov(aovs, "objectId");
  int n = 0;
  for (std::size_t i = 0; i < mask.data.size(); ++i) n += mask.data[i] > 0.5f && ids.data[i] == id;
  return n;
}

}  // namespace

// Burns08 §4.1 on open meshes: a back face seen through the cut is the cut surface, one seen
// through the mesh's own opening is its inside. C lies in front of every pixel here, so a cup
// beside the cut, which loses nothing, must look exactly as without the cutter: no cut
// surface, the same pixels and normals (its inside in view through its opening; culled when
// it is single-sided), whether drawn with the cutter's code or not. The open shell the cut
// opens still shows its cut surfaces.
TEST(AdaptiveCutaway, AnOpenMeshShowsCutSurfacesOnlyWhereItsOwnFrontWasRemoved) {
  for (const auto& [compute, doubleSided] : {std::pair{"gpu", true}, std::pair{"gpu", false},
                                             std::pair{"cpu", true}, std::pair{"cpu", false}}) {
    SCOPED_TRACE(std::string(compute) + (doubleSided ? ", double-sided" : ", single-sided"));
    const std::string cup = "[4, -1, -1]";
    const auto cut = renderAovs(openShellAndCup(cup, 0, compute, doubleSided)),
               plain = renderAovs(openShellAndCup(cup, 0, "", doubleSided));
    EXPECT_GT(cutPixelsOf(cut, 0.0f), 30);  // the shell
    EXPECT_EQ(cutPixelsOf(cut, 1.0f), 0);   // the cup
    const FloatImage &ids = aov(cut, "objectId"), &plainIds = aov(plain, "objectId");
    const FloatImage &normals = aov(cut, "normal"), &plainNormals = aov(plain, "normal");
    int cupPixels = 0;
    for (std::size_t i = 0; i < ids.data.size(); ++i) {
      if (ids.data[i] != 1.0f && plainIds.data[i] != 1.0f) continue;
      ++cupPixels;
      ASSERT_EQ(ids.data[i], plainIds.data[i]) << "pixel " << i;
      for (std::size_t k = 0; k < 3; ++k)
        ASSERT_NEAR(normals.data[3 * i + k], plainNormals.data[3 * i + k], 1e-5f) << i;
    }
    EXPECT_GT(cupPixels, 150);
  }
  // The inside is in view: single-sided, fewer of the cup's pixels are left.
  const auto count = [](const std::vector<Aov>& aovs) {
    const FloatImage& ids = aov(aovs, "objectId");
    return std::count(ids.data.begin(), ids.data.end(), 1.0f);
  };
  EXPECT_GT(count(renderAovs(openShellAndCup("[4, -1, -1]", 0, "gpu", true))),
            count(renderAovs(openShellAndCup("[4, -1, -1]", 0, "gpu", false))) + 50);
}

// `cutSurfaces: "unmarked"` leaves the marks out: the cup's inside, seen through its own
// opening behind C, is painted as a cut, and the shell's cut surfaces are those of "all".
TEST(AdaptiveCutaway, UnmarkedCutSurfacesPaintAnOpenMeshsInsideAsACut) {
  for (const char* compute : {"gpu", "cpu"}) {
    SCOPED_TRACE(compute);
    const std::string cup = "[4, -1, -1]";
    const auto marked = renderAovs(openShellAndCup(cup, 0, compute, true, "all")),
               unmarked = renderAovs(openShellAndCup(cup, 0, compute, true, "unmarked"));
    EXPECT_GT(cutPixelsOf(marked, 0.0f), 30);
    EXPECT_EQ(cutPixelsOf(unmarked, 0.0f), cutPixelsOf(marked, 0.0f));
    EXPECT_EQ(cutPixelsOf(marked, 1.0f), 0);
    EXPECT_GT(cutPixelsOf(unmarked, 1.0f), 30);
  }
}

// The marks take one stencil value per object, 255 to a clear: a cup seen through the shell's
// cut and its missing back, which loses nothing, is marked 255 objects after the shell (254
// tiny cubes the cut removes between them), with the shell's value. It shows no cut surface,
// as with none between (it would where the shell's stale marks lie). C on the GPU: every
// object is drawn with the cutter's code (on the CPU path the cup, wholly behind C, is not).
TEST(AdaptiveCutaway, RemovalMarksStartAfreshEvery255Objects) {
  const std::string behind = "[-1, -2.5, -7]";
  for (const int dummies : {0, 254}) {
    const auto aovs = renderAovs(openShellAndCup(behind, dummies, "gpu", true));
    const float cupId = float(dummies + 1);
    const FloatImage& ids = aov(aovs, "objectId");
    EXPECT_GT(std::count(ids.data.begin(), ids.data.end(), cupId), 120) << dummies;
    EXPECT_GT(cutPixelsOf(aovs, 0.0f), 30) << dummies;
    EXPECT_EQ(cutPixelsOf(aovs, cupId), 0) << dummies;
  }
}

// Burns11 §5.2.4.1 under the contextual structure (§4.1.3, eqs. 5.5–5.6, 7.1–7.3): a shell of
// importance I around a point seed seen orthographically is trimmed where R(I, Ω) = ½, i.e. at
// Ω* = (max(2I − 1, 0) + I)/2. Without an overlay, Ω runs linearly from the wide cone C₂ (θ₂)
// to the narrow one C₁ (θ₁), so the trimming surface is itself a cone about the view axis:
// height ρ·((1 − Ω*)/tan θ₂ + Ω*/tan θ₁) over the apex. Each cut pixel's normal is that
// cone's inner normal and its point lies on it (I = 0.5: θ* = 49.1°; I = 0.8: 35.8°).
TEST(AdaptiveCutaway, ContextualCutSurfaceIsTheTrimmingConeOfTheShellsImportance) {
  const float theta1 = glm::radians(30.0f), theta2 = glm::radians(60.0f);
  for (const float importance : {0.5f, 0.8f}) {
    const Scene scene = pointSeedInAShell(
        R"("angle": 30, "contextual": {"transitionAngle": 60, "overlay": 0, "reduction": "importance"})",
        R"("importance": )" + std::to_string(importance) + ", ");
    const auto aovs = renderAovs(scene);
    const FloatImage &mask = aov(aovs, "cutMask"), &normal = aov(aovs, "normal"),
                     &position = aov(aovs, "position");
    const float omega = (std::max(2.0f * importance - 1.0f, 0.0f) + importance) / 2.0f;
    const float slope = (1.0f - omega) / std::tan(theta2) + omega / std::tan(theta1);  // 1/tan θ*
    const float t = std::atan(1.0f / slope);
    // Where C₁ would lie in front of the near plane it is held there, and the cone bends.
    const Camera camera = scene.resolvedCamera();
    const float nearZ = camera.eye.z - camera.near;
    int compared = 0, off = 0;
    double worst = 0.0;
    for (int y = 0; y < mask.height; ++y)
      for (int x = 0; x < mask.width; ++x) {
        if (mask.at(x, y)[0] < 0.5f) continue;
        const glm::vec3 p = glm::make_vec3(position.at(x, y));
        const float rho = glm::length(glm::vec2(p));
        if (rho < 0.25f || std::max(std::abs(p.x), std::abs(p.y)) > 1.9f ||
            -0.5f + (rho + 0.05f) / std::tan(theta1) > nearZ)
          continue;
        worst = std::max(worst, degreesFromConeNormal(glm::make_vec3(normal.at(x, y)), p, t));
        ++compared;
        // On the cone, within the seed's footprint and a texel or two of both surfaces.
        off += std::abs(p.z - (-0.5f + rho * slope)) > 0.04f;
      }
    EXPECT_GT(compared, 2000) << "I " << importance;
    EXPECT_EQ(off, 0) << "I " << importance;
    EXPECT_LE(worst, 2.0) << "I " << importance << ", θ* " << glm::degrees(t);
  }
}

// Cutter::reaches for the adaptive cutter: a box cutawayKeepsBox lets through holds no point
// that Burns11 eq. 5.4 removes (window depth z < C at its pixel, C read bilinearly with repeat
// as the texture is). Random C images (zero, the "no cut" value, over a quarter), random boxes seen
// by a perspective camera, 400 points a box; the test is no trivial "no": a good share of boxes is
// let through.
TEST(AdaptiveCutawayFunction, ABoxItKeepsHoldsNoPointItRemoves) {
  constexpr int n = 48;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const glm::mat4 viewProjection =
      glm::perspective(glm::radians(50.0f), 1.3f, 0.5f, 50.0f) *
      glm::lookAt(glm::vec3(0.3f, 0.4f, 8.0f), glm::vec3(0.0f), glm::vec3(0, 1, 0));
  int kept = 0, boxes = 0;
  for (int image = 0; image < 20; ++image) {
    std::vector<float> c(std::size_t(n) * std::size_t(n));
    const glm::vec2 centre(unit(rng), unit(rng));
    const float top = 0.9f + 0.09f * unit(rng), fall = 2.0f + 6.0f * unit(rng);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const float d = glm::length(glm::vec2((x + 0.5f) / n, (y + 0.5f) / n) - centre);
        c[std::size_t(y) * n + x] = std::max(0.0f, top - fall * d * d + 0.01f * unit(rng));
      }
    const GreatestDepth greatest(c, n);
    const auto sample = [&](glm::vec2 uv) {  // bilinear, repeat
      const float tx = uv.x * n - 0.5f, ty = uv.y * n - 0.5f;
      const int x0 = int(std::floor(tx)), y0 = int(std::floor(ty));
      const auto at = [&](int x, int y) {
        return c[std::size_t(((y % n) + n) % n) * n + std::size_t(((x % n) + n) % n)];
      };
      const float wx = tx - float(x0), wy = ty - float(y0);
      return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), wx),
                      glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), wx), wy);
    };
    for (int b = 0; b < 100; ++b, ++boxes) {
      const glm::vec3 lo(-4.0f + 8.0f * unit(rng), -3.0f + 6.0f * unit(rng),
                         -8.0f + 12.0f * unit(rng));
      const Bounds box{lo, lo + glm::vec3(0.1f + unit(rng), 0.1f + unit(rng), 0.1f + unit(rng))};
      if (!cutawayKeepsBox(box, viewProjection, greatest)) continue;
      ++kept;
      for (int k = 0; k < 400; ++k) {
        const glm::vec3 p = glm::mix(box.min, box.max, glm::vec3(unit(rng), unit(rng), unit(rng)));
        const glm::vec4 clip = viewProjection * glm::vec4(p, 1.0f);
        const glm::vec3 ndc = glm::vec3(clip) / clip.w;
        const float z = 0.5f * ndc.z + 0.5f, at = sample(0.5f * glm::vec2(ndc) + 0.5f);
        ASSERT_GE(z, at) << "image " << image << " box " << b;
      }
    }
  }
  EXPECT_GT(kept, boxes / 5) << kept << " of " << boxes;
}
