// Konev18 §7: shafts are an outer and an inner cylinder (normals outward on both); fragments
// whose normal faces the viewer, n·v > the opening coefficient with the heights ignored, are
// discarded, so a wedge always opens towards the viewer. The outer cylinder's back faces and
// the inner one's front faces are the wall seen edge-on in the wedge: the cut surface. Mirrors
// shaftWedgeRemoves in src/geometry/pipe_network.cpp.
#include "cutters/fate.glsl"
layout(location = LOC_SHAFT_OPENING) uniform float uShaftOpening;
layout(location = LOC_SHAFT_INNER) uniform int uShaftInner;  // 1: the inner cylinder

int shaftFragment(CutFragment f, out vec3 cutPosition, out vec3 cutNormal) {
  bool inner = uShaftInner != 0, frontFacing = f.frontFacing;
  vec3 x = f.position, normal = f.normal;
  vec3 toEye = uCounts.y == 1 ? -uForward.xyz : uEye.xyz - x;
  vec2 n = normal.xz, v = toEye.xz;
  cutPosition = x;
  cutNormal = vec3(0.0);
  if (dot(n, n) < 1e-12 || dot(v, v) < 1e-12) return kKeep;  // floors
  n = normalize(n);
  v = normalize(v);
  if (dot(n, v) > uShaftOpening) return kDiscard;
  if (inner == frontFacing) {
    // The wedge's side plane through the axis: its normal is the tangent, towards the viewer.
    vec2 t = vec2(-n.y, n.x);
    cutNormal = normalize(vec3(dot(t, v) >= 0.0 ? t.x : -t.x, 0.0, dot(t, v) >= 0.0 ? t.y : -t.y));
    return kCutSurface;
  }
  return kKeep;
}
