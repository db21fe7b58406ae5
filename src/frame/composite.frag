#version 450 core
// Resolves the multisampled colour (frame/gbuffer.cpp): the average of the samples with the
// overlays (ghost lines, feature lines, cut outlines) blended over it in order. The other
// buffers become AOVs in aovs.frag, when they are read.
#include "frame/samples.glsl"
layout(binding = 0) uniform SAMPLER_MS uColor;
layout(location = 0) uniform int uSamples;
layout(location = 0) out vec4 outColor;
// Generated: the overlays' samplers and blendOverlays().
#include "frame/composite_parts.glsl"
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec3 c = vec3(0.0);
  for (int s = 0; s < uSamples; ++s) c += texelFetch(uColor, p, s).rgb;
  c /= float(uSamples);
  outColor = vec4(blendOverlays(p, c), 1.0);
}
