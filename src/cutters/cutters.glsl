// The active cutters composed into one per-fragment decision for the geometry pass; each is
// compiled in by its define (CUTTER_ADAPTIVE, CUTTER_CUTOUT, CUTTER_BREAKAWAY,
// CUTTER_CLIP_SURFACES, CUTTER_TERRAIN, CUTTER_SHAFT_WEDGE). A fragment is
// removed when any cutter that cuts its object removes it; a back face seen through a cut
// takes the first cutter's cut surface. Needs frame_uniforms.glsl.
#include "fate.glsl"
#ifdef CUTTER_ADAPTIVE
#include "adaptive/clip.glsl"
#endif
#ifdef CUTTER_CUTOUT
#include "cutout/cutout.glsl"
#endif
#ifdef CUTTER_BREAKAWAY
#include "breakaway/breakaway.glsl"
#endif
#ifdef CUTTER_CLIP_SURFACES
#include "clip_surfaces/clip_fragment.glsl"
#endif
#ifdef CUTTER_TERRAIN
#include "terrain_opening/terrain_opening.glsl"
#endif
#ifdef CUTTER_SHAFT_WEDGE
#include "shaft_wedge/shaft_wedge.glsl"
#endif

int cutFragment(int cutBy, vec3 x, vec3 normal, bool frontFacing, out vec3 cutPosition,
                out vec3 cutNormal) {
  cutPosition = vec3(0.0);
  cutNormal = vec3(0.0);
  int fate = kKeep;
  vec3 p, n;
  int f;
#ifdef CUTTER_ADAPTIVE
  if ((cutBy & kCutByAdaptive) != 0) {
    f = adaptiveFragment(frontFacing, p, n);
    if (f == kDiscard) return kDiscard;
    if (f == kCutSurface && fate == kKeep) fate = f, cutPosition = p, cutNormal = n;
  }
#endif
#ifdef CUTTER_CUTOUT
  if ((cutBy & kCutByCutout) != 0) {
    f = cutoutFragment(x, frontFacing, p, n);
    if (f == kDiscard) return kDiscard;
    if (f == kCutSurface && fate == kKeep) fate = f, cutPosition = p, cutNormal = n;
  }
#endif
#ifdef CUTTER_BREAKAWAY
  if ((cutBy & kCutByBreakaway) != 0) {
    f = breakawayFragment(frontFacing, p, n);
    if (f == kDiscard) return kDiscard;
    if (f == kCutSurface && fate == kKeep) fate = f, cutPosition = p, cutNormal = n;
  }
#endif
#ifdef CUTTER_TERRAIN
  if ((cutBy & kCutByTerrain) != 0) {
    f = terrainFragment(x, p, n);
    if (f == kDiscard) return kDiscard;
    if (f == kCutSurface && fate == kKeep) fate = f, cutPosition = p, cutNormal = n;
  }
#endif
#ifdef CUTTER_SHAFT_WEDGE
  if ((cutBy & (kCutByShaftOuter | kCutByShaftInner)) != 0) {
    f = shaftFragment((cutBy & kCutByShaftInner) != 0, x, normal, frontFacing, p, n);
    if (f == kDiscard) return kDiscard;
    if (f == kCutSurface && fate == kKeep) fate = f, cutPosition = p, cutNormal = n;
  }
#endif
#ifdef CUTTER_CLIP_SURFACES
  // Trapp13 clips the solid; its cut is covered by the caps, not by cut surfaces.
  if ((cutBy & kCutByClipSurfaces) != 0 && clipSurfacesFragment(x) == kDiscard) return kDiscard;
#endif
  return fate;
}
