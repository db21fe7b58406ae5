// Golden-image comparison for rendering tests.
//
// compareWithGolden() loads tests/golden/<name>.png and compares per channel (0–255):
// the largest difference must stay within `maxDifference` and the mean within
// `meanDifference`. On failure it writes <name>.actual.png and <name>.diff.png (differences
// amplified 8×) into the test's working directory under golden-failures/. With the
// environment variable CUTAWAY_REGENERATE_GOLDENS=1 it writes the golden instead
// (scripts/regenerate-goldens does that for all of them).
#pragma once

#include <string>

#include "cutaway/core/image.hpp"

namespace cutaway::test {

struct GoldenResult {
  bool ok;
  std::string message;
};

GoldenResult compareWithGolden(const std::string& name, const Rgba8Image& image, int maxDifference,
                               double meanDifference);

}  // namespace cutaway::test
