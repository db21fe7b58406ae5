// cutaway/styles/shadows.hpp — shadows from the key light for every style (src/styles/shadows).
//
//   scene.style.shadows.enabled = true;
#pragma once

#include <glm/glm.hpp>

#include "cutaway/core/options.hpp"

namespace cutaway {

// A shadow map from the key light (the first light), usable with every style.
struct ShadowStyle {
  bool enabled = false;
  int size = 2048;         // texels per side
  float bias = 0.005f;     // constant bias towards the light, fraction of the scene's radius
  float slopeBias = 2.0f;  // glPolygonOffset factor: bias × the caster's depth slope
  int pcfRadius = 1;       // (2r + 1)² bilinear comparison taps
};
const OptionsSchema& shadowStyleSchema();

}  // namespace cutaway
