#version 450 core
// Trapp13 §5.1, §5.3–5.4, §6.1: a cap fragment is kept only inside the capped solid (the
// volumetric parity test against its layered depth image) and where no other clip surface
// removes it; it is shaded with the active style from the relief's normal, occlusion and an
// optional solid texture.
#include "frame/frame_uniforms.glsl"
#include "styles/surface.glsl"
#include "style.glsl"
#include "clip_surfaces.glsl"
#include "parity.glsl"
#include "styles/shadows/shadow_lookup.glsl"
#include "styles/emphasis/emphasis.glsl"
#include "frame/gbuffer.glsl"
#include "cutters/composition.glsl"
in vec3 vWorldPosition;
in vec2 vST;
layout(location = 11) uniform int uObjectId;
layout(location = 13) uniform int uCutBy;  // the other cutters that cut the capped object
layout(location = 16) uniform float uEmphasisImportance;  // the capped object's emphasisImportance()
layout(location = 40) uniform int uCapSurface;
layout(location = 41) uniform mat4 uCapToTexture;  // world → LDI space of the capped solid
layout(location = 45) uniform int uDepthComplexity;
layout(location = 46) uniform vec3 uCapColor;
layout(location = 49) uniform int uHasDiffuse;
layout(binding = UNIT_CAP_DIFFUSE) uniform sampler2D uCapDiffuse;  // §6.1 diffuse map, sampled at T
// Per pixel, the parity results of cap fragments: 1 = one was outside, 2 = one was inside.
layout(binding = IMAGE_CAP_PARITY, r32ui) uniform coherent uimage2D uCapParity;

// A procedural solid texture (Trapp13 Fig. 11): marble-like veins from 3-D value noise.
float solidHash(ivec3 c) {
  uint h = uint(c.x) * 0x8da6b343u + uint(c.y) * 0xd8163841u + uint(c.z) * 0xcb1ab31fu;
  h ^= h >> 15;
  h *= 0x2c1b3c6du;
  h ^= h >> 12;
  h *= 0x297a2d39u;
  h ^= h >> 15;
  return float(h >> 8) * (1.0 / 16777216.0);
}
float solidNoise(vec3 p) {
  vec3 i = floor(p), f = p - i, s = f * f * (3.0 - 2.0 * f);
  ivec3 c = ivec3(i);
  float x00 = mix(solidHash(c), solidHash(c + ivec3(1, 0, 0)), s.x);
  float x10 = mix(solidHash(c + ivec3(0, 1, 0)), solidHash(c + ivec3(1, 1, 0)), s.x);
  float x01 = mix(solidHash(c + ivec3(0, 0, 1)), solidHash(c + ivec3(1, 0, 1)), s.x);
  float x11 = mix(solidHash(c + ivec3(0, 1, 1)), solidHash(c + ivec3(1, 1, 1)), s.x);
  return mix(mix(x00, x10, s.y), mix(x01, x11, s.y), s.z);
}
float marble(vec3 p) {
  float turbulence = 0.0, weight = 0.5;
  vec3 q = p;
  for (int o = 0; o < 4; ++o, weight *= 0.5, q *= 2.0) turbulence += weight * solidNoise(q);
  return 0.5 + 0.5 * sin(p.x + 6.0 * turbulence);
}

// The grid is linear between its vertices while the clip test of eq. 1 samples the map
// bilinearly, so the two surfaces part by the map's curvature within a cell. Where a view ray
// grazes the solid's rim, the grid's point can then lie outside the solid where the surface
// that clipped the solid lies inside it: a pinhole in the cap. Two Newton steps along the view
// ray onto f = 0 of eq. 1 (the relief's gradient gives f's), each at most the relief's depth
// S_z, take the point that the clip test agrees with.
vec3 onClipSurface(int i, vec3 x) {
  vec3 d = normalize(x - viewRayOrigin(x)), n = clipSurfaceNormal(i);
  for (int k = 0; k < 2; ++k) {
    vec4 relief = clipRelief(i, clipSurfaceTexCoord(i, x));
    float f = dot(x - uClipOrigin[i].xyz, n) + relief.r * uClipScale[i].z;
    // ∂s/∂P and ∂t/∂P are eq. 2's axes.
    vec3 gradient = n + uClipScale[i].z * (relief.g * uClipToS[i].xyz + relief.b * uClipToT[i].xyz);
    float slope = dot(gradient, d);
    if (abs(slope) < 1e-6) break;
    x -= clamp(f / slope, -uClipScale[i].z, uClipScale[i].z) * d;
  }
  return x;
}

void main() {
  int i = uCapSurface;
  vec3 x = onClipSurface(i, vWorldPosition);
  // The other cutters cut the cap with its object (an adaptive cutaway removes it in front of
  // its surface); the cap faces the viewer.
  vec3 cutPosition, cutNormal;
  int cutter;
  CutFragment f = CutFragment(x, -clipSurfaceNormal(i), true);
  if (cutFragment(uCutBy, f, cutPosition, cutNormal, cutter) == kDiscard) discard;
  vec4 t = uCapToTexture * vec4(x, 1.0);
  bool inside = volumetricParityTest(t.xyz / t.w, uDepthComplexity);
  imageAtomicMax(uCapParity, ivec2(gl_FragCoord.xy), inside ? 2u : 1u);
  if (!inside) discard;
  // The cap of surface i bounds the clipped region where the other surfaces leave it: under a
  // union where none of them clips, under an intersection where all of them do.
  if (uClipCount.x > 1) {
    bool others = clippedBySurfaces(x, i);
    if (uClipCount.y == 1 ? !others : others) discard;
  }
  vec3 n = clipSurfaceNormal(i);
  vec4 relief = clipRelief(i, vST * uClipScale[i].xy);
  vec3 normal = -n;  // the cap faces the clipped side
  if (uClipCount.z != 0) {
    // Tangents of X(s,t) = O + sU + tV − S_z h(s S_x, t S_y) N.
    vec3 ds = uClipU[i].xyz - uClipScale[i].z * uClipScale[i].x * relief.g * n;
    vec3 dt = uClipV[i].xyz - uClipScale[i].z * uClipScale[i].y * relief.b * n;
    normal = normalize(cross(ds, dt));
    if (dot(normal, n) > 0.0) normal = -normal;
  }
  vec3 toEye = uCounts.y == 1 ? -uForward.xyz : normalize(uEye.xyz - x);
  if (dot(normal, toEye) < 0.0) normal = -normal;  // seen from the kept side through a gap
  vec3 base = uCapColor;
  if (uHasDiffuse != 0) base *= texture(uCapDiffuse, vST * uClipScale[i].xy).rgb;
  if (uCapStyle.y != 0.0) base *= mix(0.55, 1.1, marble(x * uCapStyle.z));
  SurfacePoint s;
  s.position = x;
  s.normal = normal;
  s.toEye = toEye;
  s.baseColor = base;
  s.specular = 0.05;
  s.shininess = 16.0;
  s.keyLightVisibility = keyLightVisibility(s.position);
  float occlusion = mix(1.0, relief.a, uCapStyle.x);
  writeGBuffer(s, emphasize(base, shadeSurface(s), uEmphasisImportance) * occlusion, 1.0, uObjectId, false, true);
  writeNoChannels();
}
