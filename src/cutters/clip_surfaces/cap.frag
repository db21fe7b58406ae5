#version 450 core
// Trapp13 §5.1, §5.3–5.4, §6.1, with §7's relief mapping: a cap fragment finds the nearest
// point of the displaced surface along its view ray within its prism (cap.vert) that is inside
// the capped solid (the volumetric parity test against its layered depth image) and that no
// other clip surface removes, and writes that point's depth; it is shaded with the active
// style from the relief's normal, occlusion and an optional solid texture.
#include "frame/frame_uniforms.glsl"
#include "styles/surface.glsl"
#include "style.glsl"
#include "clip_surfaces.glsl"
#include "parity.glsl"
#include "styles/shadows/shadow_lookup.glsl"
#include "styles/emphasis/emphasis.glsl"
#include "frame/gbuffer.glsl"
#include "cutters/composition.glsl"
in vec3 vWorldPosition;    // on the prism's back face
flat in vec4 vPrismT;      // the prism's eq. 2 texture coordinates: least (xy), greatest (zw)
flat in vec2 vPrismLift;   // and its extent along N, (P − O)·N: least, greatest
layout(location = 11) uniform int uObjectId;
layout(location = 13) uniform int uCutBy;  // the other cutters that cut the capped object
layout(location = 16) uniform float uEmphasisImportance;  // the capped object's emphasisImportance()
layout(location = 40) uniform int uCapSurface;
layout(location = 41) uniform mat4 uCapToTexture;  // world → LDI space of the capped solid
layout(location = 45) uniform int uDepthComplexity;
layout(location = 46) uniform vec3 uCapColor;
layout(location = 49) uniform int uHasDiffuse;
// Nearer by this many steps of depth resolution (a nested cap: frame/depth_offsets.hpp).
layout(location = 51) uniform float uDepthUnits;
// The capped surface's relief maps (uClipRelief[uCapSurface]), read in capOnRay's loop without
// clipRelief's switch, whose every case llvmpipe runs.
layout(binding = UNIT_CAP_RELIEF) uniform sampler2D uCapRelief;
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

// Where the view ray p + λq is in the slab lo ≤ · ≤ hi: [entry, exit] (empty where it runs
// along the slab outside it).
vec2 slabSpan(float p, float q, float lo, float hi) {
  if (abs(q) < 1e-30) return p >= lo && p <= hi ? vec2(-1e30, 1e30) : vec2(1e30, -1e30);
  float a = (lo - p) / q, b = (hi - p) / q;
  return vec2(min(a, b), max(a, b));
}

// A point of the displaced surface shows the cap where it is in front of the eye, no other
// cutter removes it (an adaptive cutaway removes it in front of its surface), it is inside the
// capped solid (the volumetric parity test against its layered depth image) and the other
// surfaces leave the cut open there (under a union none of them clips, under an intersection
// all of them do). Returns its window depth, or −1.
float capDepth(int i, vec3 x) {
  vec4 clip = uViewProjection * vec4(x, 1.0);
  float depth = 0.5 * clip.z / clip.w + 0.5;
  if (clip.w <= 0.0 || depth < 0.0 || depth > 1.0) return -1.0;
  vec3 cutPosition, cutNormal;
  int cutter;
  CutFragment f = CutFragment(x, -clipSurfaceNormal(i), true);
  if (cutFragment(uCutBy, -1, f, cutPosition, cutNormal, cutter) == kDiscard) return -1.0;
  vec4 t = uCapToTexture * vec4(x, 1.0);
  bool inside = volumetricParityTest(t.xyz / t.w, uDepthComplexity);
  imageAtomicMax(uCapParity, ivec2(gl_FragCoord.xy), inside ? 2u : 1u);
  if (!inside) return -1.0;
  if (uClipCount.x > 1) {
    bool others = clippedBySurfaces(x, i);
    if (uClipCount.y == 1 ? !others : others) return -1.0;
  }
  return depth;
}

