// Trapp13 §4.3–4.4: a fragment is discarded where the enabled clip surfaces clip it.
#include "clip_surfaces.glsl"
// 1 where a fragment was removed by a clip surface (at any depth): the clip-mask AOV.
layout(binding = IMAGE_CLIP_MASK, r32ui) uniform coherent uimage2D uClipMask;

int clipSurfacesFragment(CutFragment f, out vec3 cutPosition, out vec3 cutNormal) {
  // Trapp13 clips the solid; its cut is covered by the caps, not by cut surfaces.
  cutPosition = f.position;
  cutNormal = vec3(0.0);
  if (!clippedBySurfaces(f.position, -1)) return kKeep;
  imageAtomicMax(uClipMask, ivec2(CUT_FRAG_COORD.xy), 1u);
  return kDiscard;
}
