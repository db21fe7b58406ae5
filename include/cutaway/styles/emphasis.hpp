// cutaway/styles/emphasis.hpp — emphasis by importance for every style (Burns11 §3.3.1,
// src/styles/emphasis): less important objects desaturated (eqs. 3.1–3.2), less shaded
// (eqs. 3.3–3.4), or drawn as lines on paper (§3.3.1.3).
//
//   scene.style.emphasis = {.color = 1.0f, .shading = 0.6f};   // E_c, E_s
#pragma once

#include <glm/glm.hpp>

#include "cutaway/core/options.hpp"

namespace cutaway {

struct EmphasisStyle {
  float color = 0.0f;    // E_c of eq. 3.1: 1 greys the least important objects fully, 0 nothing
  float shading = 0.0f;  // E_s of eq. 3.3: 1 leaves the least important objects unshaded, 0 nothing
  // §3.3.1.3: objects of importance below this are drawn as a line drawing (their feature
  // lines over the paper colour); 0: none.
  float linesOnlyBelow = 0.0f;
  glm::vec3 paper{1.0f};
};
const OptionsSchema& emphasisStyleSchema();

// The importance emphasis uses: the hybrid model of §3.2, where an object of interest is of
// binary high importance (1) and every other object has its continuous importance.
float emphasisImportance(bool objectOfInterest, float importance);

// The greyscale intensity c_i of eq. 3.1: Rec. 709 luma of the colour.
float intensity(const glm::vec3& c);

// The colour of a fragment with base colour `base` (the material's, unshaded), shaded by the
// style to `shaded`, of importance I: shading suppressed (eqs. 3.3–3.4), then desaturated
// (eqs. 3.1–3.2); the paper colour below linesOnlyBelow. The mirror of emphasis.glsl.
glm::vec3 emphasize(const EmphasisStyle& e, const glm::vec3& base, const glm::vec3& shaded,
                    float importance);

}  // namespace cutaway
