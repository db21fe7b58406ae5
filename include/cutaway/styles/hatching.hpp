// cutaway/styles/hatching.hpp — the hatching style's options (Praun et al. 2001; src/styles/hatching).
//
//   scene.style.name = "hatching";
//   scene.style.edit<cutaway::HatchingStyle>().tones = 8;
#pragma once

#include <glm/glm.hpp>

#include "cutaway/core/options.hpp"

namespace cutaway {

// Tonal art maps (Praun, Hoppe, Webb, Finkelstein 2001), generated procedurally at start-up.
struct HatchingStyle {
  static constexpr const char* kKey = "hatching";  // under "style" in the scene file
  int tones = 6;                        // TAM tones, lightest to darkest (2–12)
  glm::vec3 paper{1.0f, 0.98f, 0.93f};  // colour between strokes
  glm::vec3 ink{0.08f, 0.08f, 0.12f};   // stroke colour
  float tint = 0.35f;                   // how much the object colour tints the paper, in [0, 1]
  float scale = 0.4f;  // hatch tile size as a fraction of the scene's bounding radius
  unsigned seed = 1;   // stroke placement
  // The surface's lightness from the key light: Lambert max(n·l, 0), or Gooch's (1 + n·l)/2.
  enum class Lightness { Lambert, Gooch } lightness = Lightness::Lambert;
};
const OptionsSchema& hatchingSchema();

}  // namespace cutaway
