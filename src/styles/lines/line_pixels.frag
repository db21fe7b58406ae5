#version 450 core
// The pixels lines.frag may draw on: those with a sample of an object (or, with CUT_OUTLINES,
// of the cut mask); it gives every other pixel coverage 0. LinePass marks them in a depth
// buffer so that the rasteriser skips the rest without running lines.frag there: most of a
// frame is often background.
#include "frame/samples.glsl"
layout(binding = 1) uniform ISAMPLER_MS uObjectId;  // the id (-1: background), view depth bits
#ifdef CUT_OUTLINES
layout(binding = 2) uniform SAMPLER_MS uCutMask;
#endif
layout(location = 0) uniform int uSamples;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  bool drawn = false;
  for (int s = 0; s < uSamples; ++s) {
    drawn = drawn || texelFetch(uObjectId, p, s).r >= 0;
#ifdef CUT_OUTLINES
    drawn = drawn || texelFetch(uCutMask, p, s).r >= 0.5;
#endif
  }
  if (!drawn) discard;
}
