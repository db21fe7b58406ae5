#version 450 core
// Jump flooding starts with every seed as its own anchor.
layout(binding = 0) uniform sampler2D uAnchorCone;
layout(location = 0) out int outAnchor;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  outAnchor = texelFetch(uAnchorCone, p, 0).w > 0.5 ? p.y * textureSize(uAnchorCone, 0).x + p.x : -1;
}
