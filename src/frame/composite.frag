#version 450 core
// Resolves the multisampled G-buffer (frame/gbuffer.cpp): the final colour is the average of
// the samples with the overlays (ghost lines, feature lines, cut outlines) blended over it in
// order; the AOVs copy sample 0 (averaging ids, normals or depths across an edge would invent
// values that exist nowhere in the scene); the techniques' channels are copied by channels.frag.
#include "frame/samples.glsl"
layout(binding = 0) uniform SAMPLER_MS uColor;
layout(binding = 1) uniform SAMPLER_MS uNormal;
layout(binding = 2) uniform SAMPLER_MS uPosition;
layout(binding = 3) uniform ISAMPLER_MS uObjectId;
layout(binding = 4) uniform SAMPLER_MS uDepth;
layout(binding = 5) uniform SAMPLER_MS uCutMask;
layout(location = 0) uniform int uSamples;
layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outPosition;
layout(location = 3) out float outViewDepth;
layout(location = 4) out float outObjectId;
layout(location = 5) out float outDepth;
layout(location = 6) out float outCutMask;
// Generated: the overlays' samplers and blendOverlays().
#include "frame/composite_parts.glsl"
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec3 c = vec3(0.0);
  for (int s = 0; s < uSamples; ++s) c += texelFetch(uColor, p, s).rgb;
  c /= float(uSamples);
  outColor = vec4(blendOverlays(p, c), 1.0);
  int id = texelFetch(uObjectId, p, 0).r;
  bool background = id < 0;
  outNormal = background ? vec4(0.0) : vec4(texelFetch(uNormal, p, 0).xyz, 0.0);
  vec4 position = texelFetch(uPosition, p, 0);
  outPosition = background ? vec4(0.0) : vec4(position.xyz, 0.0);
  outViewDepth = background ? 0.0 : position.w;
  outObjectId = float(id);
  outDepth = texelFetch(uDepth, p, 0).r;
  outCutMask = texelFetch(uCutMask, p, 0).r >= 0.25 ? 1.0 : 0.0;  // cut surfaces, walls, caps
}
