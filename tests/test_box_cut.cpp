// The box cut: its C++ decision against closed forms, and the GPU's against the C++ one pixel
// by pixel on a solid block cut by a rotated box, in perspective and orthographic views; and
// its options through the schema.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cutaway/core/error.hpp"
#include "cutaway/cutters/box_cut.hpp"
#include "cutaway/render/renderer.hpp"
#include "cutaway/render/techniques.hpp"
#include "gl_test_context.hpp"
#include "render_aovs.hpp"

using namespace cutaway;
using test::aov;
using test::renderAovs;
using Fate = BoxCutFate::Fate;

namespace {

const std::string kData = CUTAWAY_TEST_DATA;

BoxCutOptions unitBox() {
  BoxCutOptions o;
  o.size = glm::vec3(2.0f);  // [-1, 1]³
  return o;
}

void expectNear(const glm::vec3& a, const glm::vec3& b) {
  EXPECT_NEAR(a.x, b.x, 1e-5f);
  EXPECT_NEAR(a.y, b.y, 1e-5f);
  EXPECT_NEAR(a.z, b.z, 1e-5f);
}

}  // namespace

TEST(BoxCutFunction, RemovingTheInsideShowsTheWallWhereTheRayLeavesTheBox) {
  const BoxCutOptions o = unitBox();
  const glm::vec3 eye(0.0f, 0.0f, 10.0f);
  EXPECT_EQ(boxCutFragment(o, {0.2f, -0.5f, 0.9f}, true, eye).fate, Fate::Discard);
  EXPECT_EQ(boxCutFragment(o, {0.2f, -0.5f, 0.9f}, false, eye).fate, Fate::Discard);
  EXPECT_EQ(boxCutFragment(o, {0.0f, 0.0f, 3.0f}, true, eye).fate, Fate::Keep);
  // A back face behind the box: the view ray crossed it, the wall is its far face z = −1.
  const BoxCutFate behind = boxCutFragment(o, {0.0f, 0.0f, -3.0f}, false, eye);
  EXPECT_EQ(behind.fate, Fate::CutSurface);
  expectNear(behind.position, {0.0f, 0.0f, -1.0f});
  expectNear(behind.normal, {0.0f, 0.0f, 1.0f});
  // Off to the side the ray misses the box: an ordinary back face.
  EXPECT_EQ(boxCutFragment(o, {3.0f, 0.0f, -3.0f}, false, eye).fate, Fate::Keep);
  // In front of the box the ray has not reached it yet.
  EXPECT_EQ(boxCutFragment(o, {0.0f, 0.0f, 2.0f}, false, eye).fate, Fate::Keep);
  // A ray parallel to two slabs, inside them and outside them.
  const BoxCutFate along = boxCutFragment(o, {0.5f, 0.5f, -4.0f}, false, {0.5f, 0.5f, 4.0f});
  EXPECT_EQ(along.fate, Fate::CutSurface);
  expectNear(along.position, {0.5f, 0.5f, -1.0f});
  EXPECT_EQ(boxCutFragment(o, {1.5f, 0.5f, -4.0f}, false, {1.5f, 0.5f, 4.0f}).fate, Fate::Keep);
  // From inside the box the wall is where the ray leaves it.
  const BoxCutFate inside = boxCutFragment(o, {0.0f, -3.0f, 0.0f}, false, {0.0f, 0.5f, 0.0f});
  EXPECT_EQ(inside.fate, Fate::CutSurface);
  expectNear(inside.position, {0.0f, -1.0f, 0.0f});
  expectNear(inside.normal, {0.0f, 1.0f, 0.0f});
  // An oblique ray leaving through the side x = 1.
  const BoxCutFate side = boxCutFragment(o, {3.0f, 0.0f, -1.5f}, false, {-3.0f, 0.0f, 1.5f});
  EXPECT_EQ(side.fate, Fate::CutSurface);
  expectNear(side.position, {1.0f, 0.0f, -0.5f});
  expectNear(side.normal, {-1.0f, 0.0f, 0.0f});
}

TEST(BoxCutFunction, TheBoxTurnsAndMovesWithItsOptions) {
  BoxCutOptions o = unitBox();
  o.size = {4.0f, 1.0f, 1.0f};  // long along its own x
  o.center = {0.0f, 5.0f, 0.0f};
  o.rotation = {0.0f, 90.0f, 0.0f};  // its x now along world −z
  const glm::mat3 axes = boxCutAxes(o);
  expectNear(axes[0], {0.0f, 0.0f, -1.0f});
  const glm::vec3 far(100.0f, 5.0f, 0.0f);
  EXPECT_EQ(boxCutFragment(o, {0.0f, 5.0f, 1.8f}, true, far).fate, Fate::Discard);
  EXPECT_EQ(boxCutFragment(o, {1.8f, 5.0f, 0.0f}, true, far).fate, Fate::Keep);
  EXPECT_EQ(boxCutFragment(o, {0.0f, 0.0f, 1.8f}, true, far).fate, Fate::Keep);
}

