// The key light's visibility at a surface point, from the shadow map of the "shadowMap" pass
// (src/styles/shadows/shadow_map.cpp). Needs frame_uniforms.glsl.
// Percentage-closer filtering (Reeves, Salesin, Cook 1987): the fraction of the map's depths
// around the point that lie behind it, over a (2r + 1)² grid of hardware-filtered 2×2
// comparisons (sampler2DShadow with linear filtering), so shadow edges are soft over about
// 2r + 2 texels instead of stair-stepped.
// UNIT_SHADOW_MAP is defined only while shadows are on (src/render/renderer.cpp).
#ifdef UNIT_SHADOW_MAP
layout(binding = UNIT_SHADOW_MAP) uniform sampler2DShadow uShadowMap;

// Needs surface.glsl (towardsLight).
float keyLightVisibility(vec3 position) {
  if (uShadowParams.x == 0.0) return 1.0;  // shadows off, or no key light
  // Constant bias: the receiver moves towards the light by y scene units. Along the light's
  // ray it keeps its shadow-map texel, and the offset is the same at every depth (a bias in
  // window depth would vanish or explode with a perspective light's non-linear depth). The
  // slope-scaled part is applied to the casters (shadow_map.cpp).
  vec3 biased = position + towardsLight(0, position) * uShadowParams.y;
  vec4 h = uShadowMatrix * vec4(biased, 1.0);
  vec3 p = h.xyz / h.w;  // [0, 1]³ inside the light's frustum
  if (p.z >= 1.0 || p.z <= 0.0) return 1.0;  // beyond the casters' depth range
  float reference = p.z;
  int r = int(uShadowParams.z);
  float lit = 0.0;
  for (int y = -r; y <= r; ++y)
    for (int x = -r; x <= r; ++x)
      lit += texture(uShadowMap, vec3(p.xy + vec2(x, y) * uShadowParams.w, reference));
  return lit / float((2 * r + 1) * (2 * r + 1));
}
#else
float keyLightVisibility(vec3 position) {
  return 1.0;
}
#endif
