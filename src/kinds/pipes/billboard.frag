#version 450 core
// Konev18 §§5–6: a billboard quad shaded as a tube (eq. 11) in one of two stencil-selected
// passes. The outside pass (stencil 0, 2 or 4) shades the outer wall and leaves out, sample by
// sample: over stencil 0 the upper half of a cut stretch (Fig. 11), over a cut surface
// (stencil 2) this pipe's own one. Over the back of an end triangle (stencil 4, Fig. 10) the
// closed tube's end shows, upper half included. The inside pass (stencil 1) shades the inner
// wall with inverted normals and its own colour, and the water surface (§6.4). A region
// marked by another pipe's proxies is shaded as this pipe's outside (Konev18 §9's
// interference): the proxies' nearest pipe id per pixel tells whose region it is. Of this
// pipe, the cut stretch shows its inside there, and so does the closed tube beyond an end
// triangle where it lies behind the triangle: it is seen through the triangle's bore (eq. 14).
#include "frame/frame_uniforms.glsl"
#include "styles/surface.glsl"
#include "style.glsl"
#include "styles/shadows/shadow_lookup.glsl"
#include "frame/gbuffer.glsl"
#include "pipes.glsl"
in vec3 vWorld;
in vec3 vAxis;
in vec3 vNormal;
in float vArc;
flat in vec3 vFace;
flat in vec3 vDirection;
flat in int vPipe;
layout(location = PIPE_CLASS_LOCATION) out float outPipeClass;
layout(binding = UNIT_PIPE_OWNER) uniform isampler2D uProxyOwner;  // global pipe id + 1; 0: none
layout(binding = UNIT_PIPE_OWNER_DEPTH) uniform sampler2D uProxyDepth;  // that proxy's depth
// The pixel's samples at stencil 0 (x's bits 0–15), 2 (x's bits 16–31) and 1 (y):
// pipe_stencil_masks.frag.
layout(binding = UNIT_PIPE_STENCIL_MASKS) uniform isampler2D uStencilMasks;

// `onTube`: the point of the tube (or water) the fragment shows, where the shadow map is
// read; the quad itself lies through the axis, half of it behind the light's quad.
SurfacePoint surface(vec3 position, vec3 normal, vec3 color, vec3 onTube) {
  SurfacePoint s;
  s.position = position;
  s.normal = normal;
  s.toEye = uCounts.y == 1 ? -uForward.xyz : normalize(uEye.xyz - position);
  s.baseColor = color;
  s.specular = 0.35;
  s.shininess = 24.0;
  s.keyLightVisibility = keyLightVisibility(onTube);
  return s;
}

void write(SurfacePoint s, float pipeClass) {
  // No feature lines from inside an opened pipe: the inside, the water and the rims alternate
  // within a few pixels on a distant pipe, and their creases and depth steps would draw it as
  // a dashed line. The outside keeps its silhouettes and the opening's outline.
  float lines = pipeClass == kClassOutside ? 1.0 : 0.0;
  writeGBuffer(s, shadeSurface(s), lines, uNetworkObjectId, false, false);
  writeNoChannels();
  outPipeClass = pipeClass;
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  ivec2 masks = texelFetch(uStencilMasks, pixel, 0).rg;
  // llvmpipe (Mesa 22.3, 4 samples) runs the whole shader for a fragment whose samples all
  // fail the stencil test; a discard at every lane ends it early. Most of the inside pass's
  // fragments lie over no inside sample: the benchmark city's `pipes` pass took half the time
  // with this test (bench/RESULTS.md, 2026-12-06).
#if INSIDE_PASS
  if ((gl_SampleMaskIn[0] & masks.y) == 0) discard;
#endif
  bool cut = inCutStretch(vPipe, vArc);
  vec3 up = cutUp(vDirection);
  bool upper = dot(vWorld - vAxis, up) > 0.0;
  bool own = texelFetch(uProxyOwner, pixel, 0).r == int(uPipes[vPipe].radii.w) + 1 &&
             (cut || gl_FragCoord.z > texelFetch(uProxyDepth, pixel, 0).r);
  vec3 tube = normalize(vNormal + vFace);  // eq. 11
#if !INSIDE_PASS
  int removed = (cut && upper ? masks.x & 0xffff : 0) | (own ? masks.x >> 16 : 0);
  if ((gl_SampleMaskIn[0] & ~removed & ~masks.y) == 0) discard;  // nothing left to write
#ifndef SINGLE_SAMPLE
  gl_SampleMask[0] = ~removed;  // written by every invocation: else it is undefined
#endif
  write(surface(vWorld, tube, uPipeColor, vAxis + outerRadius(vPipe) * tube), kClassOutside);
#else
  if (!own) {
    write(surface(vWorld, tube, uPipeColor, vAxis + outerRadius(vPipe) * tube), kClassOutside);
    return;
  }
  // The inside, seen through the opening: the water surface where the view ray meets it
  // within the bore (§6.4), else the inner wall (§6) with the vertex normals inverted before
  // eq. 11's mean: N_f = (F_a − N)/|F_a − N|, so the far inner wall faces the viewer.
  float innerR = innerRadius(vPipe);
  float depth = uPipes[vPipe].radii.z * uRadiusScale;
  if (depth > 0.0) {
    vec3 origin = uCounts.y == 1 ? vWorld - uForward.xyz : uEye.xyz;
    vec3 ray = uCounts.y == 1 ? uForward.xyz : normalize(vWorld - uEye.xyz);
    // The surface's height over the axis; above the cut plane the water is cut with the
    // pipe, so it shows at the plane across the whole bore.
    float level = min(depth - innerR, 0.0);
    float along = dot(ray, up);
    if (along < 0.0) {
      float t = (level - dot(origin - vAxis, up)) / along;
      vec3 w = origin + t * ray;
      vec3 side = normalize(cross(vDirection, up));
      float halfChord = sqrt(max(innerR * innerR - level * level, 0.0));
      if (abs(dot(w - vAxis, side)) < halfChord) {
        write(surface(w, up, waterColor(depth, innerR), w), kClassWater);
        return;
      }
    }
  }
  vec3 inward = normalize(vFace - vNormal);
  write(surface(vWorld, inward, uInsideColor, vAxis - innerR * inward), kClassInside);
#endif
}
