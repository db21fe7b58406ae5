#version 450 core
// See volume_line_segment_fate.vert.
#include "frame/frame_uniforms.glsl"
#include "styles/surface.glsl"
#include "style.glsl"
#include "styles/shadows/shadow_lookup.glsl"
#include "styles/emphasis/emphasis.glsl"
layout(location = 9) uniform int uCutBy;  // bit k: the cutter of slot k cuts it
#include "kinds/volumes/volume_sample_cut.glsl"
#include "kinds/volumes/volume_line_fate.glsl"
flat in vec3 vMiddle;
flat in float vImportance;
layout(location = 0) out float outFate;
void main() {
  outFate = float(lineFate(vMiddle, windowOf(vMiddle), vImportance));
}
