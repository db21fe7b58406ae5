#version 450 core
// Burns11 §5.2.4.1 once per pixel: where the simple structure cuts a solid, the back faces seen
// through the cut stand for the cut surface, with the cutaway surface's position and normal at
// the pixel's centre. Working it out here (five depth fetches) instead of per back-face fragment
// gives clip.glsl the same values at every fragment of the pixel for two fetches.
#include "frame/frame_uniforms.glsl"
#include "clip.glsl"
layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
void main() {
  vec3 position, normal;
  cutawaySurfaceAt(gl_FragCoord.xy * uViewport.zw, position, normal);
  outPosition = vec4(position, 1.0);
  outNormal = vec4(normal, 0.0);
}
