#version 450 core
// The hidden-line test of a volume's lines (volume_lines_pass.hpp): along the view ray through
// the pixel centre, the view depth of the nearest crossing of any of the volume's line
// isovalues among the samples the cutters keep, or of the opaque surfaces where that is
// nearer. Blended by minimum over the volumes with lines. Crossings are found between
// successive kept samples and placed by linear interpolation; a ray that starts inside the
// material (at a cut) crosses nothing there, so a cut opens the view onto what lies inside.
// Blocks whose value range holds no isovalue are skipped whole. Variant TRANSFER_2D: the
// material's importance at the gradient magnitude too.
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
// Per block of kBlock³ voxels, the least and largest value any of its samples can interpolate.
layout(binding = 7) uniform sampler3D uIsoBlocks;
const float kBlock = 8.0;  // volume_blocks.hpp's kVolumeBlock
layout(location = 2) uniform float uStep;     // world units
layout(location = 10) uniform int uInterest;  // 1: of interest (importance 1 everywhere)
layout(location = 20) uniform int uIsoCount;
layout(location = 21) uniform float uIsoValues[8];
layout(location = 0) out float outSurfaceDepth;

float viewDepth(vec3 p) {
  return -(uView * vec4(p, 1.0)).z;
}

// Whether the cutters remove the ray's sample at t, graded by its material's importance.
bool removedSample(VolumeRay r, float t) {
  if (uCutBy == 0) return false;
  vec3 index = r.o + t * r.d;
  gSampleImportance =
      uInterest != 0 ? 1.0 : texture(uMaterialImportance, transferCoordinates(valueAt(index), index)).r;
  vec3 cutNormal;
  return fateAt(r.origin + t * r.direction, gl_FragCoord.xy, true, cutNormal) == kDiscard;
}

void main() {
  vec2 uv = gl_FragCoord.xy * uViewport.zw;
  float opaque = texelFetch(uOpaqueDepth, ivec2(gl_FragCoord.xy), 0).r;
  outSurfaceDepth = opaque < 1.0 ? viewDepth(worldAtWindow(uv, opaque)) : 1e30;
  VolumeRay r = volumeRay(uv);
  if (!(r.tIn < r.tOut)) return;
  float tEnd = r.tOut;
  if (opaque < 1.0) tEnd = min(tEnd, distance(r.origin, worldAtWindow(uv, opaque)));
  // Where the cutters remove the ray whole it skips ahead (as volume.frag); elsewhere they
  // are asked only at a crossing, about the samples on both sides of it.
  vec2 spans[REMOVED_SPANS];
  removedSpans(uCutBy, r.origin, r.direction, gl_FragCoord.xy, vec2(r.tIn, tEnd), spans);
  bool havePrevious = false;
  float previous = 0.0, tPrevious = 0.0;
  float t0 = r.tIn + 0.5 * uStep;
  for (int k = 0; t0 + float(k) * uStep < tEnd; ++k) {
    float t = t0 + float(k) * uStep;
    bool removed = false;
    for (int i = 0; i < REMOVED_SPANS; ++i)
      if (t > spans[i].x && t < spans[i].y) {
        k = max(k, int(ceil((spans[i].y - t0) / uStep)) - 1);
        removed = true;
      }
    if (removed) {
      havePrevious = false;
      continue;
    }
    vec3 index = r.o + t * r.d;
    float value = valueAt(index);
    float nearest = 2.0;
    if (havePrevious)
      for (int i = 0; i < uIsoCount; ++i) {
        float a = previous - uIsoValues[i], b = value - uIsoValues[i];
        if ((a < 0.0) != (b < 0.0)) nearest = min(nearest, a / (a - b));
      }
    if (nearest <= 1.0 && !removedSample(r, tPrevious) && !removedSample(r, t)) {
      float tHit = tPrevious + nearest * (t - tPrevious);
      outSurfaceDepth = min(outSurfaceDepth, viewDepth(r.origin + tHit * r.direction));
      return;
    }
    havePrevious = true;
    previous = value, tPrevious = t;
    // A block whose values (and its neighbours') hold no isovalue has no crossing: on to its
    // last sample, so that a crossing just past it is placed between neighbouring samples.
    ivec3 block = clamp(ivec3(floor((index + 0.5) / kBlock)), ivec3(0), textureSize(uIsoBlocks, 0) - 1);
    vec2 range = texelFetch(uIsoBlocks, block, 0).rg;
    bool empty = range.x <= range.y;  // a block of NaN voxels has no range: never skipped
    for (int i = 0; i < uIsoCount; ++i)
      if (uIsoValues[i] >= range.x && uIsoValues[i] <= range.y) empty = false;
    if (empty) {
      vec3 lo = vec3(block) * kBlock - 0.5;
      vec3 ea = (lo - r.o) / r.d, eb = (lo + kBlock - r.o) / r.d;
      vec3 far = max(ea, eb);
      k = max(k, int(ceil((min(far.x, min(far.y, far.z)) - t0) / uStep)) - 2);
    }
  }
}
