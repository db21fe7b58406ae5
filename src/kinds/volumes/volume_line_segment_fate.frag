#version 450 core
// What becomes of a segment of a volume's lines (volume_lines_pass.hpp), decided at its
// middle: 0 the cutters remove it (or it lies off screen), 1 it is hidden (behind the nearest
// drawn isosurface or an opaque surface, more than the tolerance), 2 it is visible.
#include "frame/frame_uniforms.glsl"
#include "styles/surface.glsl"
#include "style.glsl"
#include "styles/shadows/shadow_lookup.glsl"
#include "styles/emphasis/emphasis.glsl"
layout(location = 9) uniform int uCutBy;  // bit k: the cutter of slot k cuts it
#include "kinds/volumes/volume_sample_cut.glsl"
layout(binding = 5) uniform sampler2D uLineSurfaces;  // volume_line_surfaces.frag's view depth
layout(location = 22) uniform float uLineTolerance;    // world units

int lineFate(vec3 p, vec2 window, float importance) {
  if (any(lessThan(window, vec2(0.0))) || any(greaterThanEqual(window, uViewport.xy))) return 0;
  gSampleImportance = importance;
  vec3 cutNormal;
  if (uCutBy != 0 && fateAt(p, window, true, cutNormal) == kDiscard) return 0;
  // The deepest surface within two pixels: at a contour the surface turns away from the view,
  // and the ray through the line's own pixel may meet it in front of the line.
  ivec2 centre = ivec2(window), last = ivec2(uViewport.xy) - 1;
  float surface = 0.0;
  for (int y = -2; y <= 2; ++y)
    for (int x = -2; x <= 2; ++x)
      surface = max(surface, texelFetch(uLineSurfaces, clamp(centre + ivec2(x, y), ivec2(0), last), 0).r);
  return -(uView * vec4(p, 1.0)).z > surface + uLineTolerance ? 1 : 2;
}

flat in vec3 vMiddle;
flat in float vImportance;
layout(location = 0) out float outFate;
void main() {
  vec4 clip = uViewProjection * vec4(vMiddle, 1.0);
  vec2 window = (clip.xy / clip.w * 0.5 + 0.5) * uViewport.xy;
  outFate = clip.w > 0.0 ? float(lineFate(vMiddle, window, vImportance)) : 0.0;
}
