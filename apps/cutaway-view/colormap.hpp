// Colour maps of the AOV inspector: a frame's float buffers (depths, masks, normals, object
// ids, the cutaway surface) turned into colours to look at, with a stated value range.
//
//   FloatImage depth = …;                           // 1 channel
//   ValueRange r = finiteRange(depth, 0);
//   Rgba8Image shown = applyColormap(depth, Colormap::Turbo, r);
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cutaway/core/image.hpp"

namespace cutaway::view {

enum class Colormap {
  Auto,     // by the buffer: normals, ids, rgb for other 3-channel buffers, else turbo
  Gray,     // first channel, min → black, max → white
  Turbo,    // first channel, Google's Turbo (perceptually ordered rainbow)
  Rgb,      // three channels, each mapped through the one range
  Normals,  // n · 0.5 + 0.5
  Ids,      // integer ids, one distinct colour each; −1 (background) black
};

const std::vector<std::string>& colormapNames();  // in enum order, "auto" first
const char* colormapName(Colormap c);
bool parseColormap(const std::string& name, Colormap& out);
// What Auto means for the buffer `aov` with `channels` channels.
Colormap resolveColormap(Colormap c, const std::string& aov, int channels);

struct ValueRange {
  float min = 0, max = 1;
};
// Smallest and largest finite value over channel `channel` (all channels if −1) of the
// texels whose entry in `include` is non-zero (all texels when `include` is empty); [0, 1]
// when there is no such value.
ValueRange finiteRange(const FloatImage& image, int channel,
                       const std::vector<std::uint8_t>& include = {});

glm::vec3 turbo(float t);  // t in [0, 1]
glm::vec3 idColor(int id);

// Same size and row order as `image`; alpha 255.
Rgba8Image applyColormap(const FloatImage& image, Colormap colormap, ValueRange range);

}  // namespace cutaway::view
