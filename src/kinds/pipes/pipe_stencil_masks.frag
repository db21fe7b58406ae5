#version 450 core
// The stencil after the proxy passes (Konev18 §6) as two bit masks over the pixel's samples,
// for the billboards' outside pass (billboard.frag): bits 0–15 the samples at 0 (outside),
// bits 16–31 those at 2 (over a cut surface).
#include "frame/samples.glsl"
layout(binding = 0) uniform USAMPLER_MS uStencil;
layout(location = 0) uniform int uSamples;
layout(location = 0) out int outMasks;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  int masks = 0;
  for (int s = 0; s < uSamples; ++s) {
    uint stencil = texelFetch(uStencil, p, s).r;
    masks |= (stencil == 0u ? 1 << s : 0) | (stencil == 2u ? 1 << (16 + s) : 0);
  }
  outMasks = masks;
}
