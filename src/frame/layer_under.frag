#version 450 core
// Translucent layers (frame/translucent_layers.hpp): one peeled layer's sample with its feature
// lines over it, blended under the accumulation (GL_ONE_MINUS_DST_ALPHA, GL_ONE). Reading
// gl_SampleID runs it per sample.
#include "frame/samples.glsl"
layout(binding = 0) uniform SAMPLER_MS uLayer;  // premultiplied colour, coverage
layout(binding = 1) uniform sampler2D uLines;    // the layer's line coverage, its opacity included
layout(location = 0) uniform vec4 uLineColor;    // w: 1 with lines
layout(location = 0) out vec4 outColor;
void main() {
  vec4 surface = texelFetch(uLayer, ivec2(gl_FragCoord.xy), gl_SampleID);
  float line = uLineColor.w > 0.0 ? texelFetch(uLines, ivec2(gl_FragCoord.xy), 0).r : 0.0;
  outColor = vec4(uLineColor.rgb * line, line) + (1.0 - line) * surface;  // lines over the surface
}
