// Occlusion culling (src/frame/occlusion_culling.hpp): the geometry pass, the ghost geometry
// and the translucent layers skip hidden objects from the second frame of a view on, and every
// picture and AOV is the same, bit for bit, as drawing every object.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "cutaway/render/renderer.hpp"
#include "cutaway/render/techniques.hpp"
#include "cutaway/scene/scene.hpp"
#include "gl_test_context.hpp"

using namespace cutaway;

namespace {

const std::string kData = CUTAWAY_TEST_DATA;

// A 20 × 20 wall at z = 0 in front of a 2 × 2 square at z = −3, seen along −z.
Scene wallScene() {
  return parseScene(R"({"resolution": [96, 72], "samples": 4,
      "style": {"name": "gooch", "lines": true},
      "camera": {"eye": [0, 0, 20], "target": [0, 0, 0], "fov": 40},
      "objects": [
        {"name": "wall", "file": "render/plane.obj"},
        {"name": "hidden", "file": "render/plane.obj", "color": [0.9, 0.2, 0.2],
         "transform": {"translate": [0, 0, -3], "scale": 0.1}}]})",
                    "wall.json", kData);
}

struct Picture {
  Rgba8Image color;
  std::vector<Aov> aovs;
};

Picture picture(Renderer& renderer, const Camera& camera) {
  renderer.render(camera);
  return {renderer.readColor(), renderer.readAovs()};
}

// Bit for bit: NaN channels (no value) compare equal to NaN.
void expectSame(const Picture& culled, const Picture& all, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(culled.color.width, all.color.width);
  ASSERT_EQ(culled.color.height, all.color.height);
  std::size_t colorDiffs = 0;
  for (std::size_t i = 0; i < all.color.pixels.size(); ++i)
    colorDiffs += culled.color.pixels[i] != all.color.pixels[i];
  EXPECT_EQ(colorDiffs, 0u) << "colour bytes differ";
  ASSERT_EQ(culled.aovs.size(), all.aovs.size());
  for (std::size_t a = 0; a < all.aovs.size(); ++a) {
    const FloatImage &x = culled.aovs[a].image, &y = all.aovs[a].image;
    ASSERT_EQ(x.data.size(), y.data.size()) << all.aovs[a].name;
    std::size_t diffs = 0;
    for (std::size_t i = 0; i < y.data.size(); ++i)
      diffs += std::memcmp(&x.data[i], &y.data[i], sizeof(float)) != 0 &&
               !(std::isnan(x.data[i]) && std::isnan(y.data[i]));
    EXPECT_EQ(diffs, 0u) << "AOV " << all.aovs[a].name << " differs";
  }
}

Camera orbit(const Scene& scene, float degrees, float distanceScale) {
  Camera c = scene.resolvedCamera(0.0f);
  const glm::vec3 offset = c.eye - c.target;
  const float a = glm::radians(degrees);
  c.eye = c.target + distanceScale * glm::vec3(std::cos(a) * offset.x + std::sin(a) * offset.z,
                                               offset.y,
                                               -std::sin(a) * offset.x + std::cos(a) * offset.z);
  c.fit = false;
  c.near = c.far = 0.0f;  // derived again: in close, the near plane cuts the engine's boxes
  Scene moved = scene;
  moved.camera = c;
  return moved.resolvedCamera(0.0f);
}

}  // namespace

TEST(OcclusionCulling, AHiddenObjectIsSkippedFromTheSecondFrameAndDrawnWhenItShows) {
  const Scene scene = wallScene();
  Renderer culling(scene, test::glContext().info()), all(scene, test::glContext().info());
  all.setOcclusionCulling(false);
  const Camera front = scene.resolvedCamera(0.0f);
  picture(culling, front);
  EXPECT_EQ(culling.culledObjects(), 0u) << "the first frame draws every object";
  expectSame(picture(culling, front), picture(all, front), "front, second frame");
  EXPECT_EQ(culling.culledObjects(), 1u) << "the square behind the wall";
  EXPECT_EQ(all.culledObjects(), 0u);
  // From behind the wall the square shows: drawn in the frame it comes into view.
  Camera back = front;
  back.eye = {4, 1, -20};
  expectSame(picture(culling, back), picture(all, back), "from behind");
  EXPECT_EQ(culling.culledObjects(), 0u);
  // The eye between the two, so the near plane cuts the square's box: never culled.
  Camera between = front;
  between.eye = {0, 0, -2.0f};
  between.near = 0.5f, between.far = 40.0f;
  expectSame(picture(culling, between), picture(all, between), "between");
  EXPECT_EQ(culling.culledObjects(), 0u);
}

