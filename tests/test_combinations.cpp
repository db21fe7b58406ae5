// Several cutters in one frame, each cutting where its own rule says and nowhere else: the
// engine with an adaptive cutaway, a cutout of its casing and a clip surface; the SS64NE city
// with its buildings cut adaptively around the sewer pipes (billboards as the region of
// interest) while the terrain opens above them (Konev18 + Burns08). Each rule is checked
// against an independent evaluation: the cutaway depth's texels, the C++ mirrors of the
// cutout wedge (Diepstraten03 §4.5), the clip surface (Trapp13 eq. 1) and the terrain opening
// (Konev18 eqs. 1–3), and against renders without the cutter.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "cutaway/cutters/adaptive.hpp"
#include "cutaway/cutters/clip_surfaces.hpp"
#include "cutaway/cutters/cutout.hpp"
#include "cutaway/cutters/terrain_opening.hpp"
#include "cutaway/render/renderer.hpp"
#include "gl_test_context.hpp"
#include "render_aovs.hpp"

using namespace cutaway;
using test::aov;
using test::renderAovs;

namespace {

const std::string kExamples = std::string(CUTAWAY_SOURCE_DIR) + "/examples/";

// One sample per pixel: every fragment lies at its pixel's centre, where the AOVs hold it.
Scene small(const std::string& file, int width, int height) {
  Scene scene = loadScene(kExamples + file);
  scene.width = width, scene.height = height, scene.samples = 1;
  return scene;
}

int id(const FloatImage& ids, int x, int y) {
  return int(ids.at(x, y)[0]);
}

// The texels of a cutaway buffer (AOV rows top-down) that linear filtering blends at the
// centre of image pixel (x, y): whatever the filter's weights, the value lies between their
// least and greatest.
std::pair<float, float> texelRange(const FloatImage& buffer, const Scene& scene, int x, int y) {
  const int n = buffer.width;
  const float u = (float(x) + 0.5f) / float(scene.width) * float(n) - 0.5f;
  const float v = (float(scene.height - 1 - y) + 0.5f) / float(scene.height) * float(n) - 0.5f;
  float lo = 1e30f, hi = -1e30f;
  for (const int ty : {int(std::floor(v)), int(std::floor(v)) + 1})
    for (const int tx : {int(std::floor(u)), int(std::floor(u)) + 1}) {
      const int cx = std::clamp(tx, 0, n - 1), cy = std::clamp(ty, 0, n - 1);
      const float c = buffer.at(cx, n - 1 - cy)[0];  // AOV rows run top to bottom
      lo = std::min(lo, c), hi = std::max(hi, c);
    }
  return {lo, hi};
}

glm::vec3 position(const FloatImage& p, int x, int y) {
  const float* v = p.at(x, y);
  return {v[0], v[1], v[2]};
}

// The window depth the cutters' GLSL compared (gl_FragCoord.z, at the pixel's centre) of the
// visible surface point: the depth AOV holds sample 0's, which even a one-sample multisample
// target may place off the centre.
struct CentreDepth {
  glm::mat4 viewProjection;
  float operator()(const FloatImage& pos, int x, int y) const {
    const glm::vec4 c = viewProjection * glm::vec4(position(pos, x, y), 1.0f);
    return c.z / c.w * 0.5f + 0.5f;
  }
};
CentreDepth centreDepth(const Scene& scene) {
  const Camera c = scene.resolvedCamera();
  return {c.projectionMatrix(float(scene.width) / float(scene.height)) * c.view()};
}

}  // namespace

