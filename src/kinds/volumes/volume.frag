#version 450 core
// Ray casting of one scene volume over the final colour (kinds/volumes/volume_kind.hpp): the
// view ray through the pixel centre, from where it enters the volume's box to where it
// leaves it or meets the opaque surfaces (sample 0 of the G-buffer's depth), sampled every
// uStep world units from a per-pixel jittered start. Each sample is decided by the cutters
// that cut the volume, like a fragment at its position (cutters/cutter.hpp), and classified by
// the transfer function. Mirrored on the CPU by volume_ray_cast.cpp. Variants (defines):
// TRANSFER_2D, a transfer function of value × gradient magnitude; SHADOWS, the shadow ray;
// MODE (0 composite, 1 maximum, 2 isosurface); SHADING, gradient normals shaded by the style;
// CUT, some cutter cuts this volume. They are constants, not uniforms, because llvmpipe runs
// both sides of a branch on a uniform: every sample would pay for the modes it is not in.
#include "frame/samples.glsl"
#include "frame/frame_uniforms.glsl"
#include "styles/surface.glsl"
#include "style.glsl"
#include "styles/shadows/shadow_lookup.glsl"
#include "styles/emphasis/emphasis.glsl"
layout(location = 9) uniform int uCutBy;  // bit k: the cutter of slot k cuts it
#include "kinds/volumes/volume_sample_cut.glsl"
#include "kinds/volumes/volume_ray.glsl"

layout(binding = 0) uniform SAMPLER_MS uOpaqueDepth;
// Where the volumes drawn before this one stopped the rays: their nearest hit, entry and
// accumulated opacity (copies of the AOVs), so that overlapping volumes hide each other.
layout(binding = 5) uniform sampler2D uPreviousHit;
layout(binding = 6) uniform sampler2D uPreviousEntry;
layout(binding = 7) uniform sampler2D uPreviousOpacity;
layout(binding = UNIT_VOLUME_PREVIOUS_TRANSMITTANCE) uniform sampler2D uPreviousTransmittance;
// Per block of kBlock³ voxels: 0 where every value its samples can interpolate is clear.
layout(binding = UNIT_VOLUME_OCCUPANCY) uniform usampler3D uOccupancy;
const float kBlock = 8.0;  // VolumeKind's kBlock
layout(location = 2) uniform float uStep;            // world units
layout(location = 3) uniform float uOpacityExponent; // step / opacity distance (both in voxels)
const int kMode = MODE;
layout(location = 6) uniform float uIsoValue;
#ifdef SHADING
const bool kShading = true;
#else
const bool kShading = false;
#endif
#ifdef CUT
const bool kCut = true;
#else
const bool kCut = false;
#endif
layout(location = 8) uniform int uJitter;
layout(location = 10) uniform int uInterest;         // 1: of interest (emphasis as I = 1)
layout(location = 14) uniform float uVoxel;          // the smallest spacing, world units

layout(location = 0) out vec4 outColor;  // premultiplied, blended over the final colour
layout(location = 1) out float outEntryDepth;
layout(location = 2) out float outHitDepth;
layout(location = 3) out float outOpacity;
layout(location = 4) out float outLightTransmittance;

const float kNaN = uintBitsToFloat(0x7fc00000u);

// An integer hash of the pixel (the same in volume_ray_cast.cpp): the jitter is fixed
// per pixel, so still frames and their goldens repeat exactly.
float pixelJitter(uvec2 p) {
  uint h = (p.x * 0x8da6b343u) ^ (p.y * 0xd8163841u);
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return float(h >> 8) * (1.0 / 16777216.0);
}

// The unit normal at a sample, against the gradient of the values (zero where they are
// flat). The gradient is precomputed per voxel (central differences) and interpolated.
vec3 normalAt(vec3 index) {
  vec3 g = gradientAt(index);
  return dot(g, g) > 1e-20 ? -normalize(g) : vec3(0.0);
}

int sampleFate(vec3 p, bool frontFacing, out vec3 cutNormal) {
  return fateAt(p, gl_FragCoord.xy, frontFacing, cutNormal);
}

