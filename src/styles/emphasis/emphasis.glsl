// Burns11 §3.3.1: emphasis by importance over every style; mirrors emphasis_function.cpp
// (cutaway/styles/emphasis.hpp). With E_c = E_s = 0 and no line-drawn objects every colour
// passes unchanged, bit for bit (mix with a zero weight).
layout(std140, binding = BLOCK_EMPHASIS) uniform EmphasisUniforms {
  vec4 uEmphasis;  // x: E_c (eq. 3.1), y: E_s (eq. 3.3), z: importance below which lines only
  vec4 uPaper;     // rgb: the fill of line-drawn objects (§3.3.1.3)
};

// Rec. 709 luma: the greyscale intensity c_i of eq. 3.1.
float intensity(vec3 c) {
  return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

// `base`: the unshaded colour c, `shaded`: the style's c_shaded, I: the importance.
vec3 emphasize(vec3 base, vec3 shaded, float importance) {
  if (importance < uEmphasis.z) return uPaper.rgb;
  vec3 suppressed = mix(shaded, base, uEmphasis.y * (1.0 - importance));  // eqs. 3.3–3.4
  float grey = uEmphasis.x * (1.0 - importance);
  return mix(suppressed, vec3(intensity(suppressed)), grey);  // eqs. 3.1–3.2
}
