// cutaway/styles/gooch.hpp — the Gooch cool-to-warm shading style's options (Gooch et al. 1998;
// src/styles/gooch).
//
//   scene.style.name = "gooch";
//   scene.style.edit<cutaway::GoochStyle>().alpha = 0.3f;
#pragma once

#include <glm/glm.hpp>

#include "cutaway/core/options.hpp"

namespace cutaway {

struct GoochStyle {
  static constexpr const char* kKey = "gooch";  // under "style" in the scene file  // Gooch et al. 1998
  glm::vec3 cool{0.0f, 0.0f, 0.55f}, warm{0.3f, 0.3f, 0.0f};
  float alpha = 0.25f, beta = 0.5f;  // how much of the object colour enters cool / warm
};
const OptionsSchema& goochSchema();

}  // namespace cutaway
