#version 450 core
// Burns08 §4.2: the minimum over a 1-pixel neighbourhood gives a slightly narrower cutaway
// for back faces, so at least one back-facing fragment shows wherever a surface is cut.
layout(binding = 0) uniform sampler2D uCutawayDepth;
layout(location = 0) out float outDilated;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 last = textureSize(uCutawayDepth, 0) - 1;
  float m = 1.0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      m = min(m, texelFetch(uCutawayDepth, clamp(p + ivec2(dx, dy), ivec2(0), last), 0).r);
  outDilated = m;
}
