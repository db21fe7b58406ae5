// Trapp13 §5.3–5.4: the volumetric parity test against a layered depth image; mirrors
// volumetricParityTest in clip_surface_function.cpp. Inside when an odd number of layers lie
// in front of T along its ray (empty texels hold 1 and never count).
layout(binding = UNIT_CAP_LAYERS) uniform sampler2DArray uLdi;
bool volumetricParityTest(vec3 t, int depthComplexity) {
  if (t.x < 0.0 || t.y < 0.0 || t.z < 0.0 || t.x >= 1.0 || t.y >= 1.0 || t.z >= 1.0) return false;
  // Nearest filtering: the texel containing T, as the CPU mirror picks it.
  int crossings = 0;
  for (int i = 0; i < depthComplexity; ++i)
    if (texture(uLdi, vec3(t.xy, float(i))).r <= t.z) ++crossings;
  return (crossings & 1) == 1;
}
