// Gooch cool-to-warm shading (Gooch, Gooch, Shirley, Cohen 1998, "A Non-Photorealistic
// Lighting Model for Automatic Technical Illustration"), as cited by Trapp13 and
// Diepstraten03:
//   k_cool = k_blue + α k_d,  k_warm = k_yellow + β k_d,
//   I = t k_warm + (1 − t) k_cool,  t = (1 + l·n) / 2
// so surfaces facing the key light are warm and those facing away are cool, never black.
// The key light is the first light (a headlight if there is none); a white Blinn highlight
// from it marks shininess, as in the paper's figures.
// In the key light's shadow the lit part of l·n is taken away (a shadowed surface facing the
// light looks like one edge-on to it: halfway between cool and warm), and so is the highlight.
layout(std140, binding = BLOCK_STYLE) uniform GoochUniforms {
  vec4 uGoochCool;  // rgb: k_blue, w: alpha
  vec4 uGoochWarm;  // rgb: k_yellow, w: beta
};
vec3 shadeSurface(SurfacePoint s) {
  vec3 l = uCounts.x > 0 ? towardsLight(0, s.position) : s.toEye;
  float nDotL = dot(s.normal, l);
  float t = 0.5 * (1.0 + min(nDotL, 0.0) + max(nDotL, 0.0) * s.keyLightVisibility);
  vec3 kCool = uGoochCool.rgb + uGoochCool.w * s.baseColor;
  vec3 kWarm = uGoochWarm.rgb + uGoochWarm.w * s.baseColor;
  return mix(kCool, kWarm, t) + vec3(s.specular * blinnSpecular(s, l) * s.keyLightVisibility);
}
