#version 450 core
// A billboard pipe as a region of interest (Burns08 §5.1, Burns11 §4.2.2): the rear hull of
// its tube for the seed of a cutaway surface grown around it. The back of the tube at the
// fragment mirrors eq. 11's front normal through the quad: N_b = (N − F_a)/|N − F_a|, so the
// seed lies on the tube's far side, which the greater-than depth test keeps.
#include "frame/frame_uniforms.glsl"
#include "pipes.glsl"
in vec3 vWorld;
in vec3 vAxis;
in vec3 vNormal;
in float vArc;
flat in vec3 vFace;
flat in vec3 vDirection;
flat in int vPipe;
layout(location = 16) uniform float uTheta;  // radians
layout(location = 0) out float outSeedDepth;
layout(location = 1) out float outSeedAngle;
void main() {
  vec3 back = vAxis + outerRadius(vPipe) * normalize(vNormal - vFace);
  vec4 clip = uViewProjection * vec4(back, 1.0);
  float depth = clamp(clip.z / clip.w * 0.5 + 0.5, 0.0, 1.0);  // the default depth range
  gl_FragDepth = depth;
  outSeedDepth = depth;
  outSeedAngle = uTheta;
}
