#include "golden.hpp"

#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "cutaway/core/error.hpp"

namespace cutaway::test {

GoldenResult compareWithGolden(const std::string& name, const Rgba8Image& image, int maxDifference,
                               double meanDifference) {
  const std::filesystem::path golden =
      std::filesystem::path(CUTAWAY_SOURCE_DIR) / "tests" / "golden" / (name + ".png");
  const char* regenerate = std::getenv("CUTAWAY_REGENERATE_GOLDENS");
  if (regenerate && std::string(regenerate) == "1") {
    writePng(golden, image);
    return {true, "regenerated " + golden.string()};
  }
  Rgba8Image expected;
  try {
    expected = readPng(golden);
  } catch (const Error& e) {
    return {false, std::string(e.what()) + " (run scripts/regenerate-goldens)"};
  }
  if (expected.width != image.width || expected.height != image.height)
    return {false, "size " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                       " differs from the golden's " + std::to_string(expected.width) + "x" +
                       std::to_string(expected.height)};
  Rgba8Image diff(image.width, image.height);
  int maxSeen = 0;
  double sum = 0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const int d = std::abs(int(image.pixels[i]) - int(expected.pixels[i]));
    maxSeen = std::max(maxSeen, d);
    sum += d;
    diff.pixels[i] = (i % 4 == 3) ? 255 : std::uint8_t(std::min(255, d * 8));
  }
  const double mean = sum / double(image.pixels.size());
  std::ostringstream message;
  message << name << ": max difference " << maxSeen << " (allowed " << maxDifference << "), mean "
          << mean << " (allowed " << meanDifference << ")";
  const bool ok = maxSeen <= maxDifference && mean <= meanDifference;
  if (!ok) {
    const std::filesystem::path dir = "golden-failures";
    std::filesystem::create_directories(dir);
    writePng(dir / (name + ".actual.png"), image);
    writePng(dir / (name + ".diff.png"), diff);
    message << "; wrote " << std::filesystem::absolute(dir / (name + ".actual.png")).string()
            << " and .diff.png";
  }
  return {ok, message.str()};
}

}  // namespace cutaway::test
