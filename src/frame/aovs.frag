#version 450 core
// The G-buffer's AOVs (frame/gbuffer.cpp), run when they are read: sample 0 of each buffer
// (averaging ids, normals or depths across an edge would invent values that exist nowhere in
// the scene); the techniques' channels are copied by channels.frag.
#include "frame/frame_uniforms.glsl"
#include "frame/samples.glsl"
#include "frame/normal_weight.glsl"
layout(binding = 0) uniform USAMPLER_MS uNormal;
layout(binding = 1) uniform ISAMPLER_MS uObjectId;
layout(binding = 2) uniform SAMPLER_MS uDepth;
layout(binding = 3) uniform SAMPLER_MS uCutMask;
layout(location = 0) out vec4 outNormal;
layout(location = 1) out vec4 outPosition;
layout(location = 2) out float outViewDepth;
layout(location = 3) out float outObjectId;
layout(location = 4) out float outDepth;
layout(location = 5) out float outCutMask;

// The point shaded at this pixel: every program shades a point on the view ray through the
// pixel's centre, and the object-id target keeps its linear view depth (frame/gbuffer.glsl).
vec3 shadedPoint(float viewDepth) {
  vec4 h = uInverseProjection * vec4(gl_FragCoord.xy * uViewport.zw * 2.0 - 1.0, 0.0, 1.0);
  vec3 q = h.xyz / h.w;  // a point of the ray
  vec3 p = uCounts.y == 1 ? vec3(q.xy, -viewDepth) : q * (viewDepth / -q.z);
  return (uInverseView * vec4(p, 1.0)).xyz;
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 id = texelFetch(uObjectId, p, 0).rg;
  bool background = id.x < 0;
  float viewDepth = intBitsToFloat(id.y);
  outNormal = background ? vec4(0.0) : vec4(unpackNormal(texelFetch(uNormal, p, 0).r), 0.0);
  outPosition = background ? vec4(0.0) : vec4(shadedPoint(viewDepth), 0.0);
  outViewDepth = background ? 0.0 : viewDepth;
  outObjectId = float(id.x);
  outDepth = texelFetch(uDepth, p, 0).r;
  outCutMask = texelFetch(uCutMask, p, 0).r >= 0.25 ? 1.0 : 0.0;  // cut surfaces, walls, caps
}
