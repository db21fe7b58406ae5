// What a cutter decides about a fragment (cutters/cutter.hpp), and what it decides it from.
// Included by every cutter's GLSL.
#ifndef CUTTERS_FATE_GLSL
#define CUTTERS_FATE_GLSL
const int kKeep = 0, kDiscard = 1, kCutSurface = 2;
// The window position (x, y, depth) of what is decided: the fragment's, or a volume's ray
// sample's (kinds/volumes/volume.frag defines it as the sample's before including cutters).
#ifndef CUT_FRAG_COORD
#define CUT_FRAG_COORD gl_FragCoord
#endif
// CUT_VOLUME_SAMPLE, defined by kinds/volumes/volume.frag: what is decided is a volume's ray
// sample (a cutter that covers its cuts by geometry of its own, as Trapp13's caps, gives such a
// sample asked as a back face the cut's normal).
// A fragment of a cut object: world position, interpolated world normal (not normalised), and
// the side seen.
struct CutFragment {
  vec3 position;
  vec3 normal;
  bool frontFacing;
};
#endif
