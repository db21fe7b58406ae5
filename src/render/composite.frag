#version 450 core
// Resolves the multisampled geometry targets: the final colour is the average of the
// samples with ghost lines, feature lines and cut outlines blended over it; the AOVs copy
// sample 0 (averaging ids, normals or depths across an edge would invent values that exist
// nowhere in the scene).
layout(binding = 0) uniform sampler2DMS uColor;
layout(binding = 1) uniform sampler2DMS uNormal;
layout(binding = 2) uniform sampler2DMS uPosition;
layout(binding = 3) uniform isampler2DMS uObjectId;
layout(binding = 4) uniform sampler2DMS uDepth;
layout(binding = 5) uniform sampler2D uLineCoverage;
layout(binding = 6) uniform sampler2D uOutlineCoverage;
layout(binding = 7) uniform sampler2D uGhostCoverage;
layout(binding = 8) uniform sampler2DMS uCutMask;
#ifdef CUTTER_CUTOUT
layout(binding = 9) uniform sampler2DMS uCutoutDistance;
layout(location = 7) out float outCutoutDistance;
#endif
layout(location = 0) uniform int uSamples;
layout(location = 1) uniform int uHasLines;
layout(location = 2) uniform vec3 uLineColor;
layout(location = 3) uniform int uHasOutlines;
layout(location = 4) uniform vec3 uOutlineColor;
layout(location = 5) uniform int uHasGhosts;
layout(location = 6) uniform float uGhostOpacity;
layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outPosition;
layout(location = 3) out float outViewDepth;
layout(location = 4) out float outObjectId;
layout(location = 5) out float outDepth;
layout(location = 6) out float outCutMask;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec3 c = vec3(0.0);
  for (int s = 0; s < uSamples; ++s) c += texelFetch(uColor, p, s).rgb;
  c /= float(uSamples);
  if (uHasGhosts != 0) c = mix(c, uLineColor, uGhostOpacity * texelFetch(uGhostCoverage, p, 0).r);
  if (uHasLines != 0) c = mix(c, uLineColor, texelFetch(uLineCoverage, p, 0).r);
  if (uHasOutlines != 0) c = mix(c, uOutlineColor, texelFetch(uOutlineCoverage, p, 0).r);
  outColor = vec4(c, 1.0);
  int id = texelFetch(uObjectId, p, 0).r;
  bool background = id < 0;
  outNormal = background ? vec4(0.0) : vec4(texelFetch(uNormal, p, 0).xyz, 0.0);
  vec4 position = texelFetch(uPosition, p, 0);
  outPosition = background ? vec4(0.0) : vec4(position.xyz, 0.0);
  outViewDepth = background ? 0.0 : position.w;
  outObjectId = float(id);
  outDepth = texelFetch(uDepth, p, 0).r;
  outCutMask = texelFetch(uCutMask, p, 0).r >= 0.25 ? 1.0 : 0.0;  // cut surfaces, walls, caps
#ifdef CUTTER_CUTOUT
  outCutoutDistance = texelFetch(uCutoutDistance, p, 0).r;
#endif
}
