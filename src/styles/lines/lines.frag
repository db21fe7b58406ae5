#version 450 core
// Image-space feature lines, evaluated per MSAA sample and averaged into a coverage value so
// the lines come out anti-aliased:
// - silhouettes: the nearer side of an object-id change (unless the two objects are coplanar
//   and meet at no crease), or of a view-depth discontinuity within one object (relative
//   second difference of inverse view depth, or of depth for orthographic views, across the
//   pixel above a threshold: zero on planes at any slant);
// - creases: normals of one object meeting at more than the crease angle;
// - with CUT_OUTLINES, the outline of the cut surfaces (Burns08 §4.2): cut-mask pixels next
//   to a pixel outside the mask.
// A line's weight is stored with the normal: 0 for objects without lines, a fade for ghost
// lines.
#include "frame/samples.glsl"
#include "frame/frame_uniforms.glsl"
#include "frame/normal_weight.glsl"
layout(binding = 0) uniform USAMPLER_MS uNormal;    // world normal and line weight
layout(binding = 1) uniform ISAMPLER_MS uObjectId;  // the id (-1: background), view depth bits
layout(location = 0) uniform int uSamples;
layout(location = 1) uniform int uRadius;            // line width in pixels
layout(location = 2) uniform float uCreaseCos;       // cos(crease angle)
layout(location = 3) uniform float uDepthThreshold;
layout(location = 4) uniform int uSilhouettes;
layout(location = 5) uniform int uCreases;
layout(location = 0) out float outCoverage;
#ifdef CUT_OUTLINES
layout(binding = 2) uniform SAMPLER_MS uCutMask;
layout(location = 1) out float outOutlineCoverage;

float outline(ivec2 p, int s) {
  if (texelFetch(uCutMask, p, s).r < 0.5) return 0.0;
  ivec2 last = sizeMS(uCutMask) - 1;
  const ivec2 offsets[4] = ivec2[4](ivec2(1, 0), ivec2(0, 1), ivec2(-1, 0), ivec2(0, -1));
  for (int r = 1; r <= uRadius; ++r)
    for (int k = 0; k < 4; ++k)
      if (texelFetch(uCutMask, clamp(p + r * offsets[k], ivec2(0), last), s).r < 0.5) return 1.0;
  return 0.0;
}
#endif

const float kFar = 1e30;

float viewDepth(ivec2 q, int s, out int id) {
  ivec2 v = texelFetch(uObjectId, q, s).rg;
  id = v.r;
  return id < 0 ? kFar : intBitsToFloat(v.g);
}

float edge(ivec2 p, int s) {
  int id;
  float d = viewDepth(p, s, id);
  if (id < 0) return 0.0;
  uint word = texelFetch(uNormal, p, s).r;
  float weight = unpackWeight(word);
  if (weight <= 0.0) return 0.0;
  vec3 n = unpackNormal(word);
  ivec2 last = sizeMS(uObjectId) - 1;
  const ivec2 offsets[4] = ivec2[4](ivec2(1, 0), ivec2(0, 1), ivec2(-1, 0), ivec2(0, -1));
  for (int r = 1; r <= uRadius; ++r) {
    for (int k = 0; k < 4; ++k) {
      ivec2 q = clamp(p + r * offsets[k], ivec2(0), last);
      int idq;
      float dq = viewDepth(q, s, idq);
      if (uSilhouettes != 0 && dq > d) {
        // A different object counts if it is really behind, or if it meets this one at a
        // crease (an object standing on another: their depths at the contact differ by less
        // than any margin). Coplanar objects (a door in its wall) z-fight, their ids
        // alternating pixel by pixel: no line between them, also where their shading normals
        // differ a little.
        if (idq != id && (dq > d * (1.0 + 1e-4) ||
                          dot(n, unpackNormal(texelFetch(uNormal, q, s).r)) < uCreaseCos))
          return weight;
        int idOpposite;
        float dOpposite = viewDepth(clamp(p - r * offsets[k], ivec2(0), last), s, idOpposite);
        // On a plane, inverse depth (perspective) or depth (orthographic) is affine in screen
        // space, so its second difference is zero however grazing the plane, and large across
        // a depth discontinuity.
        float jump = uCounts.y == 1 ? (dq + dOpposite) / d - 2.0 : d / dq + d / dOpposite - 2.0;
        if (idOpposite == id && abs(jump) > uDepthThreshold) return weight;
      }
      // Creases: compare with the +x and +y neighbours only, so a crease is one line thick.
      // Equal normals meet at 0°, which no crease angle is less than: not decoded.
      if (uCreases != 0 && k < 2 && idq == id) {
        uint wordQ = texelFetch(uNormal, q, s).r;
        if (((wordQ ^ word) & 0xffffffu) != 0u && dot(n, unpackNormal(wordQ)) < uCreaseCos)
          return weight;
      }
    }
  }
  return 0.0;
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float coverage = 0.0;
  for (int s = 0; s < uSamples; ++s) coverage += edge(p, s);
  outCoverage = coverage / float(uSamples);
#ifdef CUT_OUTLINES
  float outlines = 0.0;
  for (int s = 0; s < uSamples; ++s) outlines += outline(p, s);
  outOutlineCoverage = outlines / float(uSamples);
#endif
}
