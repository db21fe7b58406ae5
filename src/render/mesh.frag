#version 450 core
// Geometry pass: shades a visible object with the active style (aliased as "style.glsl")
// and writes the G-buffer that the line and AOV passes read.
#include "frame_uniforms.glsl"
#include "../styles/surface.glsl"
#include "style.glsl"
#include "../cutters/cutters.glsl"
#include "../styles/shadows/shadow_lookup.glsl"
#include "gbuffer.glsl"
in vec3 vWorldPosition;
in vec3 vWorldNormal;
layout(location = 8) uniform vec3 uColor;
layout(location = 9) uniform float uSpecular;
layout(location = 10) uniform float uShininess;
layout(location = 11) uniform int uObjectId;
layout(location = 12) uniform float uLines;  // 1: this object takes feature lines
layout(location = 13) uniform int uCutBy;       // which cutters cut this object (fate.glsl bits)
layout(location = 14) uniform int uCutSurface;  // 1: a solid: back faces seen through a cut are its cut surface
layout(location = 15) uniform vec3 uCutColor;
layout(location = 16) uniform vec3 uBackColor;  // back faces that are no cut surface (an open or hollow inside)
void main() {
  vec3 cutPosition, cutNormal;
  int fate = cutFragment(uCutBy, vWorldPosition, vWorldNormal, gl_FrontFacing, cutPosition,
                         cutNormal);
  if (fate == kDiscard) discard;
  bool cut = fate == kCutSurface && uCutSurface != 0;
  vec3 n = vWorldNormal;
  // Interpolated normals can vanish (opposite vertex normals); fall back to the face normal.
  if (dot(n, n) < 1e-12) n = cross(dFdx(vWorldPosition), dFdy(vWorldPosition));
  n = normalize(n);
  SurfacePoint s;
  s.position = cut ? cutPosition : vWorldPosition;
  s.normal = cut ? cutNormal : gl_FrontFacing ? n : -n;  // two-sided: open meshes show their inside
  s.toEye = uCounts.y == 1 ? -uForward.xyz : normalize(uEye.xyz - s.position);
  s.baseColor = cut ? uCutColor : gl_FrontFacing ? uColor : uBackColor;
  s.specular = uSpecular;
  s.shininess = uShininess;
  s.keyLightVisibility = keyLightVisibility(s.position);
  writeGBuffer(s, shadeSurface(s), uLines, uObjectId, cut, false);
#ifdef CUTTER_CUTOUT
  outCutoutDistance = (uCutBy & kCutByCutout) != 0 && uCutoutPlaneCount > 0
                          ? cutoutDistance(vWorldPosition)
                          : uintBitsToFloat(0x7fc00000u);  // NaN: no exterior surface here
#endif
}
