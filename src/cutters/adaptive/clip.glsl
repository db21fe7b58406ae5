// The adaptive cutter's per-fragment decision in the geometry passes (Burns08 §4.1,
// Burns11 §5.2.2 and §5.2.4.1). Needs frame_uniforms.glsl.
#include "cutters/fate.glsl"
layout(binding = UNIT_CUTAWAY_DEPTH) uniform sampler2D uCutawayDepth;  // C(p), window depth, linear filter
layout(binding = UNIT_CUTAWAY_DILATED) uniform sampler2D uCutawayDilated;  // 1-pixel minimum of C (Burns08 §4.2)
// Read with textureLod at level 0: the value texture() gives (one level, linear minification
// and magnification alike), without the derivatives llvmpipe works out for texture().

// View-space point on the view ray through uv at window depth `depth`.
vec3 viewPointAtDepth(vec2 uv, float depth) {
  vec4 h = uInverseProjection * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
  return h.xyz / h.w;
}

// The cutaway surface at screen position uv, in view space.
vec3 cutawayViewPoint(vec2 uv) {
  return viewPointAtDepth(uv, textureLod(uCutawayDepth, uv, 0.0).r);
}

// The cut surface through `center` (view space) with neighbours dx, dy apart along the
// screen's axes, in world space, its normal facing the viewer (Burns11 §5.2.4.1).
void cutSurfaceAt(vec3 center, vec3 dx, vec3 dy, out vec3 cutPosition, out vec3 cutNormal) {
  vec3 n = cross(dx, dy);
  n = dot(n, n) > 0.0 ? normalize(n) : vec3(0.0, 0.0, 1.0);
  vec3 toEye = uCounts.y == 1 ? vec3(0.0, 0.0, 1.0) : -center;
  if (dot(n, toEye) < 0.0) n = -n;
  cutNormal = normalize(mat3(uInverseView) * n);
  cutPosition = (uInverseView * vec4(center, 1.0)).xyz;
}

// The cutaway surface at uv, in world space, with its normal from the neighbouring texels'
// depths (Burns11 §5.2.4.1).
void cutawaySurfaceAt(vec2 uv, out vec3 cutPosition, out vec3 cutNormal) {
  vec2 texel = 1.0 / vec2(textureSize(uCutawayDepth, 0));
  vec3 center = cutawayViewPoint(uv);
  vec3 dx = cutawayViewPoint(uv + vec2(texel.x, 0.0)) - cutawayViewPoint(uv - vec2(texel.x, 0.0));
  vec3 dy = cutawayViewPoint(uv + vec2(0.0, texel.y)) - cutawayViewPoint(uv - vec2(0.0, texel.y));
  cutSurfaceAt(center, dx, dy, cutPosition, cutNormal);
}
#if !defined(CUT_VOLUME_SAMPLE) && !defined(TRANSLUCENT_LAYER)
// Every fragment decided here lies at its pixel's centre (one per pixel, no per-sample
// shading): the depths there, sampled once per pixel (at_pixel.frag), replace the bilinear
// fetches. Ray samples and the per-sample translucent layers sample the surfaces themselves.
#define CUTAWAY_AT_PIXEL
#include "frame/normal_weight.glsl"
layout(binding = UNIT_CUTAWAY_AT_PIXEL) uniform sampler2D uCutawayAtPixel;
#endif

// C at window position `window`, or its dilation (Burns08 §4.2) for back faces.
float cutawayDepthAt(vec2 window, bool frontFacing) {
#ifdef CUTAWAY_AT_PIXEL
  vec2 c = texelFetch(uCutawayAtPixel, ivec2(window), 0).xy;
  return frontFacing ? c.x : c.y;
#else
  vec2 uv = window * uViewport.zw;
  return frontFacing ? textureLod(uCutawayDepth, uv, 0.0).r : textureLod(uCutawayDilated, uv, 0.0).r;
#endif
}

#ifdef UNIT_CUTAWAY_DEPTH_C2
// The contextual cutaway structure (Burns11 §4.1.3, §5.2.3); mirrors contextual_function.cpp.
layout(binding = UNIT_CUTAWAY_DEPTH_C2) uniform sampler2D uCutawayDepthC2;  // C₂, window depth
layout(binding = UNIT_CUTAWAY_DILATED_C2) uniform sampler2D uCutawayDilatedC2;
// x: overlay thickness d (world units), y: t (§4.1.3.3), z: 1 for R = Ω (§7.2), 0 for eq. 7.3.
layout(location = LOC_ADAPTIVE_CONTEXTUAL) uniform vec3 uContextual;
layout(location = LOC_ADAPTIVE_IMPORTANCE) uniform float uImportance;  // I of the object drawn
// A volume's ray samples take the importance of their own material (kinds/volumes).
#ifndef CUT_IMPORTANCE
#define CUT_IMPORTANCE uImportance
#endif

// Eq. 5.5; where a = b the step x > a (eq. 7.3's degenerate ends, §7.1.2).
float contextualRamp(float a, float b, float x) {
  if (!(a < b)) return x > a ? 1.0 : 0.0;
  return clamp((x - a) / (b - a), 0.0, 1.0);
}

