#version 450 core
// The "shadowMap" pass: the casters seen from the key light. Drawn with frame/mesh.vert and
// the frame uniforms of the light (its view and projection in place of the camera's), so the
// depth target holds window depth from the light, and the AOV target the depth along the
// light's axis in scene units.
#include "frame/frame_uniforms.glsl"
in vec3 vWorldPosition;
layout(location = 0) out float outLightDepth;
void main() {
  outLightDepth = -(uView * vec4(vWorldPosition, 1.0)).z;
}
