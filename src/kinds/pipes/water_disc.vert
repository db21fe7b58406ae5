#version 450 core
// Konev18 §7 with §6.4: the water surface inside each shaft, one instanced quad per shaft,
// trimmed to the inner radius in the fragment shader.
#include "frame/frame_uniforms.glsl"
layout(location = 0) in vec4 aDisc;   // centre at the water surface, inner radius
layout(location = 1) in float aFill;  // water depth over the shaft's height
out vec2 vLocal;
out vec3 vWorld;
flat out float vFill;
void main() {
  vec2 corner = vec2(gl_VertexID & 1, gl_VertexID >> 1) * 2.0 - 1.0;
  vLocal = corner;
  vWorld = aDisc.xyz + aDisc.w * vec3(corner.x, 0.0, corner.y);
  vFill = aFill;
  gl_Position = uViewProjection * vec4(vWorld, 1.0);
}
