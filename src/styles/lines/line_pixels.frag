#version 450 core
// The pixels lines.frag may draw on: those with a sample whose line weight is not 0 where
// feature lines are drawn (edge() returns 0 at every other sample: the background, objects
// without lines, kept ghost geometry), or, with CUT_OUTLINES, a sample of
// the cut mask; it gives every other pixel coverage 0. LinePass marks them in a depth buffer
// so that the rasteriser skips the rest without running lines.frag there: most of a frame is
// often background, and ghost lines lie only where material was removed.
#include "frame/samples.glsl"
#include "frame/normal_weight.glsl"
layout(binding = 0) uniform USAMPLER_MS uNormal;  // world normal and line weight
#ifdef CUT_OUTLINES
layout(binding = 2) uniform SAMPLER_MS uCutMask;
#endif
layout(location = 0) uniform int uSamples;
layout(location = 1) uniform int uFeatureLines;  // 1: silhouettes or creases are drawn

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  bool drawn = false;
  for (int s = 0; s < uSamples; ++s) {
    drawn = drawn || (uFeatureLines != 0 && unpackWeight(texelFetch(uNormal, p, s).r) > 0.0);
#ifdef CUT_OUTLINES
    drawn = drawn || texelFetch(uCutMask, p, s).r >= 0.5;
#endif
  }
  if (!drawn) discard;
}
