// Tonal art map construction after Praun, Hoppe, Webb, Finkelstein 2001 §3.2: strokes are
// added to a tone until its mean ink reaches the tone's target, each chosen as the best of a
// few random candidates (the one that adds the most ink for its length, which fills the
// gaps and keeps the tone even), and each is drawn into every darker tone and finer level.
#include "styles/hatching/tonal_art_map.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

namespace cutaway {

namespace {

// SplitMix64 (Steele, Lea, Flood 2014): a small generator with a fixed output sequence on
// every platform, so the TAM (and the goldens drawn with it) does not depend on the
// standard library's distributions.
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  float uniform() {  // [0, 1)
    return float(next() >> 40) * (1.0f / 16777216.0f);
  }
  float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }

 private:
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  std::uint64_t state_;
};

// A straight hatch stroke in texture space ([0, 1)², repeating).
struct Stroke {
  glm::vec2 start, direction;  // direction: unit
  float length;                // texture-space units
  float pressure;              // ink at the stroke's centre line, in (0, 1]
};

constexpr int kCandidates = 6;
constexpr float kJitterRadians = 0.1f;  // ≈ 6°: hand-drawn, not ruled
constexpr float kMinLength = 0.25f, kMaxLength = 0.5f;

// Draws `stroke` into an image `width` texels wide with wrap-around (the TAM tiles), or with
// `dryRun` only measures it; returns the ink added. Ink composes as 1 − (1 − a)(1 − b), like
// layers of translucent ink: commutative and never lighter, so adding the same strokes in any
// order gives the same tone and a superset of strokes gives a darker texel (the nesting).
double drawStroke(std::vector<float>& image, int width, float strokeWidth, const Stroke& stroke,
                  bool dryRun) {
  const glm::vec2 p0 = stroke.start * float(width);
  const float lengthTexels = stroke.length * float(width);
  const glm::vec2 p1 = p0 + stroke.direction * lengthTexels;
  const float half = 0.5f * strokeWidth;
  const glm::vec2 lo = glm::floor(glm::min(p0, p1) - (half + 1.0f));
  const glm::vec2 hi = glm::ceil(glm::max(p0, p1) + (half + 1.0f));
  double added = 0.0;
  for (int y = int(lo.y); y <= int(hi.y); ++y)
    for (int x = int(lo.x); x <= int(hi.x); ++x) {
      const glm::vec2 c(float(x) + 0.5f, float(y) + 0.5f);
      const float t = std::clamp(glm::dot(c - p0, stroke.direction), 0.0f, lengthTexels);
      const float d = glm::length(c - (p0 + t * stroke.direction));
      // Box-filtered coverage of a line `strokeWidth` wide, tapered over the last texel at
      // either end so strokes do not end in a hard square.
      float coverage = std::clamp(half + 0.5f - d, 0.0f, 1.0f);
      coverage *= std::clamp(std::min(t, lengthTexels - t) + 0.5f, 0.0f, 1.0f);
      if (coverage <= 0.0f) continue;
      const int wx = ((x % width) + width) % width, wy = ((y % width) + width) % width;
      float& texel = image[std::size_t(wy) * std::size_t(width) + std::size_t(wx)];
      const float ink = 1.0f - (1.0f - texel) * (1.0f - stroke.pressure * coverage);
      added += double(ink - texel);
      if (!dryRun) texel = ink;
    }
  return added;
}

}  // namespace

double TonalArtMap::meanInk(int level, int tone) const {
  const auto& image = ink(level, tone);
  double sum = 0.0;
  for (float v : image) sum += v;
  return sum / double(image.size());
}

float tonalArtMapTarget(int tone, int tones) {
  return kTonalArtMapDarkest * float(tone + 1) / float(tones);
}

