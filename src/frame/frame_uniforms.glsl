// Per-frame data shared by every pass (std140, binding 0); filled by src/render/renderer.cpp.
const int kMaxLights = 8;
layout(std140, binding = 0) uniform FrameUniforms {
  mat4 uView;
  mat4 uProjection;
  mat4 uViewProjection;
  mat4 uInverseProjection;
  mat4 uInverseView;
  vec4 uViewport;                 // width, height, 1/width, 1/height of the final image
  vec4 uEye;                      // world-space eye position
  vec4 uForward;                  // world-space viewing direction (orthographic view rays)
  vec4 uLightVector[kMaxLights];  // w = 0: direction the light travels; w = 1: position
  vec4 uLightColor[kMaxLights];   // colour × intensity
  ivec4 uCounts;                  // x: lights, y: 1 if orthographic
  vec4 uBackgroundTop;
  vec4 uBackgroundBottom;
  mat4 uShadowMatrix;             // world → [0,1]³ key-light shadow-map coordinates
  vec4 uShadowParams;             // x: 1 if on, y: bias (scene units), z: PCF radius, w: 1/size
};

// Where the view ray through world point x starts: the eye, or for orthographic views x's
// foot on the view plane through the eye (Camera::rayOrigin in C++).
vec3 viewRayOrigin(vec3 x) {
  return uCounts.y == 1 ? x - uForward.xyz * dot(x - uEye.xyz, uForward.xyz) : uEye.xyz;
}
