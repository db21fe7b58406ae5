#version 450 core
#include "frame_uniforms.glsl"
in vec2 vUv;
layout(location = 0) out vec4 outColor;
void main() { outColor = vec4(mix(uBackgroundBottom.rgb, uBackgroundTop.rgb, vUv.y), 1.0); }
