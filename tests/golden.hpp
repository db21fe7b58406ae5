// Golden-image comparison for rendering tests.
//
// compareWithGolden() loads tests/golden/<name>.png and compares it with a rendered image.
// A pixel is *unexplained* when it differs from the golden by more than `level` (0–255) in
// some channel and its value lies outside the golden's 3×3 neighbourhood range (per channel,
// widened by `level`), or the golden's lies outside the rendered neighbourhood's: so an edge
// that a different rasteriser moves by a pixel, or covers with different MSAA samples (a blend
// of the colours on its two sides), is explained, and a changed colour is not, however small
// its region. The image passes when at most a fraction `maxUnexplained` of the pixels is
// unexplained and the
// mean absolute difference per channel is within `meanDifference`. On failure it writes
// <name>.actual.png and <name>.diff.png (differences amplified 8×, unexplained pixels in
// magenta) into the test's working directory under golden-failures/. With the environment
// variable CUTAWAY_REGENERATE_GOLDENS=1 it writes the golden instead (scripts/regenerate-goldens
// does that for all of them).
#pragma once

#include <string>

#include "cutaway/core/image.hpp"

namespace cutaway::test {

struct GoldenTolerance {
  int level = 16;
  double maxUnexplained = 0.0;  // a fraction of the pixels
  double meanDifference = 0.75;
};

struct ImageDifference {
  int maxDifference = 0;  // per channel, 0–255
  double meanDifference = 0.0;
  int unexplained = 0;  // pixels
  Rgba8Image diff;
};

// The images must have one size.
ImageDifference compareImages(const Rgba8Image& expected, const Rgba8Image& actual, int level);

struct GoldenResult {
  bool ok;
  std::string message;
};

GoldenResult compareWithGolden(const std::string& name, const Rgba8Image& image,
                               const GoldenTolerance& tolerance = {});

}  // namespace cutaway::test