TonalArtMap generateTonalArtMap(const TonalArtMapOptions& options) {
  assert(options.tones >= 1 && options.levels >= 1 && (options.size >> (options.levels - 1)) >= 2);
  TonalArtMap tam;
  tam.tones = options.tones;
  tam.size = options.size;
  tam.levels = options.levels;
  tam.inks.resize(std::size_t(tam.levels));
  std::vector<std::vector<double>> sums(std::size_t(tam.levels),
                                        std::vector<double>(std::size_t(tam.tones), 0.0));
  for (int level = 0; level < tam.levels; ++level)
    tam.inks[std::size_t(level)].assign(
        std::size_t(tam.tones),
        std::vector<float>(std::size_t(tam.width(level)) * std::size_t(tam.width(level)), 0.0f));
  const int crossFrom =
      options.crossHatchFrom >= 0 ? options.crossHatchFrom : tam.tones - tam.tones / 3;
  Random random(options.seed);

  for (int tone = 0; tone < tam.tones; ++tone) {
    const double target = tonalArtMapTarget(tone, tam.tones);
    // Coarsest level first: its strokes are also the finer levels' first strokes (Praun01
    // §3.2), so a stroke does not jump when the mipmap level changes.
    for (int level = tam.levels - 1; level >= 0; --level) {
      const int width = tam.width(level);
      const double texels = double(width) * double(width);
      // Enough for any target below 1: a stroke adds at least a texel's worth of ink while
      // the tone is below its target, so this bound only stops a runaway loop.
      const int maxStrokes = int(texels) * 4;
      for (int n = 0; sums[std::size_t(level)][std::size_t(tone)] / texels < target; ++n) {
        if (n >= maxStrokes) break;
        // Horizontal hatching; the darkest tones add cross-hatching across it.
        const bool cross = tone >= crossFrom && (n % 2 == 1);
        const float base = cross ? 1.5707963f : 0.0f;
        Stroke best{};
        double bestScore = -1.0;
        for (int k = 0; k < kCandidates; ++k) {
          const float angle = base + random.uniform(-kJitterRadians, kJitterRadians);
          const Stroke candidate{{random.uniform(), random.uniform()},
                                 {std::cos(angle), std::sin(angle)},
                                 random.uniform(kMinLength, kMaxLength),
                                 random.uniform(0.85f, 1.0f)};
          const double score = drawStroke(tam.inks[std::size_t(level)][std::size_t(tone)], width,
                                          options.strokeWidth, candidate, true) /
                               double(candidate.length);
          if (score > bestScore) bestScore = score, best = candidate;
        }
        // Nesting: into this tone and every darker one, at this level and every finer one.
        for (int l = level; l >= 0; --l)
          for (int t = tone; t < tam.tones; ++t)
            sums[std::size_t(l)][std::size_t(t)] +=
                drawStroke(tam.inks[std::size_t(l)][std::size_t(t)], tam.width(l),
                           options.strokeWidth, best, false);
      }
    }
  }
  return tam;
}

gl::Texture createTonalArtMapTexture(const TonalArtMap& tam) {
  gl::Texture texture = gl::Texture::create(GL_TEXTURE_2D_ARRAY);
  const GLuint id = texture.id();
  glTextureStorage3D(id, tam.levels, GL_R8, tam.size, tam.size, tam.tones);
  std::vector<std::uint8_t> bytes;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);  // R8 rows of the small levels are not 4-aligned
  for (int level = 0; level < tam.levels; ++level) {
    const int width = tam.width(level);
    for (int tone = 0; tone < tam.tones; ++tone) {
      const auto& ink = tam.ink(level, tone);
      bytes.resize(ink.size());
      for (std::size_t i = 0; i < ink.size(); ++i)
        bytes[i] = std::uint8_t(std::lround(std::clamp(ink[i], 0.0f, 1.0f) * 255.0f));
      glTextureSubImage3D(id, level, 0, 0, tone, width, width, 1, GL_RED, GL_UNSIGNED_BYTE,
                          bytes.data());
    }
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);  // the GL default, which other uploads assume
  // The drawn pyramid ends at size >> (levels − 1): sampling stops there instead of at
  // GL-generated levels, which would average the strokes into grey.
  glTextureParameteri(id, GL_TEXTURE_BASE_LEVEL, 0);
  glTextureParameteri(id, GL_TEXTURE_MAX_LEVEL, tam.levels - 1);
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return texture;
}

}  // namespace cutaway
