#include "cutaway/core/image.hpp"

#include <png.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>

#include "cutaway/core/atomic_file.hpp"
#include "cutaway/core/error.hpp"

namespace cutaway {

namespace {

template <typename T>
void flipRows(std::vector<T>& v, std::size_t rowLength, int height) {
  for (int y = 0; y < height / 2; ++y) {
    std::swap_ranges(v.begin() + std::ptrdiff_t(y * rowLength),
                     v.begin() + std::ptrdiff_t((y + 1) * rowLength),
                     v.begin() + std::ptrdiff_t((height - 1 - y) * rowLength));
  }
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

}  // namespace

void Rgba8Image::flipVertically() {
  flipRows(pixels, std::size_t(width) * 4, height);
}
void FloatImage::flipVertically() {
  flipRows(data, std::size_t(width) * channels, height);
}

void writePng(const std::filesystem::path& path, const Rgba8Image& image) {
  writeFileAtomically(path, [&](std::ostream& os) { writePng(os, image, path); });
}

bool isPngName(const std::filesystem::path& path) {
  std::string suffix = path.extension().string();
  for (char& c : suffix) c = char(std::tolower(static_cast<unsigned char>(c)));
  return suffix == ".png";
}

void writePng(std::ostream& os, const Rgba8Image& image, const std::filesystem::path& path) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = png_uint_32(image.width);
  png.height = png_uint_32(image.height);
  png.format = PNG_FORMAT_RGBA;
  const auto fail = [&] {
    std::string reason = png.message;
    png_image_free(&png);
    throw Error(path.string(), "", "cannot write PNG: " + reason);
  };
  // Encoded in memory (libpng's simplified API: the size first, then the bytes).
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&png, nullptr, &size, 0, image.pixels.data(), 0, nullptr)) fail();
  std::vector<char> bytes(size);
  if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, image.pixels.data(), 0, nullptr))
    fail();
  os.write(bytes.data(), std::streamsize(size));
}

namespace {

// libpng's simplified reader: the header, then the pixels in the format `choose` sets.
template <class Choose>
std::vector<std::uint8_t> readPngPixels(const std::filesystem::path& path, png_image& png,
                                        Choose choose) {
  png = png_image{};
  png.version = PNG_IMAGE_VERSION;
  // libpng says "Read Error" for a file too short for its signature: said plainly here.
  if (std::error_code ec; std::filesystem::is_regular_file(path, ec)) {
    std::ifstream in(path, std::ios::binary);
    char signature[8] = {};
    in.read(signature, sizeof signature);
    const std::size_t read = std::size_t(in.gcount());
    if (read == 0) throw Error(path.string(), "", "cannot read PNG: the file is empty");
    if (png_sig_cmp(reinterpret_cast<png_const_bytep>(signature), 0, read) != 0)
      throw Error(path.string(), "", "cannot read PNG: not a PNG file (no PNG signature)");
    if (read < sizeof signature)
      throw Error(path.string(), "", "cannot read PNG: the file ends within its signature");
  }
  if (!png_image_begin_read_from_file(&png, path.c_str())) {
    std::string reason = png.message;
    png_image_free(&png);
    if (reason == "Read Error") reason = "the file ends early (truncated)";
    throw Error(path.string(), "", "cannot read PNG: " + reason);
  }
  // A header may claim any size: one of 69 bytes claiming 46000 × 46000 had 2 GB allocated
  // before its data ran out. Deflate packs at most 1032 bytes into one, and a 1-bit image
  // holds 8 pixels a byte; the file's format as libpng's simplified API gives it counts
  // 8 bits a sample and more.
  std::error_code ec;
  const std::uintmax_t fileBytes = std::filesystem::file_size(path, ec);
  if (!ec && double(PNG_IMAGE_SIZE(png)) > 8.0 * 1032.0 * double(fileBytes) + 65536.0) {
    const std::string size = std::to_string(png.width) + " × " + std::to_string(png.height);
    png_image_free(&png);
    throw Error(path.string(), "",
                "the header claims " + size + " pixels, more than a file of " +
                    std::to_string(fileBytes) + " bytes can hold");
  }
  choose(png);
  std::vector<std::uint8_t> bytes(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, bytes.data(), 0, nullptr)) {
    std::string reason = png.message;
    png_image_free(&png);
    if (reason == "Read Error") reason = "the file ends early (truncated)";
    throw Error(path.string(), "", "cannot decode PNG: " + reason);
  }
  return bytes;
}

}  // namespace

