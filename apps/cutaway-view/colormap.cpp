#include "colormap.hpp"

#include <algorithm>
#include <cmath>

namespace cutaway::view {

const std::vector<std::string>& colormapNames() {
  static const std::vector<std::string> names{"auto", "gray", "turbo", "rgb", "normals", "ids"};
  return names;
}

const char* colormapName(Colormap c) {
  return colormapNames()[std::size_t(c)].c_str();
}

bool parseColormap(const std::string& name, Colormap& out) {
  const auto& names = colormapNames();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) return false;
  out = Colormap(it - names.begin());
  return true;
}

Colormap resolveColormap(Colormap c, const std::string& aov, int channels) {
  if (c != Colormap::Auto) return c;
  if (aov == "normal") return Colormap::Normals;
  if (aov == "objectId") return Colormap::Ids;
  if (aov == "color") return Colormap::Rgb;
  return channels == 3 ? Colormap::Rgb : Colormap::Turbo;
}

ValueRange finiteRange(const FloatImage& image, int channel,
                       const std::vector<std::uint8_t>& include) {
  float lo = INFINITY, hi = -INFINITY;
  const std::size_t channels = std::size_t(image.channels);
  for (std::size_t i = 0; i < image.data.size(); ++i) {
    if (channel >= 0 && int(i % channels) != channel) continue;
    if (!include.empty() && !include[i / channels]) continue;
    const float v = image.data[i];
    if (!std::isfinite(v)) continue;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (!(lo <= hi)) return {0.0f, 1.0f};
  return {lo, hi};
}

glm::vec3 turbo(float t) {
  // The polynomial fit of Turbo published with it (A. Mikhailov, Google AI blog, 2019).
  t = std::clamp(t, 0.0f, 1.0f);
  const glm::vec4 v4(1.0f, t, t * t, t * t * t);
  const glm::vec2 v2 = glm::vec2(v4.z, v4.w) * v4.z;
  const glm::vec4 r4(0.13572138f, 4.61539260f, -42.66032258f, 132.13108234f);
  const glm::vec4 g4(0.09140261f, 2.19418839f, 4.84296658f, -14.18503333f);
  const glm::vec4 b4(0.10667330f, 12.64194608f, -60.58204836f, 110.36276771f);
  const glm::vec2 r2(-152.94239396f, 59.28637943f), g2(4.27729857f, 2.82956604f),
      b2(-89.90310912f, 27.34824973f);
  return glm::clamp(
      glm::vec3(glm::dot(v4, r4) + glm::dot(v2, r2), glm::dot(v4, g4) + glm::dot(v2, g2),
                glm::dot(v4, b4) + glm::dot(v2, b2)),
      0.0f, 1.0f);
}

glm::vec3 idColor(int id) {
  if (id < 0) return glm::vec3(0.0f);
  // Golden-ratio hue steps keep neighbouring ids far apart in hue.
  const float hue = std::fmod(float(id) * 0.618034f, 1.0f);
  const glm::vec3 k = glm::abs(
      glm::fract(glm::vec3(hue) + glm::vec3(1.0f, 2.0f / 3, 1.0f / 3)) * 6.0f - glm::vec3(3.0f));
  const float saturation = 0.65f, value = 0.5f + 0.4f * float((id * 7) % 3) / 2.0f;
  return value * glm::mix(glm::vec3(1.0f), glm::clamp(k - 1.0f, 0.0f, 1.0f), saturation);
}

Rgba8Image applyColormap(const FloatImage& image, Colormap colormap, ValueRange range) {
  Rgba8Image out(image.width, image.height);
  const float scale = range.max > range.min ? 1.0f / (range.max - range.min) : 0.0f;
  const auto unit = [&](float v) {
    return std::isfinite(v) ? std::clamp((v - range.min) * scale, 0.0f, 1.0f) : 0.0f;
  };
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float* v = image.at(x, y);
      const int c = image.channels;
      glm::vec3 rgb(0.0f);
      switch (colormap) {
        case Colormap::Auto:
        case Colormap::Turbo:
          rgb = turbo(unit(v[0]));
          break;
        case Colormap::Gray:
          rgb = glm::vec3(unit(v[0]));
          break;
        case Colormap::Rgb:
          rgb = c >= 3 ? glm::vec3(unit(v[0]), unit(v[1]), unit(v[2])) : glm::vec3(unit(v[0]));
          break;
        case Colormap::Normals:
          rgb = c >= 3 ? glm::clamp(glm::vec3(v[0], v[1], v[2]) * 0.5f + 0.5f, 0.0f, 1.0f)
                       : glm::vec3(unit(v[0]));
          if (c >= 3 && v[0] == 0 && v[1] == 0 && v[2] == 0) rgb = glm::vec3(0.0f);  // background
          break;
        case Colormap::Ids:
          rgb = idColor(std::isfinite(v[0]) ? int(std::lround(v[0])) : -1);
          break;
      }
      std::uint8_t* p = out.at(x, y);
      for (int i = 0; i < 3; ++i) p[i] = std::uint8_t(std::lround(rgb[i] * 255.0f));
      p[3] = 255;
    }
  return out;
}

}  // namespace cutaway::view
