// Hatching with tonal art maps (Praun, Hoppe, Webb, Finkelstein 2001, "Real-time hatching"):
// the key light's Lambert term (or Gooch's (1 + n·l)/2) gives the surface's lightness; its darkness 1 − L selects a
// position among the TAM's tones (built in src/styles/hatching/tonal_art_map.cpp), and the
// two tones bracketing it are blended (Praun01 §4: per-pixel blending of neighbouring
// tones; the nesting of the TAM keeps the blend free of popping strokes).
//
// Texture coordinates: the meshes have no UVs, and Praun01 use lapped textures for them. We
// use a triplanar projection in world space instead of screen space: screen-space strokes
// stay put while the object moves under them (the "shower door" effect), whereas world-space
// coordinates keep the strokes attached to the surface when the camera moves, at the price of
// stroke directions that follow the world axes rather than the surface's curvature. The
// three projections are weighted by |n|⁸ so that each surface region shows mostly one
// hatching direction. Mipmap levels are chosen from explicit screen-space gradients, taken
// in uniform control flow.
//
// In the key light's shadow the surface counts as unlit, so shadows are hatched darkest.
layout(binding = UNIT_TONAL_ART_MAP) uniform sampler2DArray uTonalArtMap;
layout(std140, binding = BLOCK_STYLE) uniform HatchingUniforms {
  vec4 uHatchPaper;   // rgb: paper colour, w: tint by the object colour
  vec4 uHatchInk;     // rgb: ink colour, w: number of tones
  vec4 uHatchParams;  // x: 1 / tile size (world units), y: 1 for Gooch lightness
};

// Ink coverage of the TAM at `uv`, blended between the tones bracketing `darkness` ∈ [0, 1].
// Tone position u = darkness · tones − 1: −1 is bare paper, tones − 1 the darkest tone, so
// the mean ink grows linearly with darkness (tonalArtMapTarget in C++).
float hatchInk(vec2 uv, vec2 dx, vec2 dy, float darkness) {
  float tones = uHatchInk.w;
  float u = darkness * tones - 1.0;
  float lower = floor(u);
  float w = u - lower;
  float inkLower = lower < 0.0 ? 0.0
                               : textureGrad(uTonalArtMap, vec3(uv, lower), dx, dy).r;
  float inkUpper = textureGrad(uTonalArtMap, vec3(uv, min(lower + 1.0, tones - 1.0)), dx, dy).r;
  return mix(inkLower, inkUpper, w);
}

vec3 shadeSurface(SurfacePoint s) {
  vec3 l = uCounts.x > 0 ? towardsLight(0, s.position) : s.toEye;
  float nDotL = dot(s.normal, l);
  // y = 0: Lambert, max(n·l, 0); y = 1: Gooch's t = (1 + n·l) / 2 (Gooch98), which keeps
  // surfaces turned away from the light in the middle tones rather than the darkest.
  float lightness = uHatchParams.y == 0.0
                        ? max(nDotL, 0.0) * s.keyLightVisibility
                        : 0.5 * (1.0 + min(nDotL, 0.0) + max(nDotL, 0.0) * s.keyLightVisibility);
  float darkness = clamp(1.0 - lightness, 0.0, 1.0);

  vec3 p = s.position * uHatchParams.x;  // tile units
  vec3 weights = pow(abs(s.normal), vec3(8.0));
  weights /= weights.x + weights.y + weights.z;
  // The three planar projections (x: zy, y: xz, z: xy), each with its own gradients.
  vec2 uvX = p.zy, uvY = p.xz, uvZ = p.xy;
  float ink = weights.x * hatchInk(uvX, dFdx(uvX), dFdy(uvX), darkness) +
              weights.y * hatchInk(uvY, dFdx(uvY), dFdy(uvY), darkness) +
              weights.z * hatchInk(uvZ, dFdx(uvZ), dFdy(uvZ), darkness);
  // The object colour tints the paper lightly, so objects stay distinguishable.
  vec3 paper = uHatchPaper.rgb * mix(vec3(1.0), s.baseColor, uHatchPaper.w);
  return mix(paper, uHatchInk.rgb, ink);
}
