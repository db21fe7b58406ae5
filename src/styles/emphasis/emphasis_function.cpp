// Burns11 §3.3.1's emphasis by importance, mirrored line by line in emphasis.glsl.
#include "cutaway/styles/emphasis.hpp"

namespace cutaway {

float emphasisImportance(bool objectOfInterest, float importance) {
  return objectOfInterest ? 1.0f : importance;
}

float intensity(const glm::vec3& c) {
  return glm::dot(c, glm::vec3(0.2126f, 0.7152f, 0.0722f));
}

glm::vec3 emphasize(const EmphasisStyle& e, const glm::vec3& base, const glm::vec3& shaded,
                    float importance) {
  if (importance < e.linesOnlyBelow) return e.paper;
  // Eqs. 3.3–3.4 folded: c_suppressed = c_shaded + E_s (1 − I)(c − c_shaded).
  const glm::vec3 suppressed = glm::mix(shaded, base, e.shading * (1.0f - importance));
  // Eqs. 3.1–3.2 folded: c_muted = c + E_c (1 − I)(c_i − c).
  return glm::mix(suppressed, glm::vec3(intensity(suppressed)), e.color * (1.0f - importance));
}

}  // namespace cutaway
