#version 450 core
// A volume's lines over the final colour (volume_lines_pass.hpp), antialiased across their
// width; the halo pass draws their halos in the halo colour.
layout(location = 23) uniform int uHalo;  // 1: the halo pass
layout(location = 24) uniform vec3 uHaloColor;
in vec3 vColor;
flat in float vOpacity;
noperspective in float vAcross;
flat in float vHalfWidth;
layout(location = 0) out vec4 outColor;  // premultiplied, blended over the final colour
layout(location = 1) out float outCoverage;
void main() {
  float alpha = clamp(vHalfWidth + 0.5 - abs(vAcross), 0.0, 1.0) * vOpacity;
  if (alpha <= 0.0) discard;
  outColor = vec4((uHalo == 1 ? uHaloColor : vColor) * alpha, alpha);
  outCoverage = uHalo == 1 ? 0.0 : alpha;
}
