#version 450 core
// The G-buffer's AOVs (frame/gbuffer.cpp), run when they are read: sample 0 of each buffer
// (averaging ids, normals or depths across an edge would invent values that exist nowhere in
// the scene); the techniques' channels are copied by channels.frag.
#include "frame/samples.glsl"
layout(binding = 0) uniform SAMPLER_MS uNormal;
layout(binding = 1) uniform SAMPLER_MS uPosition;
layout(binding = 2) uniform ISAMPLER_MS uObjectId;
layout(binding = 3) uniform SAMPLER_MS uDepth;
layout(binding = 4) uniform SAMPLER_MS uCutMask;
layout(location = 0) out vec4 outNormal;
layout(location = 1) out vec4 outPosition;
layout(location = 2) out float outViewDepth;
layout(location = 3) out float outObjectId;
layout(location = 4) out float outDepth;
layout(location = 5) out float outCutMask;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
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
