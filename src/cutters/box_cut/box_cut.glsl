// The box cut (Li et al.'s convention, Konev18 §7; Diepstraten03 rule 2): an oriented box that
// removes its inside; back faces seen through it show the solid's cut wall on the box face
// the view ray left it by. Mirrors boxCutFragment in
// src/cutters/box_cut/box_cut_function.cpp. Needs frame_uniforms.glsl.
#include "cutters/fate.glsl"
layout(location = LOC_BOX_CUT_CENTER) uniform vec3 uBoxCutCenter;
layout(location = LOC_BOX_CUT_AXES) uniform vec3 uBoxCutAxes[3];  // unit axes, world space
layout(location = LOC_BOX_CUT_HALF) uniform vec3 uBoxCutHalf;     // half edge lengths

vec3 boxCutLocal(vec3 x) {
  vec3 d = x - uBoxCutCenter;
  return vec3(dot(d, uBoxCutAxes[0]), dot(d, uBoxCutAxes[1]), dot(d, uBoxCutAxes[2]));
}

int boxCutFragment(CutFragment f, out vec3 cutPosition, out vec3 cutNormal) {
  cutPosition = f.position;
  cutNormal = vec3(0.0);
  vec3 local = boxCutLocal(f.position);
  if (all(lessThanEqual(abs(local), uBoxCutHalf))) return kDiscard;
  if (f.frontFacing) return kKeep;
  // The view ray from → x against the box's slabs: [tIn, tOut] inside it, and the faces.
  vec3 x = f.position;
  vec3 from = boxCutLocal(viewRayOrigin(x)), v = local - from;
  float tIn = -1e30, tOut = 1e30;
  int outAxis = -1;
  for (int i = 0; i < 3; ++i) {
    if (v[i] == 0.0) {
      if (abs(from[i]) > uBoxCutHalf[i]) return kKeep;  // parallel, outside this slab
      continue;
    }
    float a = (-uBoxCutHalf[i] - from[i]) / v[i], b = (uBoxCutHalf[i] - from[i]) / v[i];
    float near = min(a, b), far = max(a, b);
    tIn = max(tIn, near);
    if (far < tOut) tOut = far, outAxis = i;
  }
  // The wall is where the ray left the box, in front of x.
  if (outAxis < 0 || !(tIn < tOut) || !(tOut > 0.0 && tOut < 1.0)) return kKeep;
  vec3 p = from + tOut * v;
  cutPosition = uBoxCutCenter + p.x * uBoxCutAxes[0] + p.y * uBoxCutAxes[1] + p.z * uBoxCutAxes[2];
  // The face's normal towards the viewer: against the ray's direction along that axis.
  cutNormal = (v[outAxis] > 0.0 ? -1.0 : 1.0) * uBoxCutAxes[outAxis];
  return kCutSurface;
}

// The span of a view ray inside the box, which it removes whole (cutters/cutter.hpp), shrunk
// by a hair so that samples on its faces are decided by boxCutFragment.
#define BOXCUT_REMOVED_SPAN
vec2 boxCutRemovedSpan(vec3 origin, vec3 direction, vec2 window, vec2 range) {
  vec3 from = boxCutLocal(origin);
  vec3 v = vec3(dot(direction, uBoxCutAxes[0]), dot(direction, uBoxCutAxes[1]),
                dot(direction, uBoxCutAxes[2]));
  vec3 a = (-uBoxCutHalf - from) / v, b = (uBoxCutHalf - from) / v;
  float tIn = max(max(min(a.x, b.x), min(a.y, b.y)), min(a.z, b.z));
  float tOut = min(min(max(a.x, b.x), max(a.y, b.y)), max(a.z, b.z));
  float hair = 1e-4 * (tOut - tIn);
  return vec2(tIn + hair, tOut - hair);
}
