// Burns11's contextual cutaway structure (§4.1.3.3, eqs. 5.5–5.6), occlusion reduction by
// importance (eqs. 7.1–7.3) and its application (eqs. 2.1–2.2); mirrored line by line in
// clip.glsl.
#include <algorithm>
#include <cmath>

#include "cutaway/cutters/adaptive.hpp"

namespace cutaway {

float ramp(float a, float b, float x) {
  if (!(a < b)) return x > a ? 1.0f : 0.0f;
  return std::clamp((x - a) / (b - a), 0.0f, 1.0f);
}

float transitionOverlayOcclusion(bool transition, bool overlay) {
  if (transition && overlay) return 0.5f;
  return transition ? 1.0f : 0.0f;
}

float contextualOcclusion(const ContextualRay& r, float z) {
  // Towards the viewer: base (behind C₂), transition (C₂..C₁), overlay (C₁..C₁ − d), clear.
  return r.t * ramp(-r.z2, -r.z1, -z) + (1.0f - r.t) * ramp(-r.z1, -r.z1 + r.d, -z);
}

float occlusionDistance(const ContextualRay& r, float omega) {
  if (r.t > 0.0f && omega <= r.t) return r.z2 - omega / r.t * (r.z2 - r.z1);
  return r.z1 - r.d * (omega - r.t) / (1.0f - r.t);
}

float occlusionReduction(float omega, float importance) {
  const float tau0 = std::max(2.0f * importance - 1.0f, 0.0f);  // eq. 7.1
  const float tau1 = importance;                                 // eq. 7.2
  return ramp(tau0, tau1, omega);                                // eq. 7.3
}

float trimOcclusion(float importance) {
  if (importance >= 1.0f) return 2.0f;
  const float tau0 = std::max(2.0f * importance - 1.0f, 0.0f), tau1 = importance;
  return 0.5f * (tau0 + tau1);
}

glm::vec2 reducedOpacity(ContextualCutawayOptions::Application apply, float reduction, float nDotV,
                         float k) {
  using Application = ContextualCutawayOptions::Application;
  switch (apply) {
    case Application::Cut:
      return glm::vec2(reduction >= 0.5f ? 0.0f : 1.0f);  // §5.2.4
    case Application::Translucency:
      return glm::vec2(1.0f - reduction);  // eq. 2.1, α_m = 1
    case Application::EdgeHighlights: {
      const float facing = std::clamp(nDotV, 0.0f, 1.0f);
      return glm::vec2(1.0f - reduction * (1.0f - std::pow(1.0f - facing, k)));  // eq. 2.2
    }
    case Application::Lines:
      return {reduction > 0.0f ? 0.0f : 1.0f, 1.0f - reduction};  // §2.3
  }
  return glm::vec2(1.0f);
}

}  // namespace cutaway
