// What a cutter decides about a fragment, and which cutters cut an object (a bit each; the
// renderer sets uCutBy per object). Included by every cutter's GLSL.
#ifndef CUTTERS_FATE_GLSL
#define CUTTERS_FATE_GLSL
const int kKeep = 0, kDiscard = 1, kCutSurface = 2;
const int kCutByAdaptive = 1, kCutByCutout = 2, kCutByBreakaway = 4, kCutByClipSurfaces = 8,
          kCutByTerrain = 16, kCutByShaftOuter = 32, kCutByShaftInner = 64;
#endif
