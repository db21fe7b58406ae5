#version 450 core
// Translucent layers (frame/translucent_layers.hpp): one peeled layer's sample, blended under
// the accumulation (GL_ONE_MINUS_DST_ALPHA, GL_ONE). Reading gl_SampleID runs it per sample.
layout(binding = 0) uniform sampler2DMS uLayer;  // premultiplied colour, coverage
layout(location = 0) out vec4 outColor;
void main() {
  outColor = texelFetch(uLayer, ivec2(gl_FragCoord.xy), gl_SampleID);
}