Rgba8Image readPng(const std::filesystem::path& path) {
  png_image png;
  std::vector<std::uint8_t> bytes =
      readPngPixels(path, png, [](png_image& p) { p.format = PNG_FORMAT_RGBA; });
  Rgba8Image image(int(png.width), int(png.height));
  image.pixels = std::move(bytes);
  return image;
}

FloatImage readPngGray(const std::filesystem::path& path) {
  png_image png;
  bool sixteen = false;
  const std::vector<std::uint8_t> bytes = readPngPixels(path, png, [&](png_image& p) {
    // libpng marks 16-bit files linear; reading them as 16-bit linear grey keeps every level.
    sixteen = (p.format & PNG_FORMAT_FLAG_LINEAR) != 0;
    p.format = sixteen ? PNG_FORMAT_LINEAR_Y : PNG_FORMAT_GRAY;
  });
  FloatImage image(int(png.width), int(png.height), 1);
  for (std::size_t i = 0; i < image.data.size(); ++i) {
    if (sixteen) {
      std::uint16_t v;
      std::memcpy(&v, &bytes[2 * i], 2);
      image.data[i] = float(v) / 65535.0f;
    } else {
      image.data[i] = float(bytes[i]) / 255.0f;
    }
  }
  return image;
}

float sampleRepeat(const FloatImage& image, float u, float v, int c) {
  const float x = u * float(image.width) - 0.5f, y = v * float(image.height) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float ax = x - fx, ay = y - fy;
  auto texel = [&](float i, float j) {
    const int col = int(i - float(image.width) * std::floor(i / float(image.width)));
    const int row = int(j - float(image.height) * std::floor(j / float(image.height)));
    return image.at(col, row)[c];
  };
  const float bottom = texel(fx, fy) * (1.0f - ax) + texel(fx + 1, fy) * ax;
  const float top = texel(fx, fy + 1) * (1.0f - ax) + texel(fx + 1, fy + 1) * ax;
  return bottom * (1.0f - ay) + top * ay;
}

void writePfm(const std::filesystem::path& path, const FloatImage& image) {
  writeFileAtomically(path, [&](std::ostream& os) { writePfm(os, image, path); });
}

void writePfm(std::ostream& os, const FloatImage& image, const std::filesystem::path& path) {
  if (image.channels != 1 && image.channels != 3)
    throw Error(path.string(), "",
                "PFM holds 1 or 3 channels, not " + std::to_string(image.channels));
  // Negative scale marks little-endian data.
  os << (image.channels == 3 ? "PF" : "Pf") << "\n"
     << image.width << " " << image.height << "\n-1.0\n";
  const std::size_t row = std::size_t(image.width) * image.channels;
  for (int y = image.height - 1; y >= 0; --y) {
    const float* p = image.data.data() + std::size_t(y) * row;
    static_assert(std::endian::native == std::endian::little);
    os.write(reinterpret_cast<const char*>(p), std::streamsize(row * sizeof(float)));
  }
}

FloatImage readPfm(const std::filesystem::path& path) {
  std::ifstream is(path, std::ios::binary);
  if (!is) throw Error(path.string(), "", "cannot open PFM");
  std::string magic;
  int w = 0, h = 0;
  double scale = 0;
  is >> magic >> w >> h >> scale;
  if (!is || (magic != "PF" && magic != "Pf"))
    throw Error(path.string(), "header", "not a PFM file (expected PF or Pf)");
  if (w <= 0 || h <= 0 || w > 65536 || h > 65536)
    throw Error(path.string(), "header",
                "invalid size " + std::to_string(w) + "x" + std::to_string(h));
  if (scale >= 0) throw Error(path.string(), "header", "big-endian PFM is not supported");
  is.get();  // the single whitespace character after the scale
  FloatImage image(w, h, magic == "PF" ? 3 : 1);
  const std::size_t row = std::size_t(w) * image.channels;
  for (int y = h - 1; y >= 0; --y) {
    is.read(reinterpret_cast<char*>(image.data.data() + std::size_t(y) * row),
            std::streamsize(row * sizeof(float)));
    if (!is) throw Error(path.string(), "row " + std::to_string(h - 1 - y), "truncated PFM");
  }
  return image;
}

}  // namespace cutaway
