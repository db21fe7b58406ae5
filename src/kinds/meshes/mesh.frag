#version 450 core
// Geometry pass: shades a visible scene mesh with the active style (aliased as "style.glsl")
// and the active cutters (the generated cutters/composition.glsl), and writes the G-buffer
// that the line and AOV passes read.
#include "frame/frame_uniforms.glsl"
#include "styles/surface.glsl"
#include "style.glsl"
#include "styles/shadows/shadow_lookup.glsl"
#include "styles/emphasis/emphasis.glsl"
#include "frame/gbuffer.glsl"
#include "cutters/composition.glsl"
in vec3 vWorldPosition;
in vec3 vWorldNormal;
layout(location = 8) uniform vec3 uColor;
layout(location = 9) uniform float uSpecular;
layout(location = 10) uniform float uShininess;
layout(location = 11) uniform int uObjectId;
layout(location = 12) uniform float uLines;       // 1: this object takes feature lines
layout(location = 13) uniform int uCutBy;         // bit k: the cutter of slot k cuts this object
layout(location = 14) uniform int uCutSurfaces;   // bit k: its cuts of this object show cut surfaces
layout(location = 15) uniform vec3 uBackColor;    // back faces that are no cut surface (an open or hollow inside)
layout(location = 16) uniform float uEmphasisImportance;  // 1 for objects of interest
layout(location = 24) uniform vec3 uCutColor[CUTTER_SLOTS];  // per slot: the cut surfaces' colour
layout(location = 31) uniform int uChannelsBy;    // bit k: the cutter of slot k writes its G-buffer channels
#ifdef UNCUT
// MeshKind's program for the objects no active cutter cuts: the cutters' code folds away
// (llvmpipe runs a branch's code for every fragment, uniform condition or not). SLAB_KEPT:
// the part of a cut object that a Cutter::slab keeps whole, whose cutters' channels still
// hold their values.
#define CUT_BY 0
#ifdef SLAB_KEPT
#define CHANNELS_BY uChannelsBy
#else
#define CHANNELS_BY 0
#endif
#else
#define CUT_BY uCutBy
#define CHANNELS_BY uChannelsBy
#endif
#ifdef TRANSLUCENT_LAYER
// One layer of frame/translucent_layers.hpp: the nearest fragment of opacity > 0 behind the
// previous layer and in front of the opaque surfaces (the depth test). It is shaded per sample
// (reading gl_SampleID), so that each sample peels at its own depth, the depth its depth test
// stored (its cut too is decided at the sample's position).
#include "frame/samples.glsl"
layout(binding = UNIT_PEEL_DEPTH) uniform SAMPLER_MS uPeelDepth;
layout(location = 17) uniform int uFirstLayer;
// The previous layer's depth at this sample.
float peelDepth() {
  return texelFetch(uPeelDepth, ivec2(gl_FragCoord.xy), gl_SampleID).r;
}
#endif
// MeshKind draws a cut object's front faces and its back faces apart (FRONT_FACES,
// BACK_FACES): the side is known, and the other side's code folds away.
#if defined(FRONT_FACES)
#define FRONT_FACING true
#elif defined(BACK_FACES)
#define FRONT_FACING false
#else
#define FRONT_FACING gl_FrontFacing
#endif
#ifdef CUT_WRITES_DEPTH
// A cut surface behind the fragment (cutters/composition.glsl) moves it back, never forward.
layout(depth_greater) out float gl_FragDepth;
#endif
void main() {
#if defined(TRANSLUCENT_LAYER) && !defined(CUT_WRITES_DEPTH)
  // Peeled by the layers before: dropped before any other work (llvmpipe skips the rest of
  // the shader where a whole block is dropped).
  if (uFirstLayer == 0 && gl_FragCoord.z <= peelDepth()) discard;
#endif
  CutFragment f = CutFragment(vWorldPosition, vWorldNormal, FRONT_FACING);
  vec3 cutPosition, cutNormal;
  int cutter;
#ifdef CUT_WRITES_DEPTH
  gCutFragDepth = gl_FragCoord.z;
#endif
  int fate = cutFragment(CUT_BY, uCutSurfaces, f, cutPosition, cutNormal, cutter);
#ifdef MARK_REMOVED
  // MeshKind's removal marks of an open mesh: its front fragments the marking cutters (its
  // uCutBy here) remove, for the stencil alone (colour and depth writes off).
  if (fate != kDiscard) discard;
#ifdef CUT_WRITES_DEPTH
  gl_FragDepth = gl_FragCoord.z;
#endif
  return;
#endif
  if (fate == kDiscard) discard;
#ifdef CUT_WRITES_DEPTH
  gl_FragDepth = gCutFragDepth;
#endif
  bool cut = fate == kCutSurface;
  vec3 n = vWorldNormal;
  // Interpolated normals can vanish (opposite vertex normals); fall back to the face normal.
  if (dot(n, n) < 1e-12) n = cross(dFdx(vWorldPosition), dFdy(vWorldPosition));
  n = normalize(n);
  SurfacePoint s;
  s.position = cut ? cutPosition : vWorldPosition;
  s.normal = cut ? cutNormal : FRONT_FACING ? n : -n;  // two-sided: open meshes show their inside
  s.toEye = uCounts.y == 1 ? -uForward.xyz : normalize(uEye.xyz - s.position);
  // Burns11 ch. 2: occlusion partly reduced by a grading cutter: the opacity of the surface
  // (x) and of its lines (y); 1 without one. Decided before the shading, which a fragment
  // dropped here does not need.
  vec2 opacity = cutOpacity(CUT_BY, f, s.normal, s.toEye);
#ifdef TRANSLUCENT_LAYER
  // Opacity ≥ 1 too: a fragment the opaque pass kept lies at the opaque depth and fails the
  // depth test, and one it dropped by a rounding apart is drawn here, so none is lost. Below
  // 1/512 a fragment changes no 8-bit colour: it takes no layer.
  opacity = min(opacity, vec2(1.0, uLines));
  if (!(max(opacity.x, opacity.y) > 1.0 / 512.0)) discard;
#ifdef CUT_WRITES_DEPTH
  // Where a cut moves the fragment back, the depth to peel by is known only now.
  if (uFirstLayer == 0 && gCutFragDepth <= peelDepth()) discard;
#endif
#else
  if (opacity.x < 1.0) discard;  // drawn in the translucent layers, or not at all
#endif
  s.baseColor = cut ? uCutColor[cutter] : FRONT_FACING ? uColor : uBackColor;
  s.specular = uSpecular;
  s.shininess = uShininess;
  s.keyLightVisibility = keyLightVisibility(s.position);
  vec3 color = emphasize(s.baseColor, shadeSurface(s), uEmphasisImportance);
#ifdef TRANSLUCENT_LAYER
  writeGBuffer(s, color, opacity.y, uObjectId, cut, false);  // the lines' weight: their opacity
  outColor = vec4(clamp(color, 0.0, 1.0) * opacity.x, opacity.x);  // premultiplied
#else
  writeGBuffer(s, color, uLines, uObjectId, cut, false);
  writeCutterChannels(CHANNELS_BY, f);
#endif
}
