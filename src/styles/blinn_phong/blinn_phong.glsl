// Blinn-Phong shading: ambient + Σ_lights (k_d max(n·l, 0) + k_s max(n·h, 0)^shininess).
// Lights have no distance falloff: illustrations want even lighting.
layout(std140, binding = BLOCK_STYLE) uniform BlinnPhongUniforms {
  vec4 uStyleParams;  // x: ambient
};
vec3 shadeSurface(SurfacePoint s) {
  vec3 c = uStyleParams.x * s.baseColor;
  for (int i = 0; i < uCounts.x; ++i) {
    vec3 l = towardsLight(i, s.position);
    float visibility = i == 0 ? s.keyLightVisibility : 1.0;  // only the key light casts shadows
    c += visibility * uLightColor[i].rgb *
         (s.baseColor * max(dot(s.normal, l), 0.0) + s.specular * blinnSpecular(s, l));
  }
  return c;
}
