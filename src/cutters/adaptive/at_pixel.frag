#version 450 core
// Once per pixel centre, what clip.glsl decides every fragment of the pixel from: every
// fragment of the geometry passes lies there (one per pixel, no per-sample shading), so one
// unfiltered fetch of these gives the values the bilinear fetches gave.
// - C and its dilation (Burns08 §4.2), and C₂ and its dilation for the contextual structure
//   (Burns11 §4.1.3);
// - the simple structure's cut surface (Burns11 §5.2.4.1): where it cuts a solid, the back
//   faces seen through the cut stand for the cut surface, with the cutaway surface's normal at
//   the pixel's centre (five depth fetches here instead of per back face; its position is C's
//   point on the pixel's ray).
#include "frame/frame_uniforms.glsl"
#include "clip.glsl"
// C, dilated C, and C₂, dilated C₂ (window depths) or the cut surface's normal (octahedral).
layout(location = 0) out vec4 outAtPixel;
void main() {
  vec2 uv = gl_FragCoord.xy * uViewport.zw;
  outAtPixel.xy = vec2(textureLod(uCutawayDepth, uv, 0.0).r, textureLod(uCutawayDilated, uv, 0.0).r);
#ifdef UNIT_CUTAWAY_DEPTH_C2
  outAtPixel.zw = vec2(textureLod(uCutawayDepthC2, uv, 0.0).r, textureLod(uCutawayDilatedC2, uv, 0.0).r);
#else
  vec3 position, normal;
  cutawaySurfaceAt(uv, position, normal);
  outAtPixel.zw = octahedralEncode(normal);
#endif
}
