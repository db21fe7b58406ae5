#version 450 core
// The hidden-line test of a volume's lines (volume_lines_pass.hpp): along the view ray through
// the pixel centre, the view depth of the nearest crossing of any of the volume's line
// isovalues among the samples the cutters keep, or of the opaque surfaces where that is
// nearer. Blended by minimum over the volumes with lines. Crossings are found between
// successive kept samples and placed by linear interpolation; a ray that starts inside the
// material (at a cut) crosses nothing there, so a cut opens the view onto what lies inside.
// Variant TRANSFER_2D: the material's importance at the gradient magnitude too.
#include "frame/frame_uniforms.glsl"
#include "styles/surface.glsl"
#include "style.glsl"
#include "styles/shadows/shadow_lookup.glsl"
#include "styles/emphasis/emphasis.glsl"
layout(location = 9) uniform int uCutBy;  // bit k: the cutter of slot k cuts it
#include "kinds/volumes/volume_sample_cut.glsl"
#include "kinds/volumes/volume_ray.glsl"
layout(binding = 0) uniform sampler2DMS uOpaqueDepth;
layout(location = 2) uniform float uStep;     // world units
layout(location = 10) uniform int uInterest;  // 1: of interest (importance 1 everywhere)
layout(location = 20) uniform int uIsoCount;
layout(location = 21) uniform float uIsoValues[8];
layout(location = 0) out float outSurfaceDepth;

float viewDepth(vec3 p) {
  return -(uView * vec4(p, 1.0)).z;
}

void main() {
  vec2 uv = gl_FragCoord.xy * uViewport.zw;
  float opaque = texelFetch(uOpaqueDepth, ivec2(gl_FragCoord.xy), 0).r;
  outSurfaceDepth = opaque < 1.0 ? viewDepth(worldAtWindow(uv, opaque)) : 1e30;
  VolumeRay r = volumeRay(uv);
  if (!(r.tIn < r.tOut)) return;
  float tEnd = r.tOut;
  if (opaque < 1.0) tEnd = min(tEnd, distance(r.origin, worldAtWindow(uv, opaque)));
  bool havePrevious = false;
  float previous = 0.0, tPrevious = 0.0;
  for (float t = r.tIn + 0.5 * uStep; t < tEnd; t += uStep) {
    vec3 index = r.o + t * r.d;
    float value = valueAt(index);
    if (uCutBy != 0) {
      gSampleImportance =
          uInterest != 0 ? 1.0 : texture(uMaterialImportance, transferCoordinates(value, index)).r;
      vec3 cutNormal;
      if (fateAt(r.origin + t * r.direction, gl_FragCoord.xy, true, cutNormal) == kDiscard) {
        havePrevious = false;
        continue;
      }
    }
    if (havePrevious) {
      float nearest = 2.0;
      for (int i = 0; i < uIsoCount; ++i) {
        float a = previous - uIsoValues[i], b = value - uIsoValues[i];
        if ((a < 0.0) != (b < 0.0)) nearest = min(nearest, a / (a - b));
      }
      if (nearest <= 1.0) {
        float t0 = tPrevious + nearest * (t - tPrevious);
        outSurfaceDepth = min(outSurfaceDepth, viewDepth(r.origin + t0 * r.direction));
        return;
      }
    }
    havePrevious = true;
    previous = value, tPrevious = t;
  }
}
