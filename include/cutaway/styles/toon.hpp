// cutaway/styles/toon.hpp — the toon shading style's options (Lake et al. 2000; src/styles/toon).
//
//   scene.style.name = "toon";
//   scene.style.edit<cutaway::ToonStyle>().ramp = {glm::vec3(0.3f), glm::vec3(1.0f)};
#pragma once

#include <glm/glm.hpp>

#include <vector>

#include "cutaway/core/options.hpp"

namespace cutaway {

// Cel shading with a 1-D ramp texture (Lake, Marshall, Harris, Blackstein 2000): the key
// light's max(n·l, 0) picks one of ramp.size() equal intervals, and that tone multiplies the
// object colour; a hard-edged highlight where the Blinn term passes a threshold.
struct ToonStyle {
  static constexpr const char* kKey = "toon";  // under "style" in the scene file
  std::vector<glm::vec3> ramp{glm::vec3(0.45f), glm::vec3(0.75f), glm::vec3(1.0f)};  // dark→light
  bool highlight = true;
  float highlightThreshold = 0.5f;  // Blinn term (n·h)^shininess above which it shows
  glm::vec3 highlightColor{1.0f};   // added, weighted by the object's specular
};
const OptionsSchema& toonSchema();

}  // namespace cutaway