// The renderer draws an object whose box the cut box does not meet (boxCutMeetsBox) without
// the box's code: no point of such a box may lie inside the cut box. Random boxes against a
// turned cut box, checked by boxCutFragment at 300 points each, corners included.
TEST(BoxCutFunction, ABoxItDoesNotMeetHoldsNoPointItRemoves) {
  BoxCutOptions o = unitBox();
  o.size = {3.0f, 1.0f, 2.0f};
  o.center = {0.5f, -1.0f, 2.0f};
  o.rotation = {20.0f, 35.0f, -10.0f};
  std::mt19937 random(3);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), fraction(0.0f, 1.0f);
  int met = 0, apart = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const glm::vec3 center = o.center + 3.0f * glm::vec3(unit(random), unit(random), unit(random));
    const glm::vec3 half = 1.5f * glm::vec3(fraction(random), fraction(random), fraction(random));
    const Bounds box{.min = center - half, .max = center + half};
    if (boxCutMeetsBox(o, box)) {
      ++met;
      continue;
    }
    ++apart;
    for (int i = 0; i < 300; ++i) {
      const glm::vec3 p =
          glm::mix(box.min, box.max,
                   i < 8 ? glm::vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1)
                         : glm::vec3(fraction(random), fraction(random), fraction(random)));
      ASSERT_NE(boxCutFragment(o, p, true, glm::vec3(100.0f)).fate, Fate::Discard)
          << "trial " << trial;
    }
  }
  EXPECT_GT(met, 300);
  EXPECT_GT(apart, 300);
  // A box that touches the cut box's face from outside meets it; one a hair beyond does not.
  const BoxCutOptions axisAligned = unitBox();  // [−1, 1]³
  EXPECT_TRUE(boxCutMeetsBox(axisAligned, {.min = {1.0f, 0, 0}, .max = {2, 1, 1}}));
  EXPECT_FALSE(boxCutMeetsBox(axisAligned, {.min = {1.01f, 0, 0}, .max = {2, 1, 1}}));
  EXPECT_FALSE(boxCutMeetsBox(axisAligned, Bounds{}));
}

// A cut box that meets no object leaves the frame as the uncut one draws it, byte for byte:
// the objects draw without the box's code (Cutter::reaches). Among them a one-sided
// (`doubleSided: false`) open square behind the box, seen from its back: as a cut object its
// back faces were drawn (7155 bytes differed), where the uncut frame culls them.
TEST(BoxCutFrame, ABoxThatMeetsNoObjectLeavesTheFrameAsUncut) {
  const Scene scene = parseScene(R"({"resolution": [120, 90], "samples": 4,
    "camera": {"eye": [0.5, 0.8, -6], "target": [0, 0, 0], "fov": 45},
    "objects": [
      {"name": "block", "file": "meshes/cube.obj", "transform": {"translate": [1.6, -0.5, -0.5]}},
      {"name": "square", "file": "meshes/flat.obj", "params": {"doubleSided": false},
       "transform": {"translate": [-2, -2, 3], "scale": 4}}],
    "cutters": {"boxCut": {"center": [0, 0, 0], "size": [2, 2, 2], "rotate": [0, 30, 0]}}})",
                                 "box.json", kData);
  Scene plain = scene;
  plain.cutters.clear();
  Renderer cut(scene, test::glContext().info()), whole(plain, test::glContext().info());
  cut.render();
  whole.render();
  const Rgba8Image a = cut.readColor(), b = whole.readColor();
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  int differ = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) differ += a.pixels[i] != b.pixels[i];
  EXPECT_EQ(differ, 0);
}

namespace {

// A solid block, [−2, 2] × [−1.5, 1.5] × [−2, 2], with a small object of interest inside, cut by a
// box turned about two axes that takes its corner towards the viewer.
Scene blockScene(bool orthographic) {
  std::string json = R"({"resolution": [160, 120], "samples": 1,
    "style": {"name": "blinn-phong", "lines": false},
    "camera": {"projection": "PROJECTION", "eye": [6, 5, 8], "target": [0, 0, 0], "fov": 45,
               "height": 8},
    "objects": [
      {"name": "block", "file": "meshes/cube.obj", "transform": {"translate": [-2, -1.5, -2], "scale": [4, 3, 4]}},
      {"name": "core", "file": "meshes/cube.obj", "role": "interest", "color": [0.9, 0.2, 0.2],
       "transform": {"translate": [-0.4, -0.4, -0.4], "scale": 0.8}}],
    "cutters": {"boxCut": {"center": [1.2, 1.0, 1.4], "size": [2.6, 2.4, 3.0],
                           "rotate": [10, 25, 0]}}})";
  json.replace(json.find("PROJECTION"), 10, orthographic ? "orthographic" : "perspective");
  return parseScene(json, "block.json", kData);
}

glm::vec3 at(const FloatImage& image, int x, int y) {
  const float* v = image.at(x, y);
  return {v[0], v[1], v[2]};
}

