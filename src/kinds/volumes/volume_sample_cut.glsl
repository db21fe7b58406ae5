// The active cutters composed for a volume's programs, which decide points that are no
// fragments of their own: ray samples (volume.frag) and points of the volume's lines
// (volume_line.frag). Needs frame_uniforms.glsl, the style and the emphasis before it, and the
// program's uCutBy (bit k: the cutter of slot k cuts it) declared before it.
// The point the cutters decide: its window position and its material's importance.
vec4 gSampleCoord;
float gSampleImportance;
#define CUT_FRAG_COORD gSampleCoord
#define CUT_IMPORTANCE gSampleImportance
// Cutters that cover their cuts by geometry of their own (Trapp13's caps) give a volume's
// samples the cut's normal instead.
#define CUT_VOLUME_SAMPLE
#include "frame/gbuffer_channels.glsl"
#include "cutters/composition.glsl"

// The cutters' fate of the point p seen at window position `window` (pixels), asked as a front
// face, or as a back face for the cut's normal: a sample just behind removed material stands
// where a back face would show the cut surface (Burns11 §5.2.4.1).
int fateAt(vec3 p, vec2 window, bool frontFacing, out vec3 cutNormal) {
  vec4 clip = uViewProjection * vec4(p, 1.0);
  gSampleCoord = vec4(window, clip.z / clip.w * 0.5 + 0.5, 1.0);
  vec3 cutPosition;
  int cutter;
  return cutFragment(uCutBy, -1, CutFragment(p, vec3(0.0), frontFacing), cutPosition,
                     cutNormal, cutter);
}
