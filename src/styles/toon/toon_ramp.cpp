#include "styles/toon/toon_ramp.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace cutaway {

std::vector<glm::vec3> toonRampTexels(const ToonStyle& style) {
  return style.ramp;  // already validated: 2–16 tones, each in [0, 1]
}

int toonRampIndex(int rampSize, float nDotL) {
  // GL_NEAREST picks texel floor(u · size) (OpenGL 4.5 §8.14.2), clamped to the edge texels.
  const float u = std::clamp(nDotL, 0.0f, 1.0f);
  return std::clamp(int(std::floor(u * float(rampSize))), 0, rampSize - 1);
}

gl::Texture createToonRampTexture(const ToonStyle& style) {
  const std::vector<glm::vec3> texels = toonRampTexels(style);
  std::vector<std::uint8_t> rgba;
  for (const glm::vec3& c : texels)
    for (int i = 0; i < 4; ++i)
      rgba.push_back(i == 3 ? 255 : std::uint8_t(std::lround(std::clamp(c[i], 0.0f, 1.0f) * 255)));
  gl::Texture texture = gl::Texture::create(GL_TEXTURE_1D);
  glTextureStorage1D(texture.id(), 1, GL_RGBA8, GLsizei(texels.size()));
  glTextureSubImage1D(texture.id(), 0, 0, GLsizei(texels.size()), GL_RGBA, GL_UNSIGNED_BYTE,
                      rgba.data());
  // Hard bands: no interpolation between tones.
  glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  return texture;
}

}  // namespace cutaway
