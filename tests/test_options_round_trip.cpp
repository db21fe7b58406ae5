// Every option of every schema survives the scene file: each technique's options changed at
// once (technique_scenes.hpp's scenes, every value moved inside its range), written back into
// the scene file by SceneDocument, read again by the scene reader, give the same values as
// the schemas write them.
#include <gtest/gtest.h>

#include "cutaway/scene/scene_writer.hpp"
#include "run_command.hpp"
#include "technique_scenes.hpp"

using namespace cutaway;
using test::Case;

class OptionsRoundTrip : public ::testing::TestWithParam<Case> {};

TEST_P(OptionsRoundTrip, EveryOptionIsWrittenAndReadBack) {
  const Case& c = GetParam();
  ASSERT_FALSE(c.examples.empty()) << c.technique << " has no scene in technique_scenes.hpp";
  const std::string file = std::string(CUTAWAY_SOURCE_DIR) + "/" + c.examples.front();
  const Scene original = loadScene(file);
  Scene current = test::small(c, c.examples.front());
  current.width = original.width, current.height = original.height;
  int changed = 0;
  for (const SceneOption& o : sceneOptions()) {
    if (o.technique != c.technique || !o.spec.inFile) continue;
    if (o.spec.applies && !o.spec.applies(&current)) continue;
    if (o.spec.type == OptionSpec::Type::Text) continue;  // style.name: the scene's choice
    o.spec.set(&current, test::changed(o.spec, o.spec.get(&current)));
    ++changed;
  }
  ASSERT_GT(changed, 0);
  const std::filesystem::path saved = test::scratchPath("round-trip", "saved.json");
  SceneDocument::load(file).save(original, current, saved);
  const Scene again = loadScene(saved);
  EXPECT_EQ(cuttersJson(again).dump(1), cuttersJson(current).dump(1));
  EXPECT_EQ(styleJson(again.style).dump(1), styleJson(current.style).dump(1));
  // And the change is real: the file differs from what it was.
  EXPECT_TRUE(cuttersJson(again) != cuttersJson(original) ||
              styleJson(again.style) != styleJson(original.style));
}

INSTANTIATE_TEST_SUITE_P(Techniques, OptionsRoundTrip, ::testing::ValuesIn(test::cases()),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           std::string name = info.param.technique;
                           std::replace(name.begin(), name.end(), '.', '_');
                           return name;
                         });
