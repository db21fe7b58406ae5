#version 450 core
// Translucent layers (frame/translucent_layers.hpp): the accumulation's samples averaged (the
// resolve of premultiplied colour is its mean) and blended over the final colour
// (GL_ONE, GL_ONE_MINUS_SRC_ALPHA).
#include "frame/samples.glsl"
layout(binding = 0) uniform SAMPLER_MS uAccumulation;
layout(location = 0) uniform int uSamples;
layout(location = 0) out vec4 outColor;
void main() {
  vec4 sum = vec4(0.0);
  for (int s = 0; s < uSamples; ++s) sum += texelFetch(uAccumulation, ivec2(gl_FragCoord.xy), s);
  outColor = sum / float(uSamples);
}
