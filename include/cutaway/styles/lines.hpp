// cutaway/styles/lines.hpp — the feature lines drawn over every style (src/styles/lines): silhouettes,
// creases, and the options they are drawn with.
//
//   scene.style.lines = cutaway::LineStyle{.creases = false};   // nullopt: no lines
#pragma once

#include <glm/glm.hpp>

#include "cutaway/core/options.hpp"

namespace cutaway {

struct LineStyle {
  bool silhouettes = true;       // object and depth discontinuities
  bool creases = true;           // normal discontinuities within an object
  float creaseAngle = 45.0f;     // degrees
  float depthThreshold = 0.01f;  // relative view-depth jump that counts as a silhouette
  float width = 1.0f;            // pixels
  glm::vec3 color{0.0f};
};
const OptionsSchema& lineStyleSchema();

}  // namespace cutaway
