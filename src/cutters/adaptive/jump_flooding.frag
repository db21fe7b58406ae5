#version 450 core
// One jump-flooding step (Rong & Tan 2006) on the cutaway function (Burns08 §5.1): keep the
// anchor whose cone is deepest at p among p's own and those of p + k·(dx, dy). Candidate
// order and the strict comparison match fields::jumpFlooding so CPU and GPU agree.
#include "cone.glsl"
layout(binding = 2) uniform isampler2D uAnchors;
layout(location = 1) uniform int uStep;
layout(location = 0) out int outAnchor;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 size = textureSize(uAnchors, 0);
  int best = texelFetch(uAnchors, p, 0).r;
  float bestDepth = best >= 0 ? coneDepth(p, best) : -1e30;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if (dx == 0 && dy == 0) continue;
      ivec2 q = p + ivec2(dx, dy) * uStep;
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
      int candidate = texelFetch(uAnchors, q, 0).r;
      if (candidate < 0) continue;
      float depth = coneDepth(p, candidate);
      if (depth > bestDepth) {
        best = candidate;
        bestDepth = depth;
      }
    }
  }
  outAnchor = best;
}
