#version 450 core
// C(p) = max(near plane, c(p, anchor(p))) (Burns11 eq. 4.2), stored as window depth.
#include "cone.glsl"
layout(binding = 2) uniform isampler2D uAnchors;
layout(location = 0) out float outCutawayDepth;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  int anchor = texelFetch(uAnchors, p, 0).r;
  float ndc = anchor >= 0 ? max(-1.0, coneDepth(p, anchor)) : -1.0;
  outCutawayDepth = ndc * 0.5 + 0.5;
}
