// A unit normal and a line weight in one 32-bit word: the format (R32UI) of the targets the
// feature lines read (the G-buffer's, the ghost geometry's, a translucent layer's). The normal
// as octahedral coordinates (Cigolle et al. 2014, "A Survey of Efficient Representations for
// Independent Unit Vectors", §3.3), 12 bits each with 0 exact, so the axes are exact and any
// other normal is at most ~0.06° off (half floats: ~0.02°); the weight, in [0, 1], in the top
// 8 bits. Half the bytes of an RGBA16F normal: llvmpipe's geometry pass pays for each byte a
// sample it stores (bench/RESULTS.md, "What the G-buffer's targets cost"). A cleared word (0)
// has weight 0.
#ifndef FRAME_NORMAL_WEIGHT_GLSL
#define FRAME_NORMAL_WEIGHT_GLSL
const float kOctahedralSteps = 2047.0;  // per side of 0: codes 0 … 4094

vec2 signNotZero(vec2 v) {
  return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0);
}

// A unit normal's octahedral coordinates, in [−1, 1]², and back.
vec2 octahedralEncode(vec3 n) {
  vec2 e = n.xy / max(abs(n.x) + abs(n.y) + abs(n.z), 1e-30);
  return n.z < 0.0 ? (1.0 - abs(e.yx)) * signNotZero(e) : e;
}

vec3 octahedralDecode(vec2 e) {
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * signNotZero(n.xy);
  return normalize(n);
}

uint packNormalWeight(vec3 n, float weight) {
  // Masked: a NaN normal may convert to any bits, and must leave the weight's alone.
  vec2 e = clamp(octahedralEncode(n), -1.0, 1.0);
  uvec2 q = uvec2(round(e * kOctahedralSteps + kOctahedralSteps)) & 0xfffu;
  return q.x | (q.y << 12) | (uint(round(clamp(weight, 0.0, 1.0) * 255.0)) << 24);
}

vec3 unpackNormal(uint word) {
  vec2 q = vec2(word & 0xfffu, (word >> 12) & 0xfffu);
  return octahedralDecode((q - kOctahedralSteps) / kOctahedralSteps);
}

float unpackWeight(uint word) {
  return float(word >> 24) / 255.0;
}
#endif