// How far outside the box a point is along its worst axis (< 0: inside).
float boxDistance(const BoxCutOptions& o, const glm::vec3& p) {
  const glm::vec3 local = glm::transpose(boxCutAxes(o)) * (p - o.center);
  const glm::vec3 d = glm::abs(local) - 0.5f * o.size;
  return std::max(d.x, std::max(d.y, d.z));
}

// Where the ray from `origin` through `p` leaves the block [−2, 2] × [−1.5, 1.5] × [−2, 2]:
// the back face behind a pixel of the block.
glm::vec3 blockExit(const glm::vec3& origin, const glm::vec3& p) {
  const glm::vec3 half(2.0f, 1.5f, 2.0f), d = p - origin;
  float t = 1e30f;
  for (int i = 0; i < 3; ++i)
    if (d[i] != 0.0f) t = std::min(t, ((d[i] > 0.0f ? half[i] : -half[i]) - origin[i]) / d[i]);
  return origin + t * d;
}

}  // namespace

class BoxCutGpu : public ::testing::TestWithParam<bool> {};

// What the block shows is what boxCutFragment keeps; its cut walls are where boxCutFragment
// puts them for the back face behind the pixel, on the box's faces inside the block; and
// where the uncut block showed material inside the box, the frame shows something else.
TEST_P(BoxCutGpu, CutsWhereTheCppFunctionSays) {
  const Scene scene = blockScene(GetParam());
  const BoxCutOptions& box = *scene.cutters.find<BoxCutOptions>();
  Scene plain = scene;
  plain.cutters.clear();
  const auto cut = renderAovs(scene), whole = renderAovs(plain);
  const FloatImage &ids = aov(cut, "objectId"), &pos = aov(cut, "position"),
                   &cutMask = aov(cut, "cutMask"), &normal = aov(cut, "normal");
  const FloatImage &plainIds = aov(whole, "objectId"), &plainPos = aov(whole, "position");
  const Camera camera = scene.resolvedCamera();
  const float margin = 1e-3f;
  int kept = 0, walls = 0, removed = 0;
  for (int y = 0; y < scene.height; ++y)
    for (int x = 0; x < scene.width; ++x) {
      const bool block = int(ids.at(x, y)[0]) == 0;
      const glm::vec3 p = at(pos, x, y);
      if (block && cutMask.at(x, y)[0] < 0.5f) {
        // A front face of the block outside the box.
        ++kept;
        EXPECT_GT(boxDistance(box, p), -margin) << x << "," << y;
      }
      if (block && cutMask.at(x, y)[0] > 0.5f) {
        // The cut wall: on a face of the box, inside the block, facing the viewer, where the
        // C++ decision for the block's back face along this view ray has it.
        ++walls;
        EXPECT_NEAR(boxDistance(box, p), 0.0f, 1e-3f) << x << "," << y;
        EXPECT_LE(std::abs(p.x), 2.0f + margin);
        EXPECT_LE(std::abs(p.y), 1.5f + margin);
        EXPECT_LE(std::abs(p.z), 2.0f + margin);
        const glm::vec3 origin = camera.rayOrigin(p);
        const BoxCutFate mirror = boxCutFragment(box, blockExit(origin, p), false, origin);
        ASSERT_EQ(mirror.fate, BoxCutFate::Fate::CutSurface) << x << "," << y;
        EXPECT_LT(glm::length(mirror.position - p), 1e-3f) << x << "," << y;
        EXPECT_LT(glm::length(mirror.normal - at(normal, x, y)), 2e-3f) << x << "," << y;
      }
      if (int(plainIds.at(x, y)[0]) == 0) {
        if (boxDistance(box, at(plainPos, x, y)) < -margin) {
          // What the cut frame shows there lies beyond the removed point along the view ray.
          ++removed;
          const glm::vec3 origin = camera.rayOrigin(p);
          EXPECT_GT(glm::length(p - origin), glm::length(at(plainPos, x, y) - origin) + 1e-4f)
              << "removed material still drawn at " << x << "," << y;
        }
      }
    }
  const int pixels = scene.width * scene.height;
  EXPECT_GT(kept, pixels / 50);
  EXPECT_GT(walls, pixels / 50);
  EXPECT_GT(removed, pixels / 50);
}

INSTANTIATE_TEST_SUITE_P(Views, BoxCutGpu, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return info.param ? "orthographic" : "perspective";
                         });

TEST(BoxCutOptions, AreReadCheckedAndSetByTheirPaths) {
  Scene scene = blockScene(false);
  const BoxCutOptions& box = *scene.cutters.find<BoxCutOptions>();
  EXPECT_EQ(box.size, glm::vec3(2.6f, 2.4f, 3.0f));
  EXPECT_EQ(box.rotation, glm::vec3(10.0f, 25.0f, 0.0f));
  setOption(scene, "cutters.boxCut.rotate", "0,45,0");
  EXPECT_EQ(scene.cutters.find<BoxCutOptions>()->rotation, glm::vec3(0.0f, 45.0f, 0.0f));
  EXPECT_THROW(setOption(scene, "cutters.boxCut.size", "1,0,1"), Error);
  EXPECT_TRUE(findSceneOption("cutters.boxCut.center")->spec.live);
}
