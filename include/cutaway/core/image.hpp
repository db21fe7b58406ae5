// cutaway/core/image.hpp — CPU images: 8-bit RGBA for final pictures, float images with
// 1 or 3 channels for intermediate buffers (AOVs), and their file formats (PNG, PFM).
//
// Rows are stored top to bottom (as in PNG). Buffers read back from OpenGL are bottom-up;
// `flipVertically()` converts.
//
//   cutaway::FloatImage depth(640, 480, 1);
//   depth.at(10, 20)[0] = 0.5f;
//   cutaway::writePfm("depth.pfm", depth);
#pragma once

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <vector>

namespace cutaway {

struct Rgba8Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 4, rows top to bottom

  Rgba8Image() = default;
  Rgba8Image(int w, int h) : width(w), height(h), pixels(std::size_t(w) * h * 4, 0) {}
  std::uint8_t* at(int x, int y) { return &pixels[(std::size_t(y) * width + x) * 4]; }
  const std::uint8_t* at(int x, int y) const { return &pixels[(std::size_t(y) * width + x) * 4]; }
  void flipVertically();
};

struct FloatImage {
  int width = 0, height = 0, channels = 0;
  std::vector<float> data;  // width * height * channels, rows top to bottom

  FloatImage() = default;
  FloatImage(int w, int h, int c)
      : width(w), height(h), channels(c), data(std::size_t(w) * h * c) {}
  float* at(int x, int y) { return &data[(std::size_t(y) * width + x) * channels]; }
  const float* at(int x, int y) const { return &data[(std::size_t(y) * width + x) * channels]; }
  void flipVertically();
};

// PNG, 8-bit RGBA. Written to a temporary file and renamed; errors throw cutaway::Error.
void writePng(const std::filesystem::path& path, const Rgba8Image& image);
// Whether `path` ends in ".png" (any case): the one format the programs write pictures in.
bool isPngName(const std::filesystem::path& path);
// The same into a stream; errors name `path`.
void writePng(std::ostream& os, const Rgba8Image& image, const std::filesystem::path& path);
// Reads any PNG (gray, RGB, palette, 8 or 16 bit) converted to 8-bit RGBA.
Rgba8Image readPng(const std::filesystem::path& path);

// A PNG's grey levels in [0, 1] with the file's precision: 8-bit files as stored (value / 255),
// 16-bit files as stored (value / 65535); colour files are converted to grey by libpng. For
// height and offset maps. One channel, rows top to bottom.
FloatImage readPngGray(const std::filesystem::path& path);

// Bilinear sample of channel `c` at texture coordinate uv with wrap-around, as OpenGL's
// GL_LINEAR + GL_REPEAT does: texel centres at (i + 0.5) / size, and uv (0, 0) at the
// first stored row (upload the image as it is stored, so row 0 is the texture's t = 0).
float sampleRepeat(const FloatImage& image, float u, float v, int c = 0);

// Portable float map: 1 channel ("Pf") or 3 channels ("PF"), little-endian, rows stored
// bottom to top on disk as the format requires.
void writePfm(const std::filesystem::path& path, const FloatImage& image);
// The same into a stream; errors name `path`.
void writePfm(std::ostream& os, const FloatImage& image, const std::filesystem::path& path);
FloatImage readPfm(const std::filesystem::path& path);

}  // namespace cutaway
