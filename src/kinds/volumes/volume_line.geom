#version 450 core
// A segment as a screen-space quad of its width (plus the halo's on each side), extended by
// half the width at both ends so that the segments of a polyline join; none for a segment the
// cutters remove, or that is hidden unless hidden lines are dimmed or shown (its middle's fate,
// volume_line_segment_fate.frag, this frame). The halo's quad is pushed away from the eye, so
// that a nearer line's halo hides what passes behind it (Appel et al. 1979).
#include "frame/frame_uniforms.glsl"
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;
layout(binding = 6) uniform sampler2D uSegmentFates;  // 0 removed, 1 hidden, 2 visible
layout(location = 23) uniform int uHalo;              // 1: the halo pass
layout(location = 25) uniform int uHidden;            // 0 removed, 1 dimmed, 2 shown
layout(location = 26) uniform float uDimmedOpacity;
layout(location = 30) uniform float uExtra;      // pixels added on each side (the halo)
layout(location = 31) uniform float uDepthPush;  // world units the quad is pushed away
layout(location = 32) uniform int uFateWidth;
layout(location = 34) uniform int uFirstSegment;  // of this draw
in vec3 vgWorld[];
in vec4 vgPen[];
out vec3 vColor;
flat out float vOpacity;
noperspective out float vAcross;  // pixels from the line's middle
flat out float vHalfWidth;  // of what this pass draws: the line, or it and its halo
void main() {
  int segment = uFirstSegment + gl_PrimitiveIDIn;
  int fate = int(texelFetch(uSegmentFates, ivec2(segment % uFateWidth, segment / uFateWidth), 0).r + 0.5);
  if (fate == 0 || (fate == 1 && (uHidden == 0 || uHalo == 1))) return;
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
      vColor = vgPen[i].rgb;
      vOpacity = fate == 1 && uHidden == 1 ? uDimmedOpacity : 1.0;
      vAcross = float(s) * reach;
      vHalfWidth = 0.5 * vgPen[0].w + uExtra;
      EmitVertex();
    }
  }
  EndPrimitive();
}
