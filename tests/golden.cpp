#include "golden.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "cutaway/core/error.hpp"

namespace cutaway::test {

namespace {

// Whether each channel of `value` lies within the [min, max] of that channel over `image`'s
// 3×3 neighbourhood of (x, y), widened by `level`.
bool withinNeighbourhood(const Rgba8Image& image, int x, int y, const std::uint8_t* value,
                         int level) {
  for (int c = 0; c < 4; ++c) {
    int lo = 255, hi = 0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int qx = std::clamp(x + dx, 0, image.width - 1);
        const int qy = std::clamp(y + dy, 0, image.height - 1);
        const int v = image.at(qx, qy)[c];
        lo = std::min(lo, v), hi = std::max(hi, v);
      }
    if (value[c] + level < lo || value[c] > hi + level) return false;
  }
  return true;
}

}  // namespace

ImageDifference compareImages(const Rgba8Image& expected, const Rgba8Image& actual, int level) {
  ImageDifference result;
  result.diff = Rgba8Image(actual.width, actual.height);
  double sum = 0;
  for (int y = 0; y < actual.height; ++y)
    for (int x = 0; x < actual.width; ++x) {
      const std::uint8_t *a = actual.at(x, y), *e = expected.at(x, y);
      std::uint8_t* d = result.diff.at(x, y);
      int largest = 0;
      for (int c = 0; c < 4; ++c) {
        const int delta = std::abs(int(a[c]) - int(e[c]));
        largest = std::max(largest, delta);
        sum += delta;
        d[c] = c == 3 ? 255 : std::uint8_t(std::min(255, delta * 8));
      }
      result.maxDifference = std::max(result.maxDifference, largest);
      if (largest > level && !(withinNeighbourhood(expected, x, y, a, level) &&
                               withinNeighbourhood(actual, x, y, e, level))) {
        ++result.unexplained;
        d[0] = 255, d[1] = 0, d[2] = 255;
      }
    }
  result.meanDifference = sum / double(std::max<std::size_t>(1, actual.pixels.size()));
  return result;
}

GoldenResult compareWithGolden(const std::string& name, const Rgba8Image& image,
                               const GoldenTolerance& tolerance) {
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
  const ImageDifference d = compareImages(expected, image, tolerance.level);
  std::ostringstream message;
  const int allowed = int(tolerance.maxUnexplained * double(image.width) * double(image.height));
  message << name << ": " << d.unexplained << " unexplained pixels (allowed " << allowed
          << "), mean difference " << d.meanDifference << " (allowed " << tolerance.meanDifference
          << "), max difference " << d.maxDifference;
  const bool ok = d.unexplained <= allowed && d.meanDifference <= tolerance.meanDifference;
  if (!ok) {
    const std::filesystem::path dir = "golden-failures";
    std::filesystem::create_directories(dir);
    writePng(dir / (name + ".actual.png"), image);
    writePng(dir / (name + ".diff.png"), d.diff);
    message << "; wrote " << std::filesystem::absolute(dir / (name + ".actual.png")).string()
            << " and .diff.png";
  }
  return {ok, message.str()};
}

}  // namespace cutaway::test
