#version 450 core
// Trapp13 §5.1: the cap surface, a grid over the clip surface's (U, V) extent (the part of it
// a capped object spans) refined to the offset map's resolution along each side, drawn as
// instanced tiles (only those that can hold the cap), displaced by the offset map:
// X = O + sU + tV − S_z·h(T)·N.
#include "frame/frame_uniforms.glsl"
#include "clip_surfaces.glsl"
layout(location = 0) in vec2 aST;   // within this instance's tile of the grid
layout(location = 1) in vec2 aTile;  // the tile's place in the grid (per instance)
layout(location = 40) uniform int uCapSurface;
layout(location = 48) uniform vec4 uCapRect;  // the part of [0,1]² the grid covers: s0, t0, s1, t1
layout(location = 50) uniform ivec2 uCapTiles;  // the grid's tiles along s and t
out vec3 vWorldPosition;
out vec2 vST;
void main() {
  int i = uCapSurface;
  vec2 st = mix(uCapRect.xy, uCapRect.zw, (aTile + aST) / vec2(uCapTiles));
  vec3 plane = uClipOrigin[i].xyz + st.x * uClipU[i].xyz + st.y * uClipV[i].xyz;
  // Indexed by the uniform itself (no loop, no discard here, unlike clipRelief's callers):
  // llvmpipe runs every case of clipRelief's switch, four fetches per grid vertex.
  float h = textureLod(uClipRelief[i], st * uClipScale[i].xy, 0.0).r;
  vWorldPosition = plane - uClipScale[i].z * h * clipSurfaceNormal(i);
  vST = st;
  gl_Position = uViewProjection * vec4(vWorldPosition, 1.0);
}
