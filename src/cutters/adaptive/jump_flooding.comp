#version 450 core
// One jump-flooding step (Rong & Tan 2006) on the cutaway function (Burns08 §5.1): keep the
// anchor whose cone is deepest at p among p's own and those of p + k·(dx, dy). Candidate
// order and the strict comparison match fields::jumpFlooding so CPU and GPU agree.
// A compute shader: it needs no rasteriser or blending, and GPUs that run fragment work on a
// few of their multiprocessors (Hopper: 11 ms at 1024² as a fragment pass) run it on all.
#include "cone.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 2) uniform isampler2D uAnchors;
layout(binding = 0, r32i) uniform writeonly iimage2D uNext;  // the pass's own unit (frame/bindings.hpp)
layout(location = 1) uniform int uStep;
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = textureSize(uAnchors, 0);
  if (any(greaterThanEqual(p, size))) return;
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
  imageStore(uNext, p, ivec4(best));
}
