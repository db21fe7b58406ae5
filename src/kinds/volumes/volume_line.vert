#version 450 core
// A volume's line segments (volume_lines_pass.hpp), two vertices each, in world coordinates.
#include "frame/frame_uniforms.glsl"
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec4 aPen;         // colour, width in pixels
out vec3 vgWorld;
out vec4 vgPen;
void main() {
  vgWorld = aPosition;
  vgPen = aPen;
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
