#version 450 core
// Trapp13 §5.1, with its §7's relief mapping: the cap surface's grid is drawn as prisms, one per
// tile of the grid that can hold the cap (capTiles, instanced), each the box over its tile's
// part of the clip surface's (U, V) extent between the least and greatest lift of the relief
// over it. cap.frag finds the displaced surface X = O + sU + tV − S_z·h(T)·N along each view ray
// within the prism: a grid refined to the offset map's texels without its triangles.
#include "frame/frame_uniforms.glsl"
#include "clip_surfaces.glsl"
layout(location = 0) in vec3 aCorner;  // of the unit cube: s, t, lift
layout(location = 1) in vec4 aTile;    // xy: the tile's place in the grid; zw: h_min, h_max over it
layout(location = 40) uniform int uCapSurface;
layout(location = 48) uniform vec4 uCapRect;  // the part of [0,1]² the grid covers: s0, t0, s1, t1
layout(location = 50) uniform ivec2 uCapTiles;  // the grid's tiles along s and t
out vec3 vWorldPosition;
flat out vec4 vPrismT;     // the prism's eq. 2 texture coordinates: least (xy), greatest (zw)
flat out vec2 vPrismLift;  // and its extent along N, (P − O)·N: least, greatest
void main() {
  int i = uCapSurface;
  vec2 st0 = mix(uCapRect.xy, uCapRect.zw, aTile.xy / vec2(uCapTiles));
  vec2 st1 = mix(uCapRect.xy, uCapRect.zw, (aTile.xy + 1.0) / vec2(uCapTiles));
  // X lies at (X − O)·N = −S_z·h; a flat relief's prism keeps a sliver of thickness.
  // A few steps of float at the size of the coordinates too (a surface far from the origin).
  float sz = uClipScale[i].z,
        pad = 1e-5 * (length(uClipU[i].xyz) + length(uClipV[i].xyz)) + 5e-7 * length(uClipOrigin[i].xyz);
  vec2 lift = vec2(-sz * aTile.w, -sz * aTile.z);
  vPrismLift = vec2(min(lift.x, lift.y) - pad, max(lift.x, lift.y) + pad);
  vPrismT = vec4(st0, st1) * uClipScale[i].xyxy;
  vec2 st = mix(st0, st1, aCorner.xy);
  vec3 n = clipSurfaceNormal(i), x = uClipOrigin[i].xyz + st.x * uClipU[i].xyz +
                                     st.y * uClipV[i].xyz + mix(vPrismLift.x, vPrismLift.y, aCorner.z) * n;
  // Drawn a pixel larger all round (a world pixel at the corner's view depth, along each of
  // the box's axes), so that a pixel whose centre's view ray crosses the prism has all its
  // samples covered by it: cap.frag shades the centre's ray, and its depth goes to every sample.
  float atOne = max(2.0 / (uViewport.x * uProjection[0][0]), 2.0 / (uViewport.y * uProjection[1][1]));
  float pixel = uCounts.y == 1 ? atOne : atOne * max(-(uView * vec4(x, 1.0)).z, 0.0);
  vec3 out3 = 2.0 * aCorner - 1.0;
  x += pixel * (out3.x * normalize(uClipU[i].xyz) + out3.y * normalize(uClipV[i].xyz) + out3.z * n);
  vWorldPosition = x;
  gl_Position = uViewProjection * vec4(x, 1.0);
}
