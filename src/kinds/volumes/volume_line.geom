#version 450 core
// A segment as a screen-space quad of its width (plus the halo's on each side), extended by
// half the width at both ends so that the segments of a polyline join. The halo's quad is
// pushed away from the eye, so that a nearer line's halo hides what passes behind it (Appel
// et al. 1979).
#include "frame/frame_uniforms.glsl"
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;
layout(location = 30) uniform float uExtra;      // pixels added on each side (the halo)
layout(location = 31) uniform float uDepthPush;  // world units the quad is pushed away
in vec3 vgWorld[];
in vec4 vgPen[];
in float vgImportance[];
out vec3 vWorld;
out vec3 vColor;
flat out float vImportance;
noperspective out float vAcross;  // pixels from the line's middle
flat out float vHalfWidth;  // of what this pass draws: the line, or it and its halo
void main() {
  vec4 c0 = gl_in[0].gl_Position, c1 = gl_in[1].gl_Position;
  if (c0.w <= 0.0 || c1.w <= 0.0) return;  // behind the eye
  vec2 w0 = (c0.xy / c0.w * 0.5 + 0.5) * uViewport.xy, w1 = (c1.xy / c1.w * 0.5 + 0.5) * uViewport.xy;
  vec2 d = w1 - w0;
  vec2 along = dot(d, d) > 1e-12 ? normalize(d) : vec2(1.0, 0.0), across = vec2(-along.y, along.x);
  float reach = 0.5 * vgPen[0].w + uExtra + 0.5;  // + half a pixel of antialiasing
  for (int i = 0; i < 2; ++i) {
    vec3 p = vgWorld[i];
    vec3 away = uCounts.y == 1 ? uForward.xyz : normalize(p - uEye.xyz);
    vec4 c = uViewProjection * vec4(p + uDepthPush * away, 1.0);
    vec2 end = (i == 0 ? w0 - along * reach : w1 + along * reach);
    for (int s = -1; s <= 1; s += 2) {
      vec2 window = end + float(s) * reach * across;
      gl_Position = vec4((window * uViewport.zw * 2.0 - 1.0) * c.w, c.z, c.w);
      vWorld = p;
      vColor = vgPen[i].rgb;
      vImportance = vgImportance[0];
      vAcross = float(s) * reach;
      vHalfWidth = 0.5 * vgPen[0].w + uExtra;
      EmitVertex();
    }
  }
  EndPrimitive();
}
