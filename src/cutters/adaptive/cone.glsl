// The cone of a seed q evaluated at pixel p (src/fields/cutaway_surface.hpp, same formula):
//   c(p, q) = z(q) − ((1 − α) mE(q) + α mF(q))·‖Δ‖,  α = clamp(dot((q − p)/‖q − p‖, f(q)), 0, 1)
// (Burns11 eq. 4.1 with Burns08 §5.5's directional slope; Δ in view-plane units).
layout(binding = 0) uniform sampler2D uAnchorCone;   // z (NDC), mE, mF, seeded (1/0)
layout(binding = 1) uniform sampler2D uAnchorFloor;  // f (unit 2-D, or 0)
layout(location = 0) uniform vec2 uUnit;             // view-plane units per buffer pixel

float coneDepth(ivec2 p, int anchor) {
  int width = textureSize(uAnchorCone, 0).x;
  ivec2 q = ivec2(anchor % width, anchor / width);
  vec4 cone = texelFetch(uAnchorCone, q, 0);
  vec2 delta = vec2(p - q) * uUnit;
  float distance = length(delta);
  float alpha = 0.0;
  if (distance > 0.0) alpha = clamp(dot(-delta / distance, texelFetch(uAnchorFloor, q, 0).xy), 0.0, 1.0);
  return cone.x - mix(cone.y, cone.z, alpha) * distance;
}
