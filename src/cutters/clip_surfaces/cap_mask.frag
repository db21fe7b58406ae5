#version 450 core
// The cap-mask AOV: sample 0 of the G-buffer's cut mask, where caps are marked 1 (gbuffer.glsl).
#include "frame/samples.glsl"
layout(binding = 0) uniform SAMPLER_MS uCutMask;
layout(location = 0) out float outCapMask;
void main() {
  outCapMask = texelFetch(uCutMask, ivec2(gl_FragCoord.xy), 0).r > 0.75 ? 1.0 : 0.0;
}
