#version 450 core
// Geometry pass: shades a visible scene mesh with the active style (aliased as "style.glsl")
// and the active cutters (the generated cutters/composition.glsl), and writes the G-buffer
// that the line and AOV passes read.
#include "frame/frame_uniforms.glsl"
#include "styles/surface.glsl"
#include "style.glsl"
#include "styles/shadows/shadow_lookup.glsl"
#include "frame/gbuffer.glsl"
#include "cutters/composition.glsl"
in vec3 vWorldPosition;
in vec3 vWorldNormal;
layout(location = 8) uniform vec3 uColor;
layout(location = 9) uniform float uSpecular;
layout(location = 10) uniform float uShininess;
layout(location = 11) uniform int uObjectId;
layout(location = 12) uniform float uLines;       // 1: this object takes feature lines
layout(location = 13) uniform int uCutBy;         // bit k: the cutter of slot k cuts this object
layout(location = 14) uniform int uCutSurfaces;   // bit k: its cuts of this object show cut surfaces
layout(location = 15) uniform vec3 uBackColor;    // back faces that are no cut surface (an open or hollow inside)
layout(location = 24) uniform vec3 uCutColor[CUTTER_SLOTS];  // per slot: the cut surfaces' colour
void main() {
  CutFragment f = CutFragment(vWorldPosition, vWorldNormal, gl_FrontFacing);
  vec3 cutPosition, cutNormal;
  int cutter;
  int fate = cutFragment(uCutBy, f, cutPosition, cutNormal, cutter);
  if (fate == kDiscard) discard;
  bool cut = fate == kCutSurface && (uCutSurfaces & (1 << cutter)) != 0;
  vec3 n = vWorldNormal;
  // Interpolated normals can vanish (opposite vertex normals); fall back to the face normal.
  if (dot(n, n) < 1e-12) n = cross(dFdx(vWorldPosition), dFdy(vWorldPosition));
  n = normalize(n);
  SurfacePoint s;
  s.position = cut ? cutPosition : vWorldPosition;
  s.normal = cut ? cutNormal : gl_FrontFacing ? n : -n;  // two-sided: open meshes show their inside
  s.toEye = uCounts.y == 1 ? -uForward.xyz : normalize(uEye.xyz - s.position);
  s.baseColor = cut ? uCutColor[cutter] : gl_FrontFacing ? uColor : uBackColor;
  s.specular = uSpecular;
  s.shininess = uShininess;
  s.keyLightVisibility = keyLightVisibility(s.position);
  writeGBuffer(s, shadeSurface(s), uLines, uObjectId, cut, false);
  writeCutterChannels(uCutBy, f);
}