// (z₁, z₂, d, t): C₁ and C₂ (window depths c1, c2) as distances in front of the eye along the
// ray through uv.
vec4 contextualRay(vec2 uv, float c1, float c2) {
  float z1 = -viewPointAtDepth(uv, c1).z;
  float z2 = max(-viewPointAtDepth(uv, c2).z, z1);  // θ₂ ≥ θ₁: C₂ lies behind C₁
  return vec4(z1, z2, uContextual.x, uContextual.y);
}

// The same, sampling C₁ and C₂ (dilated for back faces) at uv.
vec4 contextualRay(vec2 uv, bool frontFacing) {
  float c1 = frontFacing ? textureLod(uCutawayDepth, uv, 0.0).r : textureLod(uCutawayDilated, uv, 0.0).r;
  float c2 = frontFacing ? textureLod(uCutawayDepthC2, uv, 0.0).r : textureLod(uCutawayDilatedC2, uv, 0.0).r;
  return contextualRay(uv, c1, c2);
}

// The ray through the decided point's pixel.
vec4 contextualRayAt(vec2 window, bool frontFacing) {
#ifdef CUTAWAY_AT_PIXEL
  vec4 c = texelFetch(uCutawayAtPixel, ivec2(window), 0);
  return contextualRay(window * uViewport.zw, frontFacing ? c.x : c.y, frontFacing ? c.z : c.w);
#else
  return contextualRay(window * uViewport.zw, frontFacing);
#endif
}

// Ω at distance z (§4.1.3.3; eq. 5.6 when t = ½), z growing away from the eye.
float contextualOcclusion(vec4 r, float z) {
  return r.w * contextualRamp(-r.y, -r.x, -z) + (1.0 - r.w) * contextualRamp(-r.x, -r.x + r.z, -z);
}

// The distance where Ω reaches omega.
float occlusionDistance(vec4 r, float omega) {
  if (r.w > 0.0 && omega <= r.w) return r.y - omega / r.w * (r.y - r.x);
  return r.x - r.z * (omega - r.w) / (1.0 - r.w);
}

// Eqs. 7.1–7.3, or R = Ω.
float occlusionReduction(float omega) {
  if (uContextual.z > 0.5) return omega;
  return contextualRamp(max(2.0 * CUT_IMPORTANCE - 1.0, 0.0), CUT_IMPORTANCE, omega);
}

// The Ω where R reaches ½: the object's trimming surface (§5.2.4); above 1: never trimmed.
float trimOcclusion() {
  if (uContextual.z > 0.5) return 0.5;
  if (CUT_IMPORTANCE >= 1.0) return 2.0;
  return 0.5 * (max(2.0 * CUT_IMPORTANCE - 1.0, 0.0) + CUT_IMPORTANCE);
}

float fragmentDistance(vec3 worldPosition) {
  return -(uView * vec4(worldPosition, 1.0)).z;
}

// View-space point of the trimming surface at Ω = omega on the ray through uv.
vec3 trimViewPoint(vec2 uv, float omega, bool frontFacing) {
  float z = occlusionDistance(contextualRay(uv, frontFacing), omega);
  vec3 q = viewPointAtDepth(uv, 0.5);
  return uCounts.y == 1 ? vec3(q.xy, -z) : q * (z / -q.z);
}

// R ≥ ½ removes the fragment (§5.2.4: polygons take R fully or not at all); a back face
// behind its object's trimming surface is that surface's cut. Applied as translucency, edge
// highlights or lines (ADAPTIVE_GRADED), R sets the fragment's opacities instead
// (adaptiveOpacity).
int contextualFragment(CutFragment f, out vec3 cutPosition, out vec3 cutNormal) {
#ifdef ADAPTIVE_GRADED
  return kKeep;
#endif
  vec2 uv = CUT_FRAG_COORD.xy * uViewport.zw;
  vec4 r = contextualRayAt(CUT_FRAG_COORD.xy, f.frontFacing);
  if (occlusionReduction(contextualOcclusion(r, fragmentDistance(f.position))) >= 0.5) return kDiscard;
  float omega = max(trimOcclusion(), 1e-6);  // I = 0: trimmed wherever Ω > 0, i.e. at C₂
  if (f.frontFacing || omega > 1.0) return kKeep;
  // No cut along this ray where the trimming surface lies at or before the near plane.
  if (occlusionDistance(r, omega) <= -viewPointAtDepth(uv, 0.0).z) return kKeep;
  vec2 texel = 1.0 / vec2(textureSize(uCutawayDepth, 0));
  vec3 center = trimViewPoint(uv, omega, false);
  vec3 dx = trimViewPoint(uv + vec2(texel.x, 0.0), omega, false) - trimViewPoint(uv - vec2(texel.x, 0.0), omega, false);
  vec3 dy = trimViewPoint(uv + vec2(0.0, texel.y), omega, false) - trimViewPoint(uv - vec2(0.0, texel.y), omega, false);
  cutSurfaceAt(center, dx, dy, cutPosition, cutNormal);
  return kCutSurface;
}

