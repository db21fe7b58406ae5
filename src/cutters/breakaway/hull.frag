#version 450 core
// Diepstraten03 §5: the inflated hull's surface; the depth test keeps its foremost layer and
// this writes the hull's world normal there (the cut wall's normal).
in vec3 vWorldPosition;
in vec3 vWorldNormal;
layout(location = 0) out vec4 outNormal;
void main() {
  outNormal = vec4(normalize(gl_FrontFacing ? vWorldNormal : -vWorldNormal), 0.0);
}