// The view ray through this fragment within its prism, walked through the cells of the
// bilinear sample (between four texel centres, the texel-centre space's unit squares) in the
// ray's order: a 2-D grid traversal. λ is the distance along the ray from its origin.
struct RayWalk {
  vec3 origin, d;
  vec2 t0, dt;     // eq. 2's T along the ray: t0 + λ dt
  float e0, de;    // (P − O)·N along the ray
  vec2 size, g;    // the map's texels; dT/dλ in texels
  vec2 x0;         // the ray's origin in the texel-centre space (cell k spans [k, k + 1])
  vec2 dir, across, next;  // the walk: its step, λ per cell, λ at the next sides
  vec2 cell;
  float a, exit;   // λ where this cell is entered; where the prism is left
  float after;     // roots up to here were tried
  float pad;       // what the prism's span is widened by
  float slack;     // how far past its cell's sides the last root was looked for
};

// λ where the ray crosses the walk's cell's sides `side` (0: the lower, 1: the upper) along
// each axis, from the ray itself and the cell (±1e30 along an axis it runs parallel to): the
// same in every prism that walks the cell, so that nested caps solve alike (see nextRoot).
vec2 cellSides(RayWalk w, vec2 side) {
  vec2 l = (w.cell + side - w.x0) * w.dir * w.across;
  return vec2(w.across.x < 1e30 ? l.x : side.x * 2e30 - 1e30, w.across.y < 1e30 ? l.y : side.y * 2e30 - 1e30);
}

RayWalk startWalk(int i) {
  RayWalk w;
  // The view ray through the pixel's centre, from the pixel alone: every prism that covers it
  // walks the same ray, so nested caps tie bit for bit and their offset decides. (An
  // orthographic back face may lie in front of the eye plane, λ < 0.)
  vec4 v = uInverseProjection * vec4(gl_FragCoord.xy * uViewport.zw * 2.0 - 1.0, 0.0, 1.0);
  vec3 onRay = (uInverseView * vec4(v.xyz / v.w, 1.0)).xyz;
  w.origin = viewRayOrigin(onRay);
  w.d = uCounts.y == 1 ? uForward.xyz : normalize(onRay - w.origin);
  vec3 ray = vWorldPosition - w.origin;
  vec3 rel = w.origin - uClipOrigin[i].xyz, n = clipSurfaceNormal(i);
  w.t0 = vec2(dot(rel, uClipToS[i].xyz), dot(rel, uClipToT[i].xyz));
  w.dt = vec2(dot(w.d, uClipToS[i].xyz), dot(w.d, uClipToT[i].xyz));
  w.e0 = dot(rel, n), w.de = dot(w.d, n);
  // The prism itself (cap.vert draws it larger), a little past its sides, so that a root on the
  // side two prisms share is found.
  vec2 s = slabSpan(w.t0.x, w.dt.x, vPrismT.x, vPrismT.z),
       t = slabSpan(w.t0.y, w.dt.y, vPrismT.y, vPrismT.w),
       e = slabSpan(w.e0, w.de, vPrismLift.x, vPrismLift.y);
  // A few steps of float at the size of the coordinates (a scene far from the origin).
  w.pad = 1e-5 * length(ray) + 5e-7 * (length(w.origin) + length(uClipOrigin[i].xyz));
  // An orthographic view's near plane may lie behind its eye plane, where its rays start.
  w.a = max(max(max(s.x, t.x), e.x) - w.pad, uCounts.y == 1 ? -1e30 : 0.0);
  w.exit = min(min(s.y, t.y), e.y) + w.pad;
  w.after = w.a - w.pad;
  w.size = vec2(textureSize(uCapRelief, 0));
  w.g = w.dt * w.size;
  w.x0 = w.t0 * w.size - 0.5;
  w.cell = floor(w.x0 + w.a * w.g);
  w.dir = vec2(w.g.x >= 0.0 ? 1.0 : -1.0, w.g.y >= 0.0 ? 1.0 : -1.0);
  w.across = vec2(abs(w.g.x) > 1e-30 ? 1.0 / abs(w.g.x) : 1e30,
                  abs(w.g.y) > 1e-30 ? 1.0 / abs(w.g.y) : 1e30);
  w.next = cellSides(w, max(w.dir, 0.0));
  return w;
}

