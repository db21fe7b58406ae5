#version 450 core
// Ghost geometry (Burns08 §4.3): front faces of removed material up to a distance in front
// of the cutaway surface, written to a G-buffer whose feature lines are drawn faded. Kept
// front faces are written too, with weight 0: they fill the G-buffer where the removed layer
// ends at the cut, so that boundary (already drawn as the cut outline) is no silhouette.
#include "frame/frame_uniforms.glsl"
#include "clip.glsl"
#include "frame/normal_weight.glsl"
in vec3 vWorldPosition;
in vec3 vWorldNormal;
layout(location = 11) uniform int uObjectId;
layout(location = 12) uniform float uLines;  // 0: an object without lines (param "lines")
layout(location = 17) uniform float uGhostDistance;
layout(location = 0) out uint outNormal;     // the normal and, as the line weight, the fade
layout(location = 1) out ivec2 outObjectId;  // the object id, the linear view depth's bits
void main() {
  if (!gl_FrontFacing) discard;
  bool removed = gl_FragCoord.z < cutawayDepthAt(gl_FragCoord.xy, true);
  float fade = removed ? ghostFade(vWorldPosition, uGhostDistance) : 0.0;
  if (removed && fade <= 0.0) discard;  // beyond the ghost distance
  vec3 n = vWorldNormal;
  if (dot(n, n) < 1e-12) n = cross(dFdx(vWorldPosition), dFdy(vWorldPosition));
  outNormal = packNormalWeight(normalize(n), fade * uLines);
  outObjectId = ivec2(uObjectId, floatBitsToInt(-(uView * vec4(vWorldPosition, 1.0)).z));
}
