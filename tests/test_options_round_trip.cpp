// Every option of every schema survives the scene file: each technique's options changed at
// once (technique_scenes.hpp's scenes, every value moved inside its range), written back into
// the scene file by SceneDocument and read again by the scene reader, are the values set.
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
  std::vector<const SceneOption*> changed;
  for (const SceneOption& o : sceneOptions()) {
    if (o.technique != c.technique || !o.spec.inFile) continue;
    if (o.spec.applies && !o.spec.applies(&current)) continue;
    if (o.spec.type == OptionSpec::Type::Text) continue;  // style.name: the scene's choice
    // Away from the file's value (the test's setup may already have moved it).
    o.spec.set(&current, test::changed(o.spec, o.spec.get(&original)));
    changed.push_back(&o);
  }
  ASSERT_FALSE(changed.empty());
  const std::filesystem::path saved = test::scratchPath("round-trip", "saved.json");
  SceneDocument::load(file).save(original, current, saved);
  const Scene again = loadScene(saved);
  // Each option as set, not as it was: read back through the scene reader.
  for (const SceneOption* o : changed) {
    const std::string set = formatOptionValue(o->spec.get(&current));
    EXPECT_EQ(formatOptionValue(o->spec.get(&again)), set) << o->path;
    EXPECT_NE(formatOptionValue(o->spec.get(&original)), set) << o->path << " did not change";
  }
}

INSTANTIATE_TEST_SUITE_P(Techniques, OptionsRoundTrip, ::testing::ValuesIn(test::cases()),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           std::string name = info.param.technique;
                           std::replace(name.begin(), name.end(), '.', '_');
                           return name;
                         });
