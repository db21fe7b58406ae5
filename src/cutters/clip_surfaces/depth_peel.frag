#version 450 core
// Depth peeling (Everitt 2001) for the volumetric depth sprite (Trapp13 §5.2): keep the
// nearest surface strictly behind the previous layer; depths are linear (orthographic).
layout(binding = 0) uniform sampler2D uPreviousLayer;  // -1 before the first layer
layout(location = 0) out float outDepth;
void main() {
  if (gl_FragCoord.z <= texelFetch(uPreviousLayer, ivec2(gl_FragCoord.xy), 0).r) discard;
  outDepth = gl_FragCoord.z;
}
