#version 450 core
// The stencil after the proxy passes (Konev18 §6) as bit masks over the pixel's samples, for
// the billboards' passes (billboard.frag): x's bits 0–15 the samples at 0 (outside), bits
// 16–31 those at 2 (over a cut surface); y the samples at 1 (inside).
#include "frame/samples.glsl"
layout(binding = 0) uniform USAMPLER_MS uStencil;
layout(location = 0) uniform int uSamples;
layout(location = 0) out ivec2 outMasks;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 masks = ivec2(0);
  for (int s = 0; s < uSamples; ++s) {
    uint stencil = texelFetch(uStencil, p, s).r;
    masks.x |= (stencil == 0u ? 1 << s : 0) | (stencil == 2u ? 1 << (16 + s) : 0);
    masks.y |= stencil == 1u ? 1 << s : 0;
  }
  outMasks = masks;
}
