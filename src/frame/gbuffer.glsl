// The geometry pass's multisampled G-buffer (frame/gbuffer.cpp), written by every program
// that draws visible surfaces (kinds/meshes/mesh.frag, the clip-surface caps, the pipes),
// attached in this order, then the techniques' channels (generated: outChannel<i>).
layout(location = 0) out vec4 outColor;
#include "frame/normal_weight.glsl"
layout(location = 1) out uint outNormal;     // world normal and line weight (normal_weight.glsl)
// The object id, and the bits of the linear view depth of the point shaded, which lies on the
// view ray through the pixel's centre: the feature lines' silhouette test reads both with one
// fetch (styles/lines/lines.frag), and the position AOV is that point (frame/aovs.frag).
layout(location = 2) out ivec2 outObjectId;
// 0.5 on cut surfaces and cut walls, 1 on Trapp13 caps (both count as cut: >= 0.5)
layout(location = 3) out float outCutMask;
#include "frame/gbuffer_channels.glsl"

// Writes a shaded surface point to the G-buffer.
void writeGBuffer(SurfacePoint s, vec3 color, float lines, int objectId, bool cut, bool cap) {
  outColor = vec4(color, 1.0);
  outNormal = packNormalWeight(s.normal, lines);
  float viewDepth = -(uView * vec4(s.position, 1.0)).z;
  outObjectId = ivec2(objectId, floatBitsToInt(viewDepth));
  outCutMask = cap ? 1.0 : cut ? 0.5 : 0.0;
}
