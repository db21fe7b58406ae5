#version 450 core
// A volume's lines over the final colour (volume_lines_pass.hpp): each fragment removed where
// the cutters remove its point, hidden behind the nearest drawn isosurface (removed, faint or
// shown), antialiased across its width. The halo pass draws the halos of the visible points.
#include "frame/frame_uniforms.glsl"
#include "styles/surface.glsl"
#include "style.glsl"
#include "styles/shadows/shadow_lookup.glsl"
#include "styles/emphasis/emphasis.glsl"
layout(location = 9) uniform int uCutBy;  // bit k: the cutter of slot k cuts it
#include "kinds/volumes/volume_sample_cut.glsl"
#include "kinds/volumes/volume_line_fate.glsl"
layout(location = 23) uniform int uHalo;          // 1: the halo pass
layout(location = 24) uniform vec3 uHaloColor;
layout(location = 25) uniform int uHidden;        // 0 removed, 1 dimmed, 2 shown
layout(location = 26) uniform float uDimmedOpacity;
in vec3 vWorld;
in vec3 vColor;
flat in float vImportance;
noperspective in float vAcross;
flat in float vHalfWidth;
layout(location = 0) out vec4 outColor;  // premultiplied, blended over the final colour
layout(location = 1) out float outCoverage;
void main() {
  int fate = lineFate(vWorld, windowOf(vWorld), vImportance);
  if (fate == 0 || (fate == 1 && (uHidden == 0 || uHalo == 1))) discard;
  float alpha = clamp(vHalfWidth + 0.5 - abs(vAcross), 0.0, 1.0);
  if (fate == 1 && uHidden == 1) alpha *= uDimmedOpacity;
  if (alpha <= 0.0) discard;
  outColor = vec4((uHalo == 1 ? uHaloColor : vColor) * alpha, alpha);
  outCoverage = uHalo == 1 ? 0.0 : alpha;
}
