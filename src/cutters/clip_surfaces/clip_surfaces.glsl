// Trapp13 §4: 2.5D clip surfaces, several evaluated in one pass (§4.5); mirrors
// src/cutters/clip_surfaces/clip_surface_function.cpp. Shared by the fragment test
// (clip_fragment.glsl) and the caps (cap.vert, cap.frag). Needs frame_uniforms.glsl.
#ifndef CUTTERS_CLIP_SURFACES_GLSL
#define CUTTERS_CLIP_SURFACES_GLSL
#include "cutters/fate.glsl"
const int kMaxClipSurfaces = 4;
layout(std140, binding = BLOCK_CLIP_SURFACES) uniform ClipSurfaces {
  vec4 uClipOrigin[kMaxClipSurfaces];  // xyz: O, w: 1 if enabled
  vec4 uClipU[kMaxClipSurfaces];       // xyz: U
  vec4 uClipV[kMaxClipSurfaces];       // xyz: V
  vec4 uClipScale[kMaxClipSurfaces];   // xyz: S, w: the relief's largest lift, max h·S_z
  ivec4 uClipCount;                    // x: surfaces, y: 1 = intersection, z: normal map on caps
  vec4 uCapStyle;                      // x: occlusion strength, y: solid texture, z: its frequency
  vec4 uClipSurfacePlane[kMaxClipSurfaces];   // xyz: N = Û × V̂, w: N·O
  vec4 uClipToS[kMaxClipSurfaces];     // xyz: Û S_x / |U| (eq. 2's s = (P − O)·this)
  vec4 uClipToT[kMaxClipSurfaces];     // xyz: V̂ S_y / |V|
};
// Per surface: r = offset h, g = ∂h/∂s, b = ∂h/∂t, a = ambient occlusion (derived at load).
layout(binding = UNIT_CLIP_RELIEF) uniform sampler2D uClipRelief[kMaxClipSurfaces];

// Surface i's relief at st, each sampler named by a constant index: Mesa's llvmpipe (LLVM 15,
// Debian 12) crashes compiling a sampler array indexed by a variable in a loop after a discard
// (its EarlyCSE pass), as the caps' parity test and the clip test make it. Level 0 named:
// the maps have one level, filtered linearly either way, so it is texture()'s value without
// the derivatives (undefined in a switch, and work llvmpipe does in every fragment).
vec4 clipRelief(int i, vec2 st) {
  switch (i) {
    case 0: return textureLod(uClipRelief[0], st, 0.0);
    case 1: return textureLod(uClipRelief[1], st, 0.0);
    case 2: return textureLod(uClipRelief[2], st, 0.0);
    default: return textureLod(uClipRelief[3], st, 0.0);
  }
}

vec3 clipSurfaceNormal(int i) {
  return uClipSurfacePlane[i].xyz;
}

// Trapp13 eq. 2 with eq. 3: texture coordinates of P's projection onto the plane.
vec2 clipSurfaceTexCoord(int i, vec3 p) {
  vec3 d = p - uClipOrigin[i].xyz;
  return vec2(dot(d, uClipToS[i].xyz), dot(d, uClipToT[i].xyz));
}

// Trapp13 eq. 1: P·N − N·O + f(OM, T)·S_z; χ = 1 (clipped) where it is < 0.
float clipSurfaceFunction(int i, vec3 p) {
  float h = clipRelief(i, clipSurfaceTexCoord(i, p)).r;
  return dot(p, uClipSurfacePlane[i].xyz) - uClipSurfacePlane[i].w + h * uClipScale[i].z;
}

// The combination rule over the enabled surfaces other than `except` (-1: all): union (any
// clips) or intersection (all clip).
bool clippedBySurfaces(vec3 p, int except) {
  bool any = false, all = true, enabled = false;
  for (int i = 0; i < uClipCount.x; ++i) {
    if (i == except || uClipOrigin[i].w == 0.0) continue;
    enabled = true;
    bool clipped = clipSurfaceFunction(i, p) < 0.0;
    any = any || clipped;
    all = all && clipped;
  }
  if (!enabled) return except >= 0 && uClipCount.y == 1;  // alone in an intersection: kept
  return uClipCount.y == 1 ? all : any;
}
#endif
