// cutaway/core/unit_vector.hpp — directions given at any length.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>

#include <glm/glm.hpp>

namespace cutaway {

// `v` at unit length, or nothing for a zero or non-finite vector. Divided by its largest
// component first, so that no square overflows or underflows whatever its length (a float's
// squared length overflows past 1e19 and underflows below 1e-19).
inline std::optional<glm::vec3> unitVector(const glm::dvec3& v) {
  const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (!(largest > 0.0) || !std::isfinite(largest)) return std::nullopt;
  const glm::dvec3 scaled = v / largest;
  return glm::vec3(scaled / glm::length(scaled));
}

}  // namespace cutaway
