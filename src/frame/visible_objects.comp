#version 450 core
// Marks every object that owns a sample of the G-buffer's object ids: the objects the next
// frame draws before it tests the others (occlusion_culling.hpp).
#include "frame/samples.glsl"
// Groups of 1024: llvmpipe's cost per group made 8×8 ones 1.7× slower (bench/RESULTS.md).
layout(local_size_x = 64, local_size_y = 16) in;
layout(binding = 0) uniform ISAMPLER_MS uObjectId;  // -1: background
layout(std430, binding = SSBO_VISIBLE_OBJECTS) writeonly buffer VisibleObjects {
  uint visible[];
};
layout(location = 0) uniform int uSamples;
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, sizeMS(uObjectId)))) return;
  for (int s = 0; s < uSamples; ++s) {
    int id = texelFetch(uObjectId, p, s).r;
    if (id >= 0 && id < visible.length()) visible[id] = 1u;
  }
}