// The next λ past w.after where f = 0 of eq. 1, or −1e30 (an orthographic ray's λ may be
// negative: its near plane may lie behind the eye plane). f is bilinear in the map's texels and
// linear in the ray, so within a cell it is a quadratic in λ, solved exactly.
float nextRoot(inout RayWalk w, float sz) {
  for (int k = 0; k < 1024 && w.a < w.exit; ++k) {
    float b = min(min(w.next.x, w.next.y), w.exit);
    // textureGather's order: (0, 1), (1, 1), (1, 0), (0, 0) of the cell's corners.
    vec4 h = textureGather(uCapRelief, (w.cell + 1.0) / w.size, 0);
    float h00 = h.w, dx = h.z - h.w, dy = h.x - h.w, dxy = h.y - h.x - h.z + h.w;
    // f(a + μ) = c0 + c1 μ + c2 μ², about where the ray enters the cell (not the prism: two
    // prisms that walk the cell find the same roots, bit for bit).
    vec2 sides = cellSides(w, 1.0 - max(w.dir, 0.0));
    float entry = max(sides.x, sides.y);
    entry = entry > -1e29 ? entry : 0.0;  // a ray along N stays in its cell
    float len = b - entry;
    vec2 u = w.x0 + entry * w.g - w.cell;  // the weights where the ray enters
    float c0 = w.e0 + entry * w.de + sz * (h00 + dx * u.x + dy * u.y + dxy * u.x * u.y);
    float c1 = w.de + sz * (dx * w.g.x + dy * w.g.y + dxy * (u.x * w.g.y + u.y * w.g.x));
    float c2 = sz * dxy * w.g.x * w.g.y;
    vec2 roots = vec2(-1e30);
    if (abs(c2) * len * len <= 1e-6 * (abs(c1) * len + abs(c0))) {
      if (c1 != 0.0) roots.x = -c0 / c1;
    } else {
      float disc = c1 * c1 - 4.0 * c2 * c0;
      if (disc >= 0.0) {
        float q = -0.5 * (c1 + (c1 >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
        roots = vec2(q / c2, q != 0.0 ? c0 / q : -1e30);
        if (roots.y < roots.x) roots = roots.yx;
      }
    }
    // A root on a cell's side counts in both cells, so none falls between them.
    float slack = 1e-4 * len;
    roots += entry;
    for (int m = 0; m < 2; ++m)
      if (roots[m] > w.after && roots[m] >= w.a - slack && roots[m] <= b + slack) {
        w.slack = slack;
        return roots[m];
      }
    w.a = b;
    bvec2 step = lessThanEqual(w.next, vec2(b));
    w.cell += mix(vec2(0.0), w.dir, vec2(step));
    w.next = cellSides(w, max(w.dir, 0.0));
  }
  return -1e30;
}

// The nearest point along this fragment's view ray, within its prism, where f = 0 and the cap
// shows (capDepth); false where there is none, with x then where the ray crosses the middle of
// the prism's lift: a discarded fragment's neighbours take their screen-space derivatives
// (the hatching's texture gradients) across it.
bool capOnRay(int i, out vec3 x, out float depth) {
  RayWalk w = startWalk(i);
  for (int k = 0; k < 64; ++k) {
    float root = nextRoot(w, uClipScale[i].z);
    if (root <= -1e30) break;
    x = w.origin + root * w.d;
    depth = capDepth(i, x);
    if (depth >= 0.0) return true;
    w.after = root + 2.0 * w.slack;  // past the same root found again in the next cell
  }
  float middle = 0.5 * (vPrismLift.x + vPrismLift.y) - w.e0;
  x = w.origin + (abs(w.de) > 1e-30 ? middle / w.de : 0.0) * w.d;
  return false;
}

void main() {
  int i = uCapSurface;
  vec3 x;
  float depth;
  if (!capOnRay(i, x, depth)) discard;
  // Nearer by uDepthUnits steps of the depth buffer's resolution at this depth, as a polygon
  // offset would draw it (GL_DEPTH_COMPONENT32F: 2^(e − 23) for depth's exponent e).
  int e;
  frexp(depth, e);
  gl_FragDepth = depth + uDepthUnits * exp2(float(e - 24));
  vec3 n = clipSurfaceNormal(i);
  vec2 st = clipSurfaceTexCoord(i, x);
  vec4 relief = textureLod(uCapRelief, st, 0.0);
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
  if (uHasDiffuse != 0) base *= texture(uCapDiffuse, st).rgb;
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
