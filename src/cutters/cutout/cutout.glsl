// Diepstraten03 §4.5 texture-based cutout: per-fragment signed distances to the wedge's
// planes, perturbed by a jitter pattern; mirrors src/cutters/cutout/cutout_function.cpp.
// Needs frame_uniforms.glsl.
#include "cutters/fate.glsl"
layout(location = LOC_CUTOUT_PLANES) uniform vec4 uCutoutPlanes[4];  // n·x + w > 0 on the removed side
layout(location = LOC_CUTOUT_PLANE_COUNT) uniform int uCutoutPlaneCount;  // 0: this object has no wedge
layout(location = LOC_CUTOUT_ORIGIN) uniform vec4 uCutoutOrigin;  // xyz: origin on the main axis, w: axis length
layout(location = LOC_CUTOUT_AXIS) uniform vec3 uCutoutAxis;
// x: pattern (0 none, 1 sawtooth, 2 noise, 3 image), y: amplitude (world units),
// z: frequency (per world unit), w: noise octaves
layout(location = LOC_CUTOUT_JITTER) uniform vec4 uCutoutJitter;
layout(binding = UNIT_CUTOUT_IMAGE) uniform sampler2D uCutoutImage;  // grey levels, repeat, bilinear

float cutoutLatticeValue(int ix, int iy) {
  uint h = uint(ix) * 0x8da6b343u + uint(iy) * 0xd8163841u;
  h ^= h >> 15;
  h *= 0x2c1b3c6du;
  h ^= h >> 12;
  h *= 0x297a2d39u;
  h ^= h >> 15;
  return float(h >> 8) * (1.0 / 16777216.0);
}

float cutoutValueNoise(vec2 p) {
  vec2 i = floor(p), f = p - i;
  vec2 s = f * f * (3.0 - 2.0 * f);
  int ix = int(i.x), iy = int(i.y);
  float a = cutoutLatticeValue(ix, iy), b = cutoutLatticeValue(ix + 1, iy);
  float c = cutoutLatticeValue(ix, iy + 1), d = cutoutLatticeValue(ix + 1, iy + 1);
  return mix(mix(a, b, s.x), mix(c, d, s.x), s.y);
}

float cutoutFractalNoise(vec2 p, int octaves) {
  float sum = 0.0, weight = 1.0, total = 0.0;
  for (int o = 0; o < octaves; ++o) {
    sum += weight * (2.0 * cutoutValueNoise(p) - 1.0);
    total += weight;
    weight *= 0.5;
    p *= 2.0;
  }
  return sum / total;
}

float cutoutTriangleWave(float t) {
  return 4.0 * abs(t - floor(t) - 0.5) - 1.0;
}

// The jitter displacement in [−1, 1] at world point x (Diepstraten03 §4.5); the pattern is
// CUTOUT_JITTER_PATTERN (Cutout::glslDefines), an object without a wedge never asks.
float cutoutPerturbation(vec3 x) {
  vec3 d = x - uCutoutOrigin.xyz;
  float along = dot(d, uCutoutAxis);
  float radial = length(d - along * uCutoutAxis);
  vec2 uv = vec2(along, radial) * uCutoutJitter.z;
#if CUTOUT_JITTER_PATTERN == 1
  return 0.5 * (cutoutTriangleWave(uv.x) + cutoutTriangleWave(uv.y));
#elif CUTOUT_JITTER_PATTERN == 2
  return cutoutFractalNoise(uv, int(uCutoutJitter.w));
#elif CUTOUT_JITTER_PATTERN == 3
  return 2.0 * textureLod(uCutoutImage, uv, 0.0).r - 1.0;  // one level: texture()'s value
#else
  return 0.0;
#endif
}

