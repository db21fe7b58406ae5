// Trapp13 §5.3–5.4: the volumetric parity test against a layered depth image; mirrors
// volumetricParityTest in clip_surface_function.cpp. Inside when an odd number of layers lie
// in front of T along its ray (empty texels hold 1 and never count).
layout(binding = UNIT_CAP_LAYERS) uniform sampler2DArray uLdi;
bool volumetricParityTest(vec3 t, int depthComplexity) {
  if (t.x < 0.0 || t.y < 0.0 || t.z < 0.0 || t.x >= 1.0 || t.y >= 1.0 || t.z >= 1.0) return false;
  // Each layer's depth between the four texel centres around T, bilinearly, where the four
  // rays cross the same number of layers (the same sheets of the surface); elsewhere the
  // texel containing T. The texel's own depth is off by its slope over up to half a texel,
  // which near the surface puts points on the wrong side: pinholes in a cap at its rim.
  vec2 texel = t.xy * vec2(textureSize(uLdi, 0).xy) - 0.5;
  vec2 w = texel - floor(texel);
  // textureGather's order: (0, 1), (1, 1), (1, 0), (0, 0) of the 2×2 texels around T.
  int nearest = w.y >= 0.5 ? (w.x >= 0.5 ? 1 : 0) : (w.x >= 0.5 ? 2 : 3);
  ivec4 count = ivec4(0);
  int crossings = 0, crossingsNearest = 0;
  for (int i = 0; i < depthComplexity; ++i) {
    vec4 depth = textureGather(uLdi, vec3(t.xy, float(i)));
    count += ivec4(lessThan(depth, vec4(1.0)));
    if (mix(mix(depth.w, depth.z, w.x), mix(depth.x, depth.y, w.x), w.y) <= t.z) ++crossings;
    if (depth[nearest] <= t.z) ++crossingsNearest;
  }
  bool sameSheets = all(equal(count, ivec4(count.x)));
  return ((sameSheets ? crossings : crossingsNearest) & 1) == 1;
}