// The G-buffer channels occlusion (Ω) and reduction (R) at a fragment of a cut object.
float adaptiveChannel0(CutFragment f) {
  return contextualOcclusion(contextualRayAt(CUT_FRAG_COORD.xy, f.frontFacing), fragmentDistance(f.position));
}
float adaptiveChannel1(CutFragment f) {
  return occlusionReduction(adaptiveChannel0(f));
}

#ifdef ADAPTIVE_GRADED
// x: 0 translucency, 1 edge highlights, 2 lines; y: k of eq. 2.2.
layout(location = LOC_ADAPTIVE_APPLY) uniform vec2 uApply;
// Ch. 2: the opacities R leaves its surface and its lines (α_m = 1); mirrors reducedOpacity()
// in contextual_function.cpp.
vec2 adaptiveOpacity(CutFragment f, vec3 normal, vec3 toEye) {
  float r = adaptiveChannel1(f);
  if (uApply.x == 2.0) return vec2(r > 0.0 ? 0.0 : 1.0, 1.0 - r);  // §2.3: surface gone, lines fade
  if (uApply.x == 0.0) return vec2(1.0 - r);                        // eq. 2.1
  float facing = clamp(dot(normal, toEye), 0.0, 1.0);
  return vec2(1.0 - r * (1.0 - pow(1.0 - facing, uApply.y)));      // eq. 2.2
}
#endif
#endif

// kDiscard in the clear region, kKeep in the base region, kCutSurface for a back face seen
// through the cut: there it stands for the solid's cut surface, with the cutaway surface's
// position and normal (from neighbouring depths, Burns11 §5.2.4.1).
int adaptiveFragment(CutFragment f, out vec3 cutPosition, out vec3 cutNormal) {
#ifdef UNIT_CUTAWAY_DEPTH_C2
  return contextualFragment(f, cutPosition, cutNormal);
#else
  bool frontFacing = f.frontFacing;
  // Burns11 eq. 5.4: Ω = 1 − step(C(p), p_z); back faces use the dilated surface.
  float c = cutawayDepthAt(CUT_FRAG_COORD.xy, frontFacing);
  if (CUT_FRAG_COORD.z < c) return kDiscard;
  // A back face is a cut surface only where the cutaway surface lies in front of it; elsewhere
  // (no cut at this pixel) it is an ordinary inside view of an open mesh. On an open mesh the
  // mesh kind also asks that its own front was removed there (CutLook::marksOpenMeshes).
  if (frontFacing || c <= 0.0) return kKeep;
#ifdef CUTAWAY_AT_PIXEL
  // Worked out once per pixel (at_pixel.frag): every fragment here lies at a pixel centre.
  vec4 atPixel = texelFetch(uCutawayAtPixel, ivec2(CUT_FRAG_COORD.xy), 0);
  vec3 center = viewPointAtDepth(CUT_FRAG_COORD.xy * uViewport.zw, atPixel.x);
  cutPosition = (uInverseView * vec4(center, 1.0)).xyz;
  cutNormal = octahedralDecode(atPixel.zw);
#else
  cutawaySurfaceAt(CUT_FRAG_COORD.xy * uViewport.zw, cutPosition, cutNormal);
#endif
  return kCutSurface;
#endif
}

#ifndef UNIT_CUTAWAY_DEPTH_C2
// Burns11 §5.2.5: a volume's ray starts at the cutaway surface. Along the ray through `window`
// the window depth grows, so every point in front of the depth C there is removed (eq. 5.4):
// the span up to C's point, shrunk by a hair so that the samples at C are decided per sample.
// (The contextual structure keeps important samples in front of C: no such span.)
#define ADAPTIVE_REMOVED_SPAN
vec2 adaptiveRemovedSpan(vec3 origin, vec3 direction, vec2 window, vec2 range) {
  vec2 uv = window * uViewport.zw;
  float c = textureLod(uCutawayDepth, uv, 0.0).r;
  if (c <= 0.0) return vec2(1e30, -1e30);
  vec4 h = uInverseView * (uInverseProjection * vec4(uv * 2.0 - 1.0, c * 2.0 - 1.0, 1.0));
  float t = dot(h.xyz / h.w - origin, direction);
  return vec2(-1e30, t * (1.0 - 1e-4));
}
#endif

// Burns08 §4.3: how strongly a removed fragment shows as a ghost line: 1 at the cutaway
// surface, fading to 0 at `distance` (world units) in front of it; 0 for kept fragments.
float ghostFade(vec3 worldPosition, float distance) {
  float c = cutawayDepthAt(CUT_FRAG_COORD.xy, true);
  if (CUT_FRAG_COORD.z >= c) return 0.0;
  float fragmentDepth = -(uView * vec4(worldPosition, 1.0)).z;
  float cutawayDepth = -viewPointAtDepth(CUT_FRAG_COORD.xy * uViewport.zw, c).z;
  return clamp(1.0 - (cutawayDepth - fragmentDepth) / distance, 0.0, 1.0);
}
