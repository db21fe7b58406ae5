#version 450 core
// The boxes only count the samples that pass the depth test (occlusion_culling.cpp). With
// SURFACES_ONLY (mayReachBehind), only at pixels where a sample of uSurfaceIds holds a surface.
#ifdef SURFACES_ONLY
#include "frame/samples.glsl"
layout(binding = 0) uniform ISAMPLER_MS uSurfaceIds;  // the object id, -1 where none
layout(location = 2) uniform int uSamples;
#endif
void main() {
#ifdef SURFACES_ONLY
  ivec2 p = ivec2(gl_FragCoord.xy);
  bool surface = false;
  for (int s = 0; s < uSamples; ++s) surface = surface || texelFetch(uSurfaceIds, p, s).r >= 0;
  if (!surface) discard;
#endif
}
