#version 450 core
// Konev18 §5's billboards as shadow casters: drawn in the key light's "shadowMap" pass with
// the light's frame uniforms, so billboard.geom turns each quad to the light and it covers
// the tube's outline seen from the light (2r wide).
#include "frame/frame_uniforms.glsl"
#include "pipes.glsl"
in vec3 vWorld;
in vec3 vAxis;
in float vArc;
flat in vec3 vDirection;
flat in int vPipe;
layout(location = 0) out float outLightDepth;
void main() {
  vec3 p = vWorld;
  if (inCutStretch(vPipe, vArc)) {
    // §6: an opened stretch is the lower half-tube, a trough. Seen from the light its outline
    // is the quad's up to the rims on the upper side: a point d from the axis, at ŝ = d̂·up,
    // belongs to it where |d| ≤ r √(1 − ŝ²), i.e. |d|⁴ ≤ r² (|d|² − (d·up)²). Straight down
    // that is the whole width, from the side the lower half.
    vec3 up = cutUp(vDirection);
    vec3 d = vWorld - vAxis;
    float r = outerRadius(vPipe), dd = dot(d, d), h = dot(d, up);
    if (h > 0.0 && dd * dd > r * r * (dd - h * h)) discard;
    // The caster lies at the trough's bottom instead of through its axis, so that light falls
    // onto the inside and the water (an approximation: oblique light moves the shadow by up to
    // r tan θ).
    p -= r * up;
    vec4 clip = uViewProjection * vec4(p, 1.0);
    gl_FragDepth = 0.5 * clip.z / clip.w + 0.5;
  } else {
    gl_FragDepth = gl_FragCoord.z;
  }
  outLightDepth = -(uView * vec4(p, 1.0)).z;  // as src/styles/shadows/shadow_map.frag
}
