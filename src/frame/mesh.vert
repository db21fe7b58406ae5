#version 450 core
#include "frame/frame_uniforms.glsl"
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 0) uniform mat4 uModel;
layout(location = 4) uniform mat4 uNormalMatrix;  // inverse transpose of uModel
// Diepstraten03 §4.3 clip-plane cutout: kept where dot(uClipPlane, world) >= 0 (only while
// GL_CLIP_DISTANCE0 is enabled).
layout(location = 18) uniform vec4 uClipPlane;
// Cutter::slab's parts (clip distances 1–5, while enabled): kept where all are ≥ 0.
layout(location = 19) uniform vec4 uSlabClip[5];
out float gl_ClipDistance[6];
out vec3 vWorldPosition;
out vec3 vWorldNormal;
void main() {
  vec4 world = uModel * vec4(aPosition, 1.0);
  vWorldPosition = world.xyz;
  vWorldNormal = mat3(uNormalMatrix) * aNormal;
  gl_ClipDistance[0] = dot(uClipPlane, world);
  for (int i = 0; i < 5; ++i) gl_ClipDistance[i + 1] = dot(uSlabClip[i], world);
  gl_Position = uViewProjection * world;
}
