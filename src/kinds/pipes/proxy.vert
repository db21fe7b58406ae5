#version 450 core
// Konev18 §6: the static proxy geometry of the cut stretches (end triangles and quads),
// offsets in units of the pipe's outer radius so that the radius changes at run time.
#include "frame/frame_uniforms.glsl"
#include "pipes.glsl"
layout(location = 0) in vec3 aAxis;
layout(location = 1) in vec3 aOffset;  // × r_out
layout(location = 2) in vec2 aUv;
layout(location = 3) in int aPipe;
layout(location = 4) in int aKind;     // 0: end triangle, 1: quad
layout(location = 5) in vec3 aNormal;  // the proxy's plane normal (the triangle's front side)
out vec2 vUv;
out vec3 vWorld;
flat out int vPipe;
flat out int vKind;
flat out vec3 vPlaneNormal;
void main() {
  vWorld = aAxis + aOffset * outerRadius(aPipe);
  vUv = aUv;
  vPipe = aPipe;
  vKind = aKind;
  vPlaneNormal = aNormal;
  gl_Position = uViewProjection * vec4(vWorld, 1.0);
}
