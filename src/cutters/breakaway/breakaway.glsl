// Diepstraten03 §5 breakaway: exterior fragments in front of the foremost surface of the
// inflated convex hull of the interior objects are removed; back faces are clipped by a
// slightly smaller hull so the cut shows a wall of finite thickness. Needs
// frame_uniforms.glsl.
#include "cutters/fate.glsl"
// Window depth of the hulls' foremost surface (0 where no hull covers the pixel: nothing is
// clipped there), and the outer hull's world normal there.
layout(binding = UNIT_BREAKAWAY_CLIP_DEPTH) uniform sampler2D uBreakawayClipDepth;
layout(binding = UNIT_BREAKAWAY_INNER_DEPTH) uniform sampler2D uBreakawayInnerDepth;
layout(binding = UNIT_BREAKAWAY_HULL_NORMAL) uniform sampler2D uBreakawayHullNormal;

int breakawayFragment(CutFragment f, out vec3 cutPosition, out vec3 cutNormal) {
  bool frontFacing = f.frontFacing;
  ivec2 p = ivec2(CUT_FRAG_COORD.xy);
  float outer = texelFetch(uBreakawayClipDepth, p, 0).r;
  float clip = frontFacing ? outer : texelFetch(uBreakawayInnerDepth, p, 0).r;
  if (CUT_FRAG_COORD.z <= clip) return kDiscard;
  // A back face behind the hole is seen through the removed material: there the wall lies
  // on the outer hull's foremost surface.
  if (frontFacing || outer <= 0.0) return kKeep;
  vec4 ndc = vec4(CUT_FRAG_COORD.xy * uViewport.zw * 2.0 - 1.0, outer * 2.0 - 1.0, 1.0);
  vec4 world = uInverseView * (uInverseProjection * ndc);
  cutPosition = world.xyz / world.w;
  cutNormal = texelFetch(uBreakawayHullNormal, p, 0).xyz;
  return kCutSurface;
}
