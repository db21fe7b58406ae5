// Trapp13 §4.3–4.4: a fragment is discarded where the enabled clip surfaces clip it.
#include "clip_surfaces.glsl"
// 1 where a fragment was removed by a clip surface (at any depth): the clip-mask AOV.
layout(binding = 0, r32ui) uniform coherent uimage2D uClipMask;

int clipSurfacesFragment(vec3 p) {
  if (!clippedBySurfaces(p, -1)) return kKeep;
  imageAtomicMax(uClipMask, ivec2(gl_FragCoord.xy), 1u);
  return kDiscard;
}
