// Tonal art maps for real-time hatching (Praun, Hoppe, Webb, Finkelstein 2001, "Real-time
// hatching", §3): a sequence of hatch textures of increasing tone, each with a mipmap
// pyramid whose levels are drawn with strokes of the same width in texels, so that strokes
// keep their width on screen at any distance. Strokes are added tone by tone and, within a
// tone, from the coarsest level to the finest, and every stroke is kept in all darker tones
// and all finer levels: the nesting ("stroke coherence") that lets the fragment shader blend
// two neighbouring tones without strokes appearing or vanishing.
//
//   cutaway::TonalArtMap tam = cutaway::generateTonalArtMap({.tones = 6});
//   float ink = tam.ink(0, 5)[y * tam.width(0) + x];   // finest level, darkest tone
#pragma once

#include <cstdint>
#include <vector>

#include "cutaway/gl/objects.hpp"

namespace cutaway {

struct TonalArtMapOptions {
  int tones = 6;   // lightest (0) to darkest (tones − 1)
  int size = 256;  // texels per side of the finest level (a power of two)
  int levels = 6;  // mipmap levels drawn, size down to size >> (levels − 1)
  std::uint32_t seed = 1;
  float strokeWidth = 1.0f;  // texels, at every level (Praun01 §3.2)
  // Tones from this one on add cross-hatching strokes across the first direction.
  int crossHatchFrom = -1;  // −1: the darker third of the tones
};

struct TonalArtMap {
  int tones = 0, size = 0, levels = 0;
  // inks[level][tone]: ink coverage in [0, 1] per texel (0 = paper), rows of width(level).
  std::vector<std::vector<std::vector<float>>> inks;

  int width(int level) const { return size >> level; }
  const std::vector<float>& ink(int level, int tone) const {
    return inks[std::size_t(level)][std::size_t(tone)];
  }
  double meanInk(int level, int tone) const;
};

// The mean ink a tone is built to (Praun01 §3.2: strokes are added until the tone's average
// reaches its target): evenly spaced, the darkest at kTonalArtMapDarkest.
constexpr float kTonalArtMapDarkest = 0.8f;
float tonalArtMapTarget(int tone, int tones);

TonalArtMap generateTonalArtMap(const TonalArtMapOptions& options);

// The TAM as a mipmapped GL_R8 2-D texture array (one layer per tone), trilinear, repeating.
gl::Texture createTonalArtMapTexture(const TonalArtMap& tam);

}  // namespace cutaway
