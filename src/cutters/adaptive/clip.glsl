// The adaptive cutter's per-fragment decision in the geometry passes (Burns08 §4.1,
// Burns11 §5.2.2 and §5.2.4.1). Needs frame_uniforms.glsl.
#include "cutters/fate.glsl"
layout(binding = UNIT_CUTAWAY_DEPTH) uniform sampler2D uCutawayDepth;  // C(p), window depth, linear filter
layout(binding = UNIT_CUTAWAY_DILATED) uniform sampler2D uCutawayDilated;  // 1-pixel minimum of C (Burns08 §4.2)

// The cutaway surface at screen position uv, in view space.
vec3 cutawayViewPoint(vec2 uv) {
  vec4 h = uInverseProjection * vec4(uv * 2.0 - 1.0, texture(uCutawayDepth, uv).r * 2.0 - 1.0, 1.0);
  return h.xyz / h.w;
}

// kDiscard in the clear region, kKeep in the base region, kCutSurface for a back face seen
// through the cut: there it stands for the solid's cut surface, with the cutaway surface's
// position and normal (from neighbouring depths, Burns11 §5.2.4.1).
int adaptiveFragment(CutFragment f, out vec3 cutPosition, out vec3 cutNormal) {
  bool frontFacing = f.frontFacing;
  vec2 uv = gl_FragCoord.xy * uViewport.zw;
  // Burns11 eq. 5.4: Ω = 1 − step(C(p), p_z); back faces use the dilated surface.
  float c = frontFacing ? texture(uCutawayDepth, uv).r : texture(uCutawayDilated, uv).r;
  if (gl_FragCoord.z < c) return kDiscard;
  // A back face is a cut surface only where the cutaway surface lies in front of it; elsewhere
  // (no cut at this pixel) it is an ordinary inside view of an open mesh.
  if (frontFacing || c <= 0.0) return kKeep;
  vec2 texel = 1.0 / vec2(textureSize(uCutawayDepth, 0));
  vec3 center = cutawayViewPoint(uv);
  vec3 dx = cutawayViewPoint(uv + vec2(texel.x, 0.0)) - cutawayViewPoint(uv - vec2(texel.x, 0.0));
  vec3 dy = cutawayViewPoint(uv + vec2(0.0, texel.y)) - cutawayViewPoint(uv - vec2(0.0, texel.y));
  vec3 n = cross(dx, dy);
  n = dot(n, n) > 0.0 ? normalize(n) : vec3(0.0, 0.0, 1.0);
  vec3 toEye = uCounts.y == 1 ? vec3(0.0, 0.0, 1.0) : -center;
  if (dot(n, toEye) < 0.0) n = -n;
  cutNormal = normalize(mat3(uInverseView) * n);
  cutPosition = (uInverseView * vec4(center, 1.0)).xyz;
  return kCutSurface;
}

// Burns08 §4.3: how strongly a removed fragment shows as a ghost line: 1 at the cutaway
// surface, fading to 0 at `distance` (world units) in front of it; 0 for kept fragments.
float ghostFade(vec3 worldPosition, float distance) {
  vec2 uv = gl_FragCoord.xy * uViewport.zw;
  if (gl_FragCoord.z >= texture(uCutawayDepth, uv).r) return 0.0;
  float fragmentDepth = -(uView * vec4(worldPosition, 1.0)).z;
  float cutawayDepth = -cutawayViewPoint(uv).z;
  return clamp(1.0 - (cutawayDepth - fragmentDepth) / distance, 0.0, 1.0);
}
