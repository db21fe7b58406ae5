// Every option a schema calls live really is: changed between two frames of one renderer, the
// second frame is the image a new renderer makes of the changed scene, pixel for pixel. Each
// technique is checked on scenes where it is on (technique_scenes.hpp); and each option's
// change must show in the image of one of them, so that no live option is a no-op.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "cutaway/render/renderer.hpp"
#include "cutaway/render/techniques.hpp"
#include "gl_test_context.hpp"
#include "technique_scenes.hpp"

using namespace cutaway;
using test::Case;

namespace {

Rgba8Image renderOnce(const Scene& scene) {
  Renderer renderer(scene, test::glContext().info());
  renderer.render();
  return renderer.readColor();
}

}  // namespace

class LiveOptions : public ::testing::TestWithParam<Case> {};

TEST_P(LiveOptions, AChangeBetweenFramesIsTheFreshRenderersImage) {
  const Case& c = GetParam();
  ASSERT_FALSE(c.examples.empty()) << c.technique << " has no scene in technique_scenes.hpp";
  std::map<std::string, bool> shows;  // live option → its change showed in some example
  for (const std::string& example : c.examples) {
    SCOPED_TRACE(example);
    Scene scene = test::small(c, example);
    const TechniqueSettings cutters = scene.cutters;
    const Style style = scene.style;
    const auto networks = scene.networks;
    const auto volumes = scene.volumes;
    std::vector<glm::vec3> colors;  // the networks' colours reach their shafts' objects
    for (const SceneObject& o : scene.objects) colors.push_back(o.material.color);
    Renderer renderer(scene, test::glContext().info());
    // Occlusion culling draws an object the change reveals after the others, so an exact
    // depth tie with them may go the other way for that one frame (test_occlusion_culling.cpp).
    renderer.setOcclusionCulling(false);
    renderer.render();
    const Rgba8Image before = renderer.readColor();
    for (const SceneOption& o : sceneOptions()) {
      if (o.technique != c.technique || !o.spec.live) continue;
      if (o.spec.applies && !o.spec.applies(&scene)) continue;
      SCOPED_TRACE(o.path);
      const OptionValue old = o.spec.get(&scene);
      const OptionValue next = test::changed(o.spec, old);
      ASSERT_NE(formatOptionValue(next), formatOptionValue(old));
      o.spec.set(&scene, next);
      renderer.render();
      const Rgba8Image live = renderer.readColor();
      EXPECT_EQ(live.pixels, renderOnce(scene).pixels)
          << o.path << " = " << formatOptionValue(next) << ": the live frame differs from a new "
          << "renderer's";
      shows[o.path] |= live.pixels != before.pixels;
      scene.cutters = cutters;  // back as it was, unset optional values included
      scene.style = style;
      scene.networks = networks;
      scene.volumes = volumes;
      for (std::size_t i = 0; i < colors.size(); ++i) scene.objects[i].material.color = colors[i];
    }
    renderer.render();
    EXPECT_EQ(renderer.readColor().pixels, before.pixels) << "the options did not go back";
  }
  EXPECT_FALSE(shows.empty()) << c.technique << " has no live option that applies";
  for (const auto& [path, shown] : shows)
    EXPECT_TRUE(shown) << path << ": its change showed in none of the examples";
}

INSTANTIATE_TEST_SUITE_P(Techniques, LiveOptions, ::testing::ValuesIn(test::cases()),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           std::string name = info.param.technique;
                           std::replace(name.begin(), name.end(), '.', '_');
                           return name;
                         });