// Signed distance to the removed region, perturbed: > 0 removed.
float cutoutDistance(vec3 x) {
  float d = 1e30;
  for (int i = 0; i < uCutoutPlaneCount; ++i) d = min(d, dot(uCutoutPlanes[i].xyz, x) + uCutoutPlanes[i].w);
#if CUTOUT_JITTER_PATTERN == 0
  return d;
#else
  return d + uCutoutJitter.y * cutoutPerturbation(x);
#endif
}

// kDiscard inside the wedge; a back face outside it is seen through the cut (Diepstraten03
// rule 5: the cut wall is visible): the wall lies where the view ray leaves the wedge.
int cutoutFragment(CutFragment f, out vec3 cutPosition, out vec3 cutNormal) {
  vec3 x = f.position;
  bool frontFacing = f.frontFacing;
  if (uCutoutPlaneCount == 0) return kKeep;
  if (cutoutDistance(x) > 0.0) return kDiscard;
  if (frontFacing) return kKeep;
  vec3 from = viewRayOrigin(x);
  vec3 v = x - from;
  // Clip the segment from → x against every half-space: [tIn, tOut] inside the wedge.
  float tIn = 0.0, tOut = 1.0;
  int exitPlane = 0, keeper = 0;
  for (int i = 0; i < uCutoutPlaneCount; ++i) {
    float d0 = dot(uCutoutPlanes[i].xyz, from) + uCutoutPlanes[i].w;
    float dv = dot(uCutoutPlanes[i].xyz, v);
    if (dv > 0.0) {
      tIn = max(tIn, -d0 / dv);
    } else if (dv < 0.0) {
      float t = -d0 / dv;
      if (t < tOut) tOut = t, exitPlane = i;
    } else if (d0 <= 0.0) {
      tOut = -1.0;
    }
  }
  if (tIn < tOut) {
    cutPosition = from + tOut * v;
    cutNormal = uCutoutPlanes[exitPlane].xyz;
  } else {
    // Jitter moved the boundary past the planes: the wall at the fragment, facing the
    // plane that keeps it.
    float least = 1e30;
    for (int i = 0; i < uCutoutPlaneCount; ++i) {
      float di = dot(uCutoutPlanes[i].xyz, x) + uCutoutPlanes[i].w;
      if (di < least) least = di, keeper = i;
    }
    cutPosition = x;
    cutNormal = uCutoutPlanes[keeper].xyz;
  }
  return kCutSurface;
}

// The span of a view ray inside the wedge shrunk by the jitter's amplitude, which it removes
// whatever the pattern (cutters/cutter.hpp): every plane's n·x + w exceeds the amplitude there.
// Shrunk by a hair so that samples on its ends are decided by cutoutFragment.
#define CUTOUT_REMOVED_SPAN
vec2 cutoutRemovedSpan(vec3 origin, vec3 direction, vec2 window, vec2 range) {
  if (uCutoutPlaneCount == 0) return vec2(1e30, -1e30);
  float margin = uCutoutJitter.x == 0.0 ? 0.0 : abs(uCutoutJitter.y);
  float tIn = -1e30, tOut = 1e30;
  for (int i = 0; i < uCutoutPlaneCount; ++i) {
    float d0 = dot(uCutoutPlanes[i].xyz, origin) + uCutoutPlanes[i].w - margin;
    float dv = dot(uCutoutPlanes[i].xyz, direction);
    if (dv > 0.0) tIn = max(tIn, -d0 / dv);
    else if (dv < 0.0) tOut = min(tOut, -d0 / dv);
    else if (d0 <= 0.0) return vec2(1e30, -1e30);
  }
  return vec2(tIn + 1e-4 * (1.0 + abs(tIn)), tOut - 1e-4 * (1.0 + abs(tOut)));
}

// The G-buffer channel cutoutDistance: the signed distance at a fragment of an exterior object.
float cutoutChannel0(CutFragment f) {
  return uCutoutPlaneCount > 0 ? cutoutDistance(f.position) : uintBitsToFloat(0x7fc00000u);
}
