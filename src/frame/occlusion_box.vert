#version 450 core
// An object's box for occlusion_culling.cpp: the 12 triangles of the world-space box
// [uMin, uMax], wound counter-clockwise seen from outside, from gl_VertexID alone.
#include "frame/frame_uniforms.glsl"
layout(location = 0) uniform vec3 uMin;
layout(location = 1) uniform vec3 uMax;
const int kCorners[36] = int[36](0, 6, 2, 0, 4, 6, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4, 2, 7, 3, 2,
                                 6, 7, 0, 3, 1, 0, 2, 3, 4, 5, 7, 4, 7, 6);
void main() {
  int c = kCorners[gl_VertexID];  // bit 0: x, bit 1: y, bit 2: z at the maximum
  vec3 p = mix(uMin, uMax, vec3(c & 1, (c >> 1) & 1, (c >> 2) & 1));
  gl_Position = uViewProjection * vec4(p, 1.0);
}
