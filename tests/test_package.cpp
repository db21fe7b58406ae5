// The library as a CMake package: this build installed into a staging prefix, the consumer
// project (examples/consumer) configured against it with find_package(Cutaway), built, and
// its two programs run: a scene rendered through the Renderer with an option set by its path,
// and an application's own OpenGL scene opened by AdaptiveCutawaySurface; and the consumer
// configured against the build folder itself.
#include <gtest/gtest.h>

#include <filesystem>

#include "cutaway/core/image.hpp"
#include "run_command.hpp"

using namespace cutaway;
namespace fs = std::filesystem;

namespace {

std::string quoted(const fs::path& p) {
  return "'" + p.string() + "'";
}

void run(const std::string& command) {
  const test::Result r = test::runCommand(command);
  ASSERT_EQ(r.exitCode, 0) << command << "\n" << r.out << r.err;
}

const std::uint8_t* pixel(const Rgba8Image& image, float x, float y) {
  return image.at(int(x * float(image.width)), int(y * float(image.height)));
}

}  // namespace

TEST(Package, AConsumerProjectFindsBuildsAndRendersWithIt) {
  const fs::path prefix = test::scratchPath("package", "prefix");
  const fs::path build = test::scratchPath("package", "consumer");
  const std::string cmake = quoted(CUTAWAY_CMAKE);
  ASSERT_NO_FATAL_FAILURE(run(cmake + " --install " + quoted(CUTAWAY_BINARY_DIR) + " --prefix " +
                              quoted(prefix)));
  EXPECT_TRUE(fs::exists(prefix / "lib/cmake/Cutaway/CutawayConfig.cmake"));
  EXPECT_TRUE(fs::exists(prefix / "lib/cmake/Cutaway/CutawayConfigVersion.cmake"));
  EXPECT_TRUE(fs::exists(prefix / "include/cutaway/render/renderer.hpp"));
  // The consumer is compiled the way this build was (sanitizer flags included), else it
  // could not link the library.
  ASSERT_NO_FATAL_FAILURE(run(cmake + " -S " + quoted(CUTAWAY_SOURCE_DIR "/examples/consumer") +
                              " -B " + quoted(build) + " -G Ninja -DCMAKE_PREFIX_PATH=" +
                              quoted(prefix) + " -DCMAKE_BUILD_TYPE=" CUTAWAY_BUILD_TYPE
                              " '-DCMAKE_CXX_FLAGS=" CUTAWAY_CXX_FLAGS
                              "' '-DCMAKE_EXE_LINKER_FLAGS=" CUTAWAY_LINKER_FLAGS "'"));
  ASSERT_NO_FATAL_FAILURE(run(cmake + " --build " + quoted(build)));

  // The engine's adaptive cutaway with options set by their paths: the picture the CLI makes
  // with the same --set options, pixel for pixel.
  const std::string options = " cutters.adaptive.angle=20 style.lines=false";
  const fs::path engine = build / "engine.png", cli = build / "engine-cli.png";
  ASSERT_NO_FATAL_FAILURE(run(quoted(build / "render-scene") + " " +
                              quoted(CUTAWAY_SOURCE_DIR "/examples/engine-cutaway.json") + " " +
                              quoted(engine) + options));
  ASSERT_NO_FATAL_FAILURE(run(quoted(CUTAWAY_BINARY) + " render " +
                              quoted(CUTAWAY_SOURCE_DIR "/examples/engine-cutaway.json") + " -o " +
                              quoted(cli) + " --set cutters.adaptive.angle=20 --set style.lines=false"));
  EXPECT_EQ(readPng(engine).pixels, readPng(cli).pixels);
  const test::Result bad = test::runCommand(quoted(build / "render-scene") + " " +
                                            quoted(CUTAWAY_SOURCE_DIR "/examples/engine.json") +
                                            " " + quoted(build / "bad.png") +
                                            " cutters.adaptive.angle=200");
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_NE(bad.err.find("cutters.adaptive.angle"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(build / "bad.png"));

  // The application's ball inside a closed box: seen at the image centre through the
  // opening the cutaway surface made; the box's outside still at its left edge.
  const fs::path own = build / "own-gl.png";
  ASSERT_NO_FATAL_FAILURE(run(quoted(build / "own-gl") + " " + quoted(own)));
  const Rgba8Image image = readPng(own);
  const std::uint8_t* centre = pixel(image, 0.5f, 0.5f);
  EXPECT_GT(centre[0], 2 * centre[1]) << "the ball (red) is not visible at the centre";
  const std::uint8_t* side = pixel(image, 0.2f, 0.5f);
  EXPECT_EQ(side[0], side[1]) << "the box (grey) is missing left of the ball";
  EXPECT_LT(side[0], 200);

  // The build folder is a package too: its CutawayConfig.cmake found its targets (it
  // included a CutawayTargets.cmake that only the install wrote).
  ASSERT_NO_FATAL_FAILURE(run(cmake + " -S " + quoted(CUTAWAY_SOURCE_DIR "/examples/consumer") +
                              " -B " + quoted(test::scratchPath("package", "from-build")) +
                              " -G Ninja -DCutaway_DIR=" + quoted(CUTAWAY_BINARY_DIR) +
                              " -DCMAKE_BUILD_TYPE=" CUTAWAY_BUILD_TYPE));
}
