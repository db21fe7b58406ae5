#version 450 core
#include "frame/frame_uniforms.glsl"
#include "styles/surface.glsl"
#include "style.glsl"
#include "styles/shadows/shadow_lookup.glsl"
#include "frame/gbuffer.glsl"
#include "pipes.glsl"
in vec2 vLocal;
in vec3 vWorld;
flat in float vFill;
layout(location = PIPE_CLASS_LOCATION) out float outPipeClass;
void main() {
  if (dot(vLocal, vLocal) > 1.0) discard;
  SurfacePoint s;
  s.position = vWorld;
  s.normal = vec3(0.0, 1.0, 0.0);
  s.toEye = uCounts.y == 1 ? -uForward.xyz : normalize(uEye.xyz - vWorld);
  s.baseColor = mix(uWaterLow, uWaterHigh, vFill);
  s.specular = 0.5;
  s.shininess = 48.0;
  s.keyLightVisibility = keyLightVisibility(vWorld);
  writeGBuffer(s, shadeSurface(s), 1.0, uNetworkObjectId, false, false);
  writeNoChannels();
  outPipeClass = kClassWater;
}
