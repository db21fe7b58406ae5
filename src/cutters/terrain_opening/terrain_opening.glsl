// Konev18 §4: the terrain opened above the pipe network, per fragment (eqs. 1–3); mirrors
// terrainFate in terrain_function.cpp. Needs frame_uniforms.glsl.
#include "cutters/fate.glsl"
layout(location = LOC_TERRAIN_FRAME) uniform vec4 uTerrainFrame;   // min x, min z, 1 / size x, 1 / size z
layout(location = LOC_TERRAIN_PARAMS) uniform vec4 uTerrainParams;  // w, s, camera-distance dependency (0/1), T
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

int terrainFragment(CutFragment f, out vec3 cutPosition, out vec3 cutNormal) {
  vec3 x = f.position;
  ivec2 pixel = ivec2(CUT_FRAG_COORD.xy);
  vec2 uv = (x.xz - uTerrainFrame.xy) * uTerrainFrame.zw;
  float dc = length(uEye.xyz - x);
  float w = uTerrainParams.x, s = uTerrainParams.y;
  float t = uTerrainParams.z != 0.0 ? w * (s * s - dc) / s : w * s;  // eq. 1
  imageStore(uTerrainThreshold, pixel, vec4(dc, t, 0.0, 0.0));
  if (terrainDistanceAt(uv) >= t) {  // eq. 2: draw terrain
    imageAtomicMax(uTerrainClass, pixel, 1u);
    return kKeep;
  }
  // Eq. 2's peek: one texel further along the view's horizontal direction (y ignored).
  vec2 v = uForward.xz * uTerrainFrame.zw;
  v = dot(v, v) > 0.0 ? normalize(v) : vec2(0.0);
  if (terrainDistanceAt(uv + v * (sqrt(2.0) / uTerrainParams.w)) > t) {  // eq. 3: thickness
    imageAtomicMax(uTerrainClass, pixel, 2u);
    // Beyond the paper (its §4 suggestion): the thickness lit as a wall facing the closest
    // pipe, its normal against the distance field's gradient.
    float texel = 1.0 / uTerrainParams.w;
    vec2 g = vec2(terrainDistanceAt(uv + vec2(texel, 0.0)) - terrainDistanceAt(uv - vec2(texel, 0.0)),
                  terrainDistanceAt(uv + vec2(0.0, texel)) - terrainDistanceAt(uv - vec2(0.0, texel)));
    g *= uTerrainFrame.zw;  // per world unit
    vec3 n = dot(g, g) > 0.0 ? normalize(vec3(-g.x, 0.0, -g.y)) : -vec3(v.x, 0.0, v.y);
    cutPosition = x;
    cutNormal = dot(n, n) > 0.0 ? n : vec3(0.0, 1.0, 0.0);
    return kCutSurface;
  }
  imageAtomicMax(uTerrainClass, pixel, 3u);  // eq. 3: discard
  return kDiscard;
}