TEST(OcclusionCulling, ExamplesDrawTheSamePicturesAndAovsWhenTheViewHoldsStill) {
  std::size_t culledInAll = 0;
  // One example per kind of pass that draws scene meshes: the geometry pass, the caps, the
  // cutout's texture and clip planes, the ghost geometry, the translucent layers, with pipes and
  // with volumes.
  const std::vector<std::pair<std::string, std::string>> examples{
      {"engine.json", ""},
      {"engine-cutaway.json", ""},
      {"engine-clip.json", ""},
      {"engine-cutout.json", ""},
      {"engine-cutout.json", "clipPlanes"},
      {"engine-translucent.json", ""},
      {"house-cutaway.json", ""},
      {"ss64ne-city-cutaway.json", ""},
      {"mri-head-needle.json", ""}};
  for (const auto& [file, cutoutMethod] : examples) {
    Scene scene = loadScene(std::string(CUTAWAY_SOURCE_DIR) + "/examples/" + file);
    scene.width = 128, scene.height = 96;
    if (!cutoutMethod.empty()) setOption(scene, "cutters.cutout.method", cutoutMethod);
    Renderer culling(scene, test::glContext().info()), all(scene, test::glContext().info());
    all.setOcclusionCulling(false);
    const Camera camera = scene.resolvedCamera(0.0f);
    picture(culling, camera);
    expectSame(picture(culling, camera), picture(all, camera), file + " " + cutoutMethod);
    culledInAll += culling.culledObjects();
  }
  EXPECT_GT(culledInAll, 10u) << "the engine's inside is hidden in its plain view";
}

// While the view moves, every frame too, here: the engine's parts meet in no exact depth tie
// with the parts they come into view beside. The cutaway's ghost geometry (its ghost lines)
// is culled in its own pass.
TEST(OcclusionCulling, AnOrbitOfTheEngineDrawsTheSamePictureEveryFrame) {
  for (const std::string file : {"engine.json", "engine-cutaway.json"}) {
    Scene scene = loadScene(std::string(CUTAWAY_SOURCE_DIR) + "/examples/" + file);
    scene.width = 160, scene.height = 120;
    Renderer culling(scene, test::glContext().info()), all(scene, test::glContext().info());
    all.setOcclusionCulling(false);
    std::size_t culled = 0;
    for (int step = 0; step < 8; ++step) {
      // A quarter turn, then in close: the near plane cuts the engine's boxes.
      const Camera c = orbit(scene, 12.0f * float(step), step < 6 ? 1.0f : 0.35f);
      expectSame(picture(culling, c), picture(all, c), file + ", step " + std::to_string(step));
      culled += culling.culledObjects();
    }
    EXPECT_GT(culled, 0u) << file;
  }
}

// A live change (a cutter turned between frames) reveals objects, drawn that frame after those
// shown before; from the next frame on the picture is the fresh renderer's, bit for bit.
TEST(OcclusionCulling, AfterALiveChangeTheNextFrameIsTheFreshRenderersPicture) {
  Scene scene = loadScene(std::string(CUTAWAY_SOURCE_DIR) + "/examples/house-box-cut.json");
  scene.width = 96, scene.height = 72;
  const Camera camera = scene.resolvedCamera(0.0f);
  Renderer culling(scene, test::glContext().info());
  picture(culling, camera);
  picture(culling, camera);
  const std::size_t before = culling.culledObjects();
  setOption(scene, "cutters.boxCut.rotate", "0.05,0.05,0.05");
  picture(culling, camera);  // the frame of the change
  Renderer all(scene, test::glContext().info());
  all.setOcclusionCulling(false);
  expectSame(picture(culling, camera), picture(all, camera), "the frame after the change");
  EXPECT_GT(before, 0u);
  EXPECT_GT(culling.culledObjects(), 0u);
}

// Burns11 ch. 2's translucent layers: an object whose fragments all lie at or in front of an
// earlier layer, wherever that layer found a surface, is left out of the later layers (its
// box's far side against that layer's depth). Exact within the frame, so from the first one:
// the picture and every AOV are the same bit for bit, as the view turns too.
TEST(OcclusionCulling, TranslucentLayersLeaveOutWhatTheyHavePeeled) {
  Scene scene = loadScene(std::string(CUTAWAY_SOURCE_DIR) + "/examples/engine-translucent.json");
  scene.width = 160, scene.height = 120;
  Renderer culling(scene, test::glContext().info()), all(scene, test::glContext().info());
  all.setOcclusionCulling(false);
  for (const float degrees : {0.0f, 30.0f, 75.0f}) {
    const Camera camera = orbit(scene, degrees, 1.0f);
    expectSame(picture(culling, camera), picture(all, camera),
               "turned " + std::to_string(degrees) + "°");
    EXPECT_GT(culling.peeledLayerDraws(), 20u) << degrees << "°";
    EXPECT_EQ(all.peeledLayerDraws(), 0u);
  }
}