// The fraction of the key light that reaches p through this volume's material (Beer–Lambert
// along the ray towards the light, up to a point light): every second step, the transfer
// function's opacity corrected for that length. Material the cutters remove casts no shadow,
// so light falls into the cut; a sample off screen or behind the eye, where the cutters have
// no buffers, is kept.
#ifdef SHADOWS
float volumeTransmittance(vec3 p) {
  vec3 l = towardsLight(0, p);
  vec3 o = (uWorldToIndex * vec4(p, 1.0)).xyz, d = mat3(uWorldToIndex) * l;
  vec3 a = (vec3(-0.5) - o) / d, b = (uDims - 0.5 - o) / d;
  float tExit = min(min(max(a.x, b.x), max(a.y, b.y)), max(a.z, b.z));
  if (uLightVector[0].w != 0.0) tExit = min(tExit, distance(p, uLightVector[0].xyz));
  float step = 2.0 * uStep, exponent = 2.0 * uOpacityExponent, transmittance = 1.0;
  for (float t = step; t < tExit && transmittance > 0.004; t += step) {
    vec3 index = o + t * d;
    vec2 u = transferCoordinates(valueAt(index), index);
    float alpha = texture(uTransfer, u).a;
    if (alpha == 0.0) continue;
    vec3 q = p + t * l;
    if (kCut) {
      vec4 clip = uViewProjection * vec4(q, 1.0);
      vec2 ndc = clip.xy / clip.w;
      gSampleImportance = uInterest != 0 ? 1.0 : texture(uMaterialImportance, u).r;
      vec3 cutNormal;
      if (clip.w > 0.0 && all(lessThanEqual(abs(ndc), vec2(1.0))) &&
          fateAt(q, (ndc * 0.5 + 0.5) * uViewport.xy, true, cutNormal) == kDiscard)
        continue;
    }
    transmittance *= pow(1.0 - alpha, exponent);
  }
  return transmittance;
}
#endif
float gTransmittance;  // the last shaded sample's key-light transmittance

// The sample's colour: the transfer function's, shaded with the normal `n` (zero: unshaded),
// emphasised by its importance (Burns11 eqs. 3.1–3.4).
// The key light's transmittance is taken from `shadowFrom`: p, or for a sample of a cut's face
// the removed sample in front of the face (from p, a step inside the kept material, a grazing
// light's first shadow samples would lie in that material: bands of shadow on the face).
vec3 shadeSample(vec3 p, vec3 base, float importance, vec3 n, vec3 shadowFrom) {
  gTransmittance = 1.0;
  if (!kShading || n == vec3(0.0)) return emphasize(base, base, importance);
  SurfacePoint s;
  s.position = p;
  s.toEye = uCounts.y == 1 ? -uForward.xyz : normalize(uEye.xyz - p);
  s.normal = dot(n, s.toEye) < 0.0 ? -n : n;  // lit from the side seen, as two-sided meshes
  s.baseColor = base;
  s.specular = 0.2;
  s.shininess = 32.0;
#ifdef SHADOWS
  float sampleImportance = gSampleImportance;  // the shadow ray's samples set their own
  gTransmittance = volumeTransmittance(shadowFrom);
  gSampleImportance = sampleImportance;
#endif
  s.keyLightVisibility = keyLightVisibility(p) * gTransmittance;
  return emphasize(base, shadeSurface(s), importance);
}

