#version 450 core
// The clip-mask AOV, when it is read: each object the surfaces reach, drawn whole without a
// depth test over the geometry pass's samples, marks the pixels where eq. 1 clips its surface
// (the geometry pass leaves the parts a surface removes whole undrawn: Cutter::slab).
#include "frame/frame_uniforms.glsl"
#include "cutters/clip_surfaces/clip_surfaces.glsl"
layout(binding = IMAGE_CLIP_MASK, r32ui) uniform coherent uimage2D uClipMask;
in vec3 vWorldPosition;
void main() {
  if (clippedBySurfaces(vWorldPosition, -1)) imageAtomicMax(uClipMask, ivec2(gl_FragCoord.xy), 1u);
}
