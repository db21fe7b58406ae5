// What every style receives about a visible surface point (world space), and the lights.
struct SurfacePoint {
  vec3 position;
  vec3 normal;     // unit, facing the viewer's side
  vec3 toEye;      // unit, from the point towards the eye
  vec3 baseColor;
  float specular;
  float shininess;
  float keyLightVisibility;  // in [0, 1]: 0 in the key light's (the first light's) shadow
};

// Unit vector from `p` towards light `i`.
vec3 towardsLight(int i, vec3 p) {
  vec4 l = uLightVector[i];
  return l.w == 0.0 ? -normalize(l.xyz) : normalize(l.xyz - p);
}

// Blinn-Phong specular term (Blinn 1977), zero where the light is behind the surface.
float blinnSpecular(SurfacePoint s, vec3 l) {
  if (dot(s.normal, l) <= 0.0) return 0.0;
  return pow(max(dot(s.normal, normalize(l + s.toEye)), 0.0), s.shininess);
}