// The distance along the ray (origin, unit direction) to the point at view depth z.
float distanceAtViewDepth(vec3 origin, vec3 direction, float z) {
  float along = dot(direction, uForward.xyz);
  return (z + (uView * vec4(origin, 1.0)).z) / along;
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  // What the volumes before this one left: their values stand where this one casts nothing.
  float previousHit = texelFetch(uPreviousHit, pixel, 0).r;
  float previousEntry = texelFetch(uPreviousEntry, pixel, 0).r;
  float previousOpacity = texelFetch(uPreviousOpacity, pixel, 0).r;
  float previousTransmittance = texelFetch(uPreviousTransmittance, pixel, 0).r;
  outColor = vec4(0.0);
  outEntryDepth = previousEntry;
  outHitDepth = previousHit;
  outOpacity = previousOpacity;
  outLightTransmittance = previousTransmittance;
  vec2 uv = gl_FragCoord.xy * uViewport.zw;
  VolumeRay ray = volumeRay(uv);
  vec3 origin = ray.origin, direction = ray.direction, o = ray.o, d = ray.d;
  // The rays stop at the opaque surfaces and where an earlier volume's material hid the rest.
  float tIn = ray.tIn, tOut = ray.tOut;
  float opaque = texelFetch(uOpaqueDepth, pixel, 0).r;
  if (opaque < 1.0) tOut = min(tOut, distance(origin, worldAtWindow(uv, opaque)));
  if (!isnan(previousHit)) tOut = min(tOut, distanceAtViewDepth(origin, direction, previousHit));
  if (!(tIn < tOut)) discard;
  float entry = kNaN, hit = kNaN, hitTransmittance = kNaN;
  float offset = uJitter != 0 ? pixelJitter(uvec2(gl_FragCoord.xy)) : 0.5;
  vec4 sum = vec4(0.0);  // premultiplied colour, opacity
  float maxValue = -1e30, maxT = 0.0;
  float previousValue = 0.0;
  bool previousKept = false;
  // The cut's face: samples this close behind where a ray entered kept material from removed
  // material take the cut's normal, so that the cut reads as a solid face (one and a half
  // voxels: the gradient's reach).
  float cutSkin = 1.5 * uVoxel, tCut = -1e30;
  vec3 faceNormal = vec3(0.0);
  // Where the cutters remove the ray whole (the cutaway surface's near side, a box cut's
  // inside), it skips ahead instead of asking them per sample (Burns11 §5.2.5).
  vec2 spans[REMOVED_SPANS];
  for (int i = 0; i < REMOVED_SPANS; ++i) spans[i] = vec2(1e30, -1e30);
  if (kCut) removedSpans(uCutBy, origin, direction, gl_FragCoord.xy, vec2(tIn, tOut), spans);
  // The samples lie on the lattice t₀ + k·step, so skipping removed spans and empty blocks
  // changes none of them.
  float t0 = tIn + offset * uStep;
  for (int k = 0; t0 + float(k) * uStep < tOut; ++k) {
    float t = t0 + float(k) * uStep;
    bool removed = false;
    for (int i = 0; i < REMOVED_SPANS; ++i)
      if (t > spans[i].x && t < spans[i].y) {
        k = max(k, int(ceil((spans[i].y - t0) / uStep)) - 1);
        removed = true;
      }
    if (removed) {
      previousKept = false;
      continue;
    }
    vec3 p = origin + t * direction;
    vec3 index = o + t * d;
    // Composite: a block whose values the transfer function makes all clear is skipped to
    // its far side (empty-space skipping; the blocks' flags are conservative).
    if (kMode == 0) {
      ivec3 block = clamp(ivec3(floor((index + 0.5) / kBlock)), ivec3(0),
                          textureSize(uOccupancy, 0) - 1);
      if (texelFetch(uOccupancy, block, 0).r == 0u) {
        vec3 lo = vec3(block) * kBlock - 0.5;
        vec3 a = (lo - o) / d, b = (lo + kBlock - o) / d;
        vec3 far = max(a, b);
        float tExit = min(far.x, min(far.y, far.z));
        k = max(k, int(ceil((tExit - t0) / uStep)) - 1);
        previousKept = false;
        continue;
      }
    }
    float value = valueAt(index);
    vec2 u = transferCoordinates(value, index);
    vec4 c = texture(uTransfer, u);
    // Empty space costs no cutter and no shading (composite: no opacity; isosurface: below
    // the isovalue, where only the previous value matters).
    if ((kMode == 0 && c.a == 0.0) || (kMode == 2 && value < uIsoValue && !kCut)) {
      previousKept = kMode == 2;
      previousValue = value;
      continue;
    }
    gSampleImportance = uInterest != 0 ? 1.0 : texture(uMaterialImportance, u).r;
    vec3 cutNormal;
    if (kCut && sampleFate(p, true, cutNormal) == kDiscard) {
      previousKept = false;
      continue;
    }
    float depth = -(uView * vec4(p, 1.0)).z;
    if (isnan(entry)) entry = depth;
    // Entering kept material from removed material: the cut's face, lit by its normal. Both
    // samples are decided as this sample's material (with its importance): a face is where
    // the cut of this material passes between them, not where other material ends.
    if (kCut && !previousKept && t - uStep > tIn &&
        sampleFate(p - uStep * direction, true, cutNormal) == kDiscard &&
        sampleFate(p, false, cutNormal) == kCutSurface)
      tCut = t, faceNormal = cutNormal;
    bool onCut = t - tCut < cutSkin;
    vec3 shadowFrom = onCut ? origin + (tCut - uStep) * direction : p;
    if (kMode == 1) {
      if (value > maxValue) maxValue = value, maxT = t;
    } else if (kMode == 2) {
      // The first crossing of the isovalue, placed by linear interpolation between samples;
      // material cut open above the isovalue shows the cut's face.
      if (value >= uIsoValue) {
        float tHit = t;
        if (previousKept) tHit = t - uStep * (value - uIsoValue) / (value - previousValue);
        vec3 q = origin + tHit * direction;
        vec2 iso = transferCoordinates(uIsoValue, o + tHit * d);
        float importance = uInterest != 0 ? 1.0 : texture(uMaterialImportance, iso).r;
        vec3 n = onCut ? faceNormal : normalAt(o + tHit * d);
        sum = vec4(shadeSample(q, texture(uTransfer, iso).rgb, importance, n, onCut ? shadowFrom : q), 1.0);
        hit = -(uView * vec4(q, 1.0)).z;
        hitTransmittance = gTransmittance;
        break;
      }
    } else {
      // Opacity correction for the step (the table holds opacity per opacity distance).
      float alpha = 1.0 - pow(1.0 - c.a, uOpacityExponent);
      vec3 n = onCut ? faceNormal : normalAt(index);
      vec3 toEye = uCounts.y == 1 ? -uForward.xyz : normalize(uEye.xyz - p);
      // Burns11 ch. 2 per sample: what a grading cutter leaves of its opacity. Eq. 2.2 reads
      // the normal facing the viewer, as a two-sided mesh's; inside uniform material (no
      // gradient) the material faces the viewer whichever way it is looked at.
      vec3 facing = n == vec3(0.0) ? toEye : dot(n, toEye) < 0.0 ? -n : n;
      if (kCut) alpha *= cutOpacity(uCutBy, CutFragment(p, facing, true), facing, toEye).x;
      vec3 color = shadeSample(p, c.rgb, gSampleImportance, n, shadowFrom);
      sum += (1.0 - sum.a) * vec4(clamp(color, 0.0, 1.0) * alpha, alpha);
      if (isnan(hit) && sum.a >= 0.5) hit = depth, hitTransmittance = gTransmittance;
      if (sum.a > 0.995) break;  // early ray termination
    }
    previousKept = true;
    previousValue = value;
  }
  if (kMode == 1 && maxValue > -1e30) {
    vec2 u = transferCoordinates(maxValue, o + maxT * d);
    vec4 c = texture(uTransfer, u);
    float importance = uInterest != 0 ? 1.0 : texture(uMaterialImportance, u).r;
    sum = vec4(emphasize(c.rgb, c.rgb, importance) * c.a, c.a);
    hit = -(uView * vec4(origin + maxT * direction, 1.0)).z;
    hitTransmittance = 1.0;  // unshaded
  }
  outColor = sum;
  // Over the volumes before: the nearest entry and hit, the opacity accumulated.
  outEntryDepth = isnan(previousEntry) ? entry : isnan(entry) ? previousEntry : min(entry, previousEntry);
  outHitDepth = isnan(previousHit) ? hit : isnan(hit) ? previousHit : min(hit, previousHit);
  outOpacity = 1.0 - (1.0 - previousOpacity) * (1.0 - sum.a);
  // This ray stopped at the earlier volumes' hit: a hit of its own is the nearer.
  outLightTransmittance = isnan(hit) ? previousTransmittance : hitTransmittance;
}
