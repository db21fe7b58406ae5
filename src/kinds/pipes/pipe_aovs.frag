#version 450 core
// The pipes' AOVs at sample 0: the stencil after the proxy passes (Konev18 §6) and the class
// of the visible pipe surface.
#include "frame/samples.glsl"
layout(binding = 0) uniform USAMPLER_MS uStencil;
layout(binding = 1) uniform SAMPLER_MS uPipeClass;
layout(location = 0) out float outStencil;
layout(location = 1) out float outPipeClass;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  outStencil = float(texelFetch(uStencil, p, 0).r);
  outPipeClass = texelFetch(uPipeClass, p, 0).r;
}
