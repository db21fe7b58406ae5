#version 450 core
// Konev18 §6: the proxy passes. uPass 1 draws the cut surface (T1 on the end triangles' front
// faces, Q2 on the quads) and the renderer's stencil op writes 2 there; uPass 2 marks the
// inside (T2, Q1; stencil 1); uPass 3 is Fig. 10's fix: an end triangle seen from behind
// resets its area to 0, so the pipe's outside shows there; uPass 4 writes the nearest
// proxy's pipe id for the billboards' ownership test.
#include "frame/frame_uniforms.glsl"
#include "styles/surface.glsl"
#include "style.glsl"
#include "styles/shadows/shadow_lookup.glsl"
#include "pipes.glsl"
#include "cutters/pipe_opening/pipe_opening.glsl"
in vec2 vUv;
in vec3 vWorld;
flat in int vPipe;
flat in int vKind;
flat in vec3 vPlaneNormal;
layout(location = 37) uniform int uPass;
#ifdef PROXY_OWNER
layout(location = 0) out int outOwner;
#else
#include "frame/gbuffer.glsl"
layout(location = PIPE_CLASS_LOCATION) out float outPipeClass;
#endif

void main() {
  float outerR = outerRadius(vPipe), innerR = innerRadius(vPipe);
  bool triangle = vKind == 0;
  if (uPass == 3) {  // Fig. 10
    if (!triangle || gl_FrontFacing || length(vUv - vec2(0.5)) >= 0.5) discard;
    return;
  }
  if (triangle && !gl_FrontFacing) discard;
#ifdef PROXY_OWNER
  int cutSurface = triangle ? proxyTriangle(1, vUv, innerR, outerR) : proxyQuad(1, vUv.y, innerR, outerR);
  int inside = triangle ? proxyTriangle(2, vUv, innerR, outerR) : proxyQuad(2, vUv.y, innerR, outerR);
  if (cutSurface == kProxyDiscard && inside == kProxyDiscard) discard;
  outOwner = int(uPipes[vPipe].radii.w) + 1;
#else
  int action = triangle ? proxyTriangle(uPass, vUv, innerR, outerR) : proxyQuad(uPass, vUv.y, innerR, outerR);
  if (action == kProxyDiscard) discard;
  if (uPass == 2) return;  // stencil only
  SurfacePoint s;
  s.position = vWorld;
  s.normal = gl_FrontFacing ? vPlaneNormal : -vPlaneNormal;
  s.toEye = uCounts.y == 1 ? -uForward.xyz : normalize(uEye.xyz - vWorld);
  s.baseColor = uPipeCutColor;
  s.specular = 0.1;
  s.shininess = 16.0;
  s.keyLightVisibility = keyLightVisibility(vWorld);
  // No feature lines on the thin rims either (see billboard.frag).
  writeGBuffer(s, shadeSurface(s), 0.0, uNetworkObjectId, true, false);
  writeNoChannels();
  outPipeClass = kClassCut;
#endif
}
