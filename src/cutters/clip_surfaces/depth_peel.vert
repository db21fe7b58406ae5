#version 450 core
// Trapp13 §5.2: a mesh drawn orthographically into LDI space [0,1]³ (M · model).
layout(location = 0) in vec3 aPosition;
layout(location = 0) uniform mat4 uToTexture;
void main() {
  vec3 t = (uToTexture * vec4(aPosition, 1.0)).xyz;
  gl_Position = vec4(t * 2.0 - 1.0, 1.0);
}
