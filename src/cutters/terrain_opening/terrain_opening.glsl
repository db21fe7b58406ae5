// Konev18 §4: the terrain opened above the pipe network, per fragment (eqs. 1–3); mirrors
// terrainFate in terrain_function.cpp. Needs frame_uniforms.glsl.
#include "cutters/fate.glsl"
layout(location = LOC_TERRAIN_FRAME) uniform vec4 uTerrainFrame;   // min x, min z, 1 / size x, 1 / size z
layout(location = LOC_TERRAIN_PARAMS) uniform vec4 uTerrainParams;  // w, s, camera-distance dependency (0/1), T
layout(location = LOC_TERRAIN_WALL) uniform float uTerrainWall;  // the wall's depth in half-widths; 0: eq. 3's peek
layout(binding = UNIT_TERRAIN_DISTANCE) uniform sampler2D uTerrainDistance;  // D_p in [0, 1]
// Per pixel: d_c and t of the last terrain fragment; the largest fate seen (1 terrain,
// 2 thickness, 3 discarded).
layout(binding = IMAGE_TERRAIN_THRESHOLD, rg32f) uniform writeonly image2D uTerrainThreshold;
layout(binding = IMAGE_TERRAIN_CLASS, r32ui) uniform coherent uimage2D uTerrainClass;

float terrainTexel(ivec2 texel) {
  return texelFetch(uTerrainDistance, clamp(texel, ivec2(0), textureSize(uTerrainDistance, 0) - 1), 0).r;
}

// As TerrainField::at: the nearest texel when rough (TERRAIN_NEAREST, TerrainOpening::
// glslDefines), else bilinear between texel centres, weighted in float as on the CPU rather
// than by the texture unit's coarser fixed-point weights.
float terrainDistanceAt(vec2 uv) {
  float n = float(textureSize(uTerrainDistance, 0).x);
  vec2 g = clamp(uv * n, vec2(-1.0), vec2(n + 1.0));
#if TERRAIN_NEAREST
  return terrainTexel(ivec2(floor(g)));
#else
  vec2 c = g - 0.5;
  vec2 base = floor(c), f = c - base;
  ivec2 i = ivec2(base);
  float bottom = terrainTexel(i) + f.x * (terrainTexel(i + ivec2(1, 0)) - terrainTexel(i));
  float top = terrainTexel(i + ivec2(0, 1)) + f.x * (terrainTexel(i + ivec2(1, 1)) - terrainTexel(i + ivec2(0, 1)));
  return bottom + f.y * (top - bottom);
#endif
}

// The wall's normal at uv: −∇D_p per world unit, towards the closest pipe; where D_p is flat,
// against the ray's horizontal direction `along`; for a vertical ray, up.
vec3 terrainWallNormal(vec2 uv, vec2 along) {
  float texel = 1.0 / uTerrainParams.w;
  vec2 g = vec2(terrainDistanceAt(uv + vec2(texel, 0.0)) - terrainDistanceAt(uv - vec2(texel, 0.0)),
                terrainDistanceAt(uv + vec2(0.0, texel)) - terrainDistanceAt(uv - vec2(0.0, texel)));
  g *= uTerrainFrame.zw;
  vec3 n = dot(g, g) > 0.0 ? normalize(vec3(-g.x, 0.0, -g.y)) : -vec3(along.x, 0.0, along.y);
  return dot(n, n) > 0.0 ? n : vec3(0.0, 1.0, 0.0);
}

int terrainFragment(CutFragment f, out vec3 cutPosition, out vec3 cutNormal) {
  vec3 x = f.position;
  ivec2 pixel = ivec2(CUT_FRAG_COORD.xy);
  vec2 uv = (x.xz - uTerrainFrame.xy) * uTerrainFrame.zw;
  float dc = length(uEye.xyz - x);
  float w = uTerrainParams.x, s = uTerrainParams.y, T = uTerrainParams.w;
  float t = uTerrainParams.z != 0.0 ? w * (s * s - dc) / s : w * s;  // eq. 1
  imageStore(uTerrainThreshold, pixel, vec4(dc, t, 0.0, 0.0));
  if (terrainDistanceAt(uv) >= t) {  // eq. 2: draw terrain
    imageAtomicMax(uTerrainClass, pixel, 1u);
    return kKeep;
  }
  vec3 ray = uCounts.y == 1 ? uForward.xyz : x - uEye.xyz;
  float across = length(ray.xz);
  vec2 along = across > 0.0 ? ray.xz / across : vec2(0.0);  // the ray's horizontal direction
  float found = -1.0;  // world distance along `along` to where D_p > t: the thickness
  if (uTerrainWall == 0.0) {
    // Eq. 3's peek: one texel (ε = √2/T in texture space) along the view's horizontal
    // direction.
    vec2 v = along * uTerrainFrame.zw;
    v = dot(v, v) > 0.0 ? normalize(v) : vec2(0.0);
    if (terrainDistanceAt(uv + v * (sqrt(2.0) / T)) > t) found = 0.0;
  } else if (ray.y < 0.0 && across > 0.0) {
    // Beyond the paper: the thickness as a trench wall of depth H = wall × the opening's
    // half-width (t · 255 texels). The ray, continued below the ground, meets the wall where
    // D_p first exceeds t within the horizontal distance it covers while descending H.
    float texel = inversesqrt(uTerrainFrame.z * uTerrainFrame.w) / T;
    float reach = uTerrainWall * t * 255.0 * texel * across / -ray.y;
    int steps = int(clamp(ceil(reach / texel), 1.0, 64.0));
    float step = reach / float(steps), below = 0.0;
    for (int k = 1; k <= steps && found < 0.0; ++k) {
      float d = float(k) * step;
      if (terrainDistanceAt(uv + along * d * uTerrainFrame.zw) > t) found = d;
      else below = d;
    }
    for (int k = 0; k < 6 && found > 0.0; ++k) {  // bisection: the crossing within a step
      float mid = 0.5 * (below + found);
      if (terrainDistanceAt(uv + along * mid * uTerrainFrame.zw) > t) found = mid;
      else below = mid;
    }
  }
  if (found < 0.0) {
    imageAtomicMax(uTerrainClass, pixel, 3u);  // eq. 3: discard
    return kDiscard;
  }
  imageAtomicMax(uTerrainClass, pixel, 2u);  // eq. 3: the artificial thickness
  cutPosition = found > 0.0 ? x + ray * (found / across) : x;
  // Beyond the paper (its §4 suggestion): lit as a wall facing the closest pipe.
  cutNormal = terrainWallNormal(uv + along * found * uTerrainFrame.zw, along);
  return kCutSurface;
}
