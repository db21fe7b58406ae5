// Toon (cel) shading (Lake, Marshall, Harris, Blackstein 2000, §3.1): the key light's diffuse
// term max(n·l, 0) indexes a 1-D ramp texture built in src/styles/toon/toon_ramp.cpp; its
// nearest filtering gives hard bands. The tone multiplies the object colour, so objects keep
// their colours. In the key light's shadow (SurfacePoint.keyLightVisibility) the surface
// counts as turned away from the light, so shadows fall into the darkest tone; a hard-edged
// highlight (Lake00 §3.1, "specular highlight" as a second ramp of two tones) appears where
// the Blinn term passes a threshold. Silhouettes come from the line pass (styles/lines).
// The key light is the first light (a headlight without lights); its colour is not used.
layout(binding = UNIT_TOON_RAMP) uniform sampler1D uToonRamp;
layout(std140, binding = BLOCK_STYLE) uniform ToonUniforms {
  vec4 uToonParams;     // x: ramp size, y: highlight threshold, z: 1 for highlights
  vec4 uToonHighlight;  // rgb: highlight colour
};
vec3 shadeSurface(SurfacePoint s) {
  vec3 l = uCounts.x > 0 ? towardsLight(0, s.position) : s.toEye;
  float nDotL = max(dot(s.normal, l), 0.0) * step(0.5, s.keyLightVisibility);
  vec3 c = texture(uToonRamp, nDotL).rgb * s.baseColor;
  // x: ramp size, y: highlight threshold, z: 1 with highlights
  if (uToonParams.z != 0.0 && s.keyLightVisibility >= 0.5 &&
      blinnSpecular(s, l) > uToonParams.y)
    c += s.specular * uToonHighlight.rgb;
  return min(c, vec3(1.0));
}
