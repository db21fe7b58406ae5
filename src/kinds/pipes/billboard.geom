#version 450 core
// Konev18 §5, eqs. 4–10: one camera-facing quad per segment P_i P_{i+1}, from a line strip
// with adjacency whose ends repeat the first and last node (an end: eqs. 4 and 6). Mirrors
// billboardUp / billboardFaceNormal in src/geometry/pipe_network.cpp.
#include "frame/frame_uniforms.glsl"
#include "pipes.glsl"
layout(lines_adjacency) in;
layout(triangle_strip, max_vertices = 4) out;
in vec3 gPosition[];
in float gArc[];
flat in int gPipe[];
out vec3 vWorld;
out vec3 vAxis;      // the axis point level with the fragment
out vec3 vNormal;    // N: ±û at the upper and lower vertices, interpolated (eq. 11)
out float vArc;
flat out vec3 vFace;       // F_a (eqs. 8–10)
flat out vec3 vDirection;  // n̂ of the segment
flat out int vPipe;

// The direction the quad's edge at `p` is built around: the normalised mean of the two
// segments (eq. 5), or the segment's own at an end (eqs. 4, 6).
vec3 nodeDirection(vec3 other, vec3 p, vec3 n, bool after) {
  if (distance(other, p) < 1e-6) return n;
  vec3 m = n + (after ? normalize(other - p) : normalize(p - other));
  return dot(m, m) < 1e-8 ? n : normalize(m);
}

vec3 billboardUp(vec3 p, vec3 direction) {
  vec3 v = uCounts.y == 1 ? uForward.xyz : normalize(p - uEye.xyz);
  vec3 u = cross(v, direction);  // eqs. 4–6
  return dot(u, u) < 1e-10 ? normalize(cross(direction, vec3(0.0, 1.0, 0.0) + 1e-3)) : normalize(u);
}

void emit(vec3 axis, vec3 u, float r, float arc, float across) {
  vWorld = axis + across * r * u;  // eq. 7: the lower vertex at −û
  vAxis = axis;
  vNormal = across * u;
  vArc = arc;
  gl_Position = uViewProjection * vec4(vWorld, 1.0);
  EmitVertex();
}

void main() {
  vec3 p0 = gPosition[1], p1 = gPosition[2];
  vec3 n = normalize(p1 - p0);
  vec3 u0 = billboardUp(p0, nodeDirection(gPosition[0], p0, n, false));
  vec3 u1 = billboardUp(p1, nodeDirection(gPosition[3], p1, n, true));
  int pipe = gPipe[1];
  float r = outerRadius(pipe);
  vPipe = pipe;
  vDirection = n;
  vFace = normalize(cross(normalize(u0 + u1), n));  // eqs. 8–10
  emit(p0, u0, r, gArc[1], -1.0);
  emit(p0, u0, r, gArc[1], 1.0);
  emit(p1, u1, r, gArc[2], -1.0);
  emit(p1, u1, r, gArc[2], 1.0);
  EndPrimitive();
}