TEST(Combinations, EngineAdaptiveCutoutAndClipSurfaceEachCutWhereTheySay) {
  const Scene scene = small("engine-combined.json", 240, 180);
  Scene plain = scene;
  plain.cutters.clear();
  const auto cut = renderAovs(scene);
  const auto whole = renderAovs(plain);
  const FloatImage &ids = aov(cut, "objectId"), &pos = aov(cut, "position"),
                   &cutMask = aov(cut, "cutMask"),
                   &capMask = aov(cut, "capMask"), &distance = aov(cut, "cutoutDistance"),
                   &cutaway = aov(cut, "cutawayDepth"), &dilated = aov(cut, "cutawayDilated");
  const FloatImage &plainIds = aov(whole, "objectId"), &plainPos = aov(whole, "position");
  const CentreDepth depthOf = centreDepth(scene);
  const auto isCasing = [&](int i) { return i >= 0 && scene.objects[std::size_t(i)].group == "casing"; };
  const auto isContext = [&](int i) {
    return i >= 0 && scene.objects[std::size_t(i)].role == Role::Context;
  };
  // The C++ mirrors of the wedge and the clip surface, for the camera of this frame.
  const Camera camera = scene.resolvedCamera();
  const CutoutOptions& cutout = *scene.cutters.find<CutoutOptions>();
  const std::vector<ExteriorUnit> units = exteriorUnits(scene);
  ASSERT_EQ(units.size(), 1u);  // one group: the casing
  const CutoutWedge wedge = cutoutWedge(units[0].axes, cutout, camera.eye - units[0].axes.center);
  const ClipSurface& clip = scene.cutters.find<ClipSurfaceOptions>()->surfaces[0];

  int adaptiveChecked = 0, removedByAdaptive = 0, casingChecked = 0, removedByWedge = 0,
      clipChecked = 0, removedByClip = 0, caps = 0;
  for (int y = 0; y < scene.height; ++y)
    for (int x = 0; x < scene.width; ++x) {
      const int i = id(ids, x, y), before = id(plainIds, x, y);
      const bool cap = capMask.at(x, y)[0] > 0.5f;
      // A cut surface shows the cutaway surface's point, not the fragment's.
      const bool meshPoint = cutMask.at(x, y)[0] < 0.5f || cap;
      caps += cap;
      // Burns08 §4.1: no kept fragment of the material the adaptive cutter cuts (caps of it
      // included) lies in front of the cutaway surface (back faces: its 1-pixel dilation, §4.2).
      if (isContext(i) && meshPoint) {
        ++adaptiveChecked;
        EXPECT_GE(depthOf(pos, x, y), texelRange(dilated, scene, x, y).first - 1e-6f)
            << x << "," << y;
      }
      // ... and where the whole engine showed such material clearly in front of it, the cut
      // frame shows something deeper.
      if (isContext(before) && depthOf(plainPos, x, y) < texelRange(cutaway, scene, x, y).first &&
          (i < 0 || depthOf(pos, x, y) > depthOf(plainPos, x, y)))
        ++removedByAdaptive;
      // Diepstraten03 §4.5: a visible casing fragment lies outside the wedge, by the GPU's
      // distance and by the C++ one at its position; inside it the whole engine's casing
      // is gone.
      if (isCasing(i) && cutMask.at(x, y)[0] < 0.5f) {
        ++casingChecked;
        const float gpu = distance.at(x, y)[0];
        EXPECT_LE(gpu, 1e-6f) << x << "," << y;
        EXPECT_NEAR(gpu, cutoutDistance(wedge, cutout.jitter, position(pos, x, y)),
                    1e-4f * wedge.axisLength)
            << x << "," << y;
      }
      if (isCasing(before) && cutoutDistance(wedge, cutout.jitter, position(plainPos, x, y)) >
                                  1e-3f * wedge.axisLength) {
        ++removedByWedge;
        EXPECT_FALSE(isCasing(i) && std::abs(depthOf(pos, x, y) - depthOf(plainPos, x, y)) < 1e-6f)
            << "casing inside the wedge still drawn at " << x << "," << y;
      }
      // Trapp13 eq. 1: no visible fragment of what the clip surface cuts lies on its clipped
      // side (cut surfaces and caps show other points: left out).
      if (isContext(i) && !cap && meshPoint) {
        ++clipChecked;
        EXPECT_GE(clipSurfaceFunction(clip, position(pos, x, y)), -1e-3f) << x << "," << y;
      }
      if (isContext(before) && clipSurfaceFunction(clip, position(plainPos, x, y)) < 0.0f)
        ++removedByClip;
    }
  const int pixels = scene.width * scene.height;
  // Each cutter had work in this view: at least a share of the image that no stray pixels make
  // (a thousandth; each is ten times that or more here).
  EXPECT_GT(adaptiveChecked, pixels / 1000);
  EXPECT_GT(removedByAdaptive, pixels / 1000);
  EXPECT_GT(casingChecked, pixels / 1000);
  EXPECT_GT(removedByWedge, pixels / 1000);
  EXPECT_GT(clipChecked, pixels / 1000);
  EXPECT_GT(removedByClip, pixels / 1000);
  // Caps close what the clip surface cut where the adaptive cutaway left it (38 pixels here).
  EXPECT_GT(caps, 10);
  // The objects of interest are never cut: the cut frame shows more of them.
  int interestBefore = 0, interestAfter = 0;
  for (int y = 0; y < scene.height; ++y)
    for (int x = 0; x < scene.width; ++x) {
      const int a = id(plainIds, x, y), b = id(ids, x, y);
      interestBefore += a >= 0 && scene.objects[std::size_t(a)].role == Role::Interest;
      interestAfter += b >= 0 && scene.objects[std::size_t(b)].role == Role::Interest;
    }
  EXPECT_GT(interestAfter, 2 * interestBefore + pixels / 100);
}

