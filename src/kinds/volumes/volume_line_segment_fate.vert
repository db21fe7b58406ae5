#version 450 core
// The fate of each segment's middle (volume_line_segment_fate.frag) into texel i of a target
// `uFateWidth` texels wide, read by the lines' geometry shader and by their vector output
// (volume_lines_pass.hpp).
layout(location = 0) in vec3 aMiddle;
layout(location = 2) in float aImportance;
layout(location = 32) uniform int uFateWidth;
layout(location = 33) uniform vec2 uFateSize;
flat out vec3 vMiddle;
flat out float vImportance;
void main() {
  vMiddle = aMiddle;
  vImportance = aImportance;
  vec2 texel = vec2(gl_VertexID % uFateWidth, gl_VertexID / uFateWidth) + 0.5;
  gl_Position = vec4(texel / uFateSize * 2.0 - 1.0, 0.0, 1.0);
  gl_PointSize = 1.0;
}
