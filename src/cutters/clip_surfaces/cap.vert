#version 450 core
// Trapp13 §5.1: the cap surface, a grid over the clip surface's (U, V) extent refined to the
// offset map's resolution, displaced by the offset map: X = O + sU + tV − S_z·h(T)·N.
#include "../../render/frame_uniforms.glsl"
#include "clip_surfaces.glsl"
layout(location = 0) in vec2 aST;
layout(location = 40) uniform int uCapSurface;
out vec3 vWorldPosition;
out vec2 vST;
void main() {
  int i = uCapSurface;
  vec3 plane = uClipOrigin[i].xyz + aST.x * uClipU[i].xyz + aST.y * uClipV[i].xyz;
  float h = textureLod(uClipRelief[i], aST * uClipScale[i].xy, 0.0).r;
  vWorldPosition = plane - uClipScale[i].z * h * clipSurfaceNormal(i);
  vST = aST;
  gl_Position = uViewProjection * vec4(vWorldPosition, 1.0);
}