TEST(Combinations, CityBuildingsCutAroundThePipesWhileTheTerrainOpens) {
  const Scene scene = small("ss64ne-city-cutaway.json", 320, 200);
  Scene terrainOnly = scene;
  terrainOnly.cutters.disable<AdaptiveCutawayOptions>();
  const auto cut = renderAovs(scene);
  const auto opened = renderAovs(terrainOnly);
  const FloatImage &ids = aov(cut, "objectId"), &pos = aov(cut, "position"),
                   &cutMask = aov(cut, "cutMask"),
                   &cutaway = aov(cut, "cutawayDepth"), &dilated = aov(cut, "cutawayDilated"),
                   &seeds = aov(cut, "seedDepth"), &pipeClass = aov(cut, "pipeClass");
  const FloatImage &openIds = aov(opened, "objectId"), &openPos = aov(opened, "position"),
                   &openCutMask = aov(opened, "cutMask"), &openPipes = aov(opened, "pipeClass");
  const CentreDepth depthOf = centreDepth(scene);
  const SceneObject* ground = scene.find("ground");
  const SceneObject* buildings = scene.find("buildings");
  ASSERT_TRUE(ground && buildings);
  const int groundId = int(ground - scene.objects.data()), buildingsId = int(buildings - scene.objects.data());

  // The pipes, drawn as billboards, are the region of interest: they seed the cutaway.
  int seeded = 0;
  for (float s : seeds.data) seeded += s > 0.0f;
  EXPECT_GT(seeded, int(seeds.data.size()) / 500);

  // Konev18 eqs. 1–3 in C++, for the terrain as the cutter sees it.
  const TerrainOpeningOptions& opening = *scene.cutters.find<TerrainOpeningOptions>();
  const TerrainField field = terrainField(opening, ground->worldBounds());
  const Camera camera = scene.resolvedCamera();

  int buildingsChecked = 0, buildingsRemoved = 0, groundChecked = 0, groundFateDisagrees = 0,
      groundLost = 0, pipesBefore = 0, pipesAfter = 0;
  for (int y = 0; y < scene.height; ++y)
    for (int x = 0; x < scene.width; ++x) {
      const int i = id(ids, x, y), before = id(openIds, x, y);
      pipesBefore += openPipes.at(x, y)[0] > 0.0f;
      pipesAfter += pipeClass.at(x, y)[0] > 0.0f;
      // No kept building fragment lies in front of the cutaway surface around the pipes (a
      // cut surface shows that surface's point: left out).
      if (i == buildingsId && cutMask.at(x, y)[0] < 0.5f) {
        ++buildingsChecked;
        EXPECT_GE(depthOf(pos, x, y), texelRange(dilated, scene, x, y).first - 1e-6f)
            << x << "," << y;
      }
      if (before == buildingsId && openCutMask.at(x, y)[0] < 0.5f &&
          depthOf(openPos, x, y) < texelRange(cutaway, scene, x, y).first) {
        ++buildingsRemoved;  // behind it: the ground, a pipe, or the building's own cut walls
        EXPECT_TRUE(i != buildingsId || depthOf(pos, x, y) > depthOf(openPos, x, y)) << x << "," << y;
      }
      // The ground is cut by the terrain opening alone: wherever the opening left it, the
      // adaptive cutaway left it too (removing buildings puts nothing in front of it) …
      if (before == groundId) groundLost += i != groundId;
      // … and each of its visible fragments is one eqs. 2–3 keep (texel-boundary rounding
      // between the GPU and C++ may flip a few); its trench walls show a point below it.
      if (i == groundId && cutMask.at(x, y)[0] < 0.5f) {
        ++groundChecked;
        groundFateDisagrees +=
            terrainFate(field, opening, position(pos, x, y), camera.eye,
                        position(pos, x, y) - camera.eye) == TerrainFate::Discard;
      }
    }
  EXPECT_EQ(groundLost, 0);
  EXPECT_GT(groundChecked, scene.width * scene.height / 4);
  EXPECT_LE(groundFateDisagrees, groundChecked / 200) << groundChecked << " ground pixels";
  EXPECT_GT(buildingsChecked, 0);
  EXPECT_GT(buildingsRemoved, 50);
  // What the buildings hid of the pipes shows now.
  EXPECT_GT(pipesAfter, pipesBefore);
}
