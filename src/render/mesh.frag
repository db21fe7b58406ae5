#version 450 core
// Geometry pass: shades a visible object with the active style (aliased as "style.glsl")
// and writes the G-buffer that the line and AOV passes read.
#include "frame_uniforms.glsl"
#include "../styles/surface.glsl"
#include "style.glsl"
#include "cutter.glsl"
#include "../styles/shadows/shadow_lookup.glsl"
in vec3 vWorldPosition;
in vec3 vWorldNormal;
layout(location = 8) uniform vec3 uColor;
layout(location = 9) uniform float uSpecular;
layout(location = 10) uniform float uShininess;
layout(location = 11) uniform int uObjectId;
layout(location = 12) uniform float uLines;  // 1: this object takes feature lines
layout(location = 13) uniform int uClipped;     // 0 for objects of interest: never cut
layout(location = 14) uniform int uCutSurface;  // 1: show back faces through the cut as solid
layout(location = 15) uniform vec3 uCutColor;
layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outNormal;     // world normal, w: lines flag
layout(location = 2) out vec4 outPosition;   // world position, w: linear view depth
layout(location = 3) out int outObjectId;
layout(location = 4) out float outCutMask;    // 1 on cut surfaces
void main() {
  vec3 cutPosition, cutNormal;
  int fate = uClipped != 0 ? cutFragment(gl_FrontFacing, cutPosition, cutNormal) : kKeep;
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
  s.baseColor = cut ? uCutColor : uColor;
  s.specular = uSpecular;
  s.shininess = uShininess;
  s.keyLightVisibility = keyLightVisibility(s.position);
  outColor = vec4(shadeSurface(s), 1.0);
  outNormal = vec4(s.normal, uLines);
  outPosition = vec4(s.position, -(uView * vec4(s.position, 1.0)).z);
  outObjectId = uObjectId;
  outCutMask = cut ? 1.0 : 0.0;
}
