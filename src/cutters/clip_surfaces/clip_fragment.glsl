// Trapp13 §4.3–4.4: a fragment is discarded where the enabled clip surfaces clip it.
#include "clip_surfaces.glsl"
#ifdef CUT_VOLUME_SAMPLE
// 1 where a ray sample was removed by a clip surface: the clip-mask AOV (for meshes,
// clip_mask.frag draws it when it is read).
layout(binding = IMAGE_CLIP_MASK, r32ui) uniform coherent uimage2D uClipMask;

// The cut's normal at p: the relief normal of the enabled surface nearest to p (its cap's
// normal in cap.frag), or its plane's without the caps' normal map.
vec3 clipCutNormal(vec3 p) {
  int nearest = -1;
  float best = 1e30;
  for (int i = 0; i < uClipCount.x; ++i) {
    if (uClipOrigin[i].w == 0.0) continue;
    float distance = abs(clipSurfaceFunction(i, p));
    if (distance < best) best = distance, nearest = i;
  }
  if (nearest < 0) return vec3(0.0);
  vec3 n = clipSurfaceNormal(nearest);
  if (uClipCount.z == 0) return -n;
  vec4 relief = clipRelief(nearest, clipSurfaceTexCoord(nearest, p));
  vec3 ds = uClipU[nearest].xyz - uClipScale[nearest].z * uClipScale[nearest].x * relief.g * n;
  vec3 dt = uClipV[nearest].xyz - uClipScale[nearest].z * uClipScale[nearest].y * relief.b * n;
  vec3 normal = normalize(cross(ds, dt));
  return dot(normal, n) > 0.0 ? -normal : normal;
}
#endif

int clipSurfacesFragment(CutFragment f, out vec3 cutPosition, out vec3 cutNormal) {
  // Trapp13 clips the solid; its cut is covered by the caps, not by cut surfaces.
  cutPosition = f.position;
  cutNormal = vec3(0.0);
  if (!clippedBySurfaces(f.position, -1)) {
#ifdef CUT_VOLUME_SAMPLE
    // A volume has no caps: its sample just behind clipped material, asked as a back face, is
    // the cut's face, lit by the surface's normal (kinds/volumes).
    if (!f.frontFacing) {
      cutNormal = clipCutNormal(f.position);
      return kCutSurface;
    }
#endif
    return kKeep;
  }
#ifdef CUT_VOLUME_SAMPLE
  imageAtomicMax(uClipMask, ivec2(CUT_FRAG_COORD.xy), 1u);
#endif
  return kDiscard;
}

#ifdef CUT_VOLUME_SAMPLE
// The span of a view ray that the surfaces remove whatever their relief (cutters/cutter.hpp):
// eq. 1 is < 0 wherever P·N − N·O + max(h·S_z) is, a half-space along the ray. Intersection:
// the spans' common part; union: the first enabled surface's span (the others are asked per
// sample). Shrunk by a hair so that samples on its ends are decided by clipSurfacesFragment;
// where it overlaps the sampled range, the pixel's clip mask is set as those samples would.
#define CLIPSURFACES_REMOVED_SPAN
vec2 clipSurfacesRemovedSpan(vec3 origin, vec3 direction, vec2 window, vec2 range) {
  vec2 span = vec2(-1e30, 1e30);
  bool enabled = false;
  for (int i = 0; i < uClipCount.x; ++i) {
    if (uClipOrigin[i].w == 0.0) continue;
    vec3 n = clipSurfaceNormal(i);
    float a = dot(origin, n) - uClipSurfacePlane[i].w + uClipScale[i].w;
    float b = dot(direction, n);
    vec2 own = b > 0.0 ? vec2(-1e30, -a / b) : b < 0.0 ? vec2(-a / b, 1e30)
             : a < 0.0 ? vec2(-1e30, 1e30) : vec2(1e30, -1e30);
    span = vec2(max(span.x, own.x), min(span.y, own.y));
    enabled = true;
    if (uClipCount.y == 0) break;
  }
  if (!enabled) return vec2(1e30, -1e30);
  span = vec2(span.x + 1e-4 * (1.0 + abs(span.x)), span.y - 1e-4 * (1.0 + abs(span.y)));
  if (max(span.x, range.x) < min(span.y, range.y))
    imageAtomicMax(uClipMask, ivec2(window), 1u);
  return span;
}
#endif
