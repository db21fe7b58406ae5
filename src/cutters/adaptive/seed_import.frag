#version 450 core
// The seed from another application's depth of its objects of interest (any size): each
// cutaway-buffer texel takes the farthest rear hull in its footprint, so that no seed is lost
// and the cut is never shallower than at full resolution (Burns08 §5.1: the cutaway surface
// is the maximum of the seeds' cones); θ is the angle texture's value there, or uTheta.
layout(binding = 0) uniform sampler2D uInterestDepth;  // window depth, 0 = no seed
layout(binding = 1) uniform sampler2D uInterestAngle;  // radians, where uAngleTexture
layout(location = 0) uniform int uAngleTexture;
layout(location = 1) uniform float uTheta;
layout(location = 2) uniform int uBufferSize;
layout(location = 0) out float outSeedDepth;
layout(location = 1) out float outSeedAngle;
void main() {
  ivec2 source = textureSize(uInterestDepth, 0);
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 lo = p * source / uBufferSize;
  ivec2 hi = max((p + 1) * source / uBufferSize, lo + 1);
  float depth = 0.0;
  ivec2 at = lo;
  for (int y = lo.y; y < hi.y; ++y)
    for (int x = lo.x; x < hi.x; ++x) {
      float z = texelFetch(uInterestDepth, ivec2(x, y), 0).r;
      if (z > depth) {
        depth = z;
        at = ivec2(x, y);
      }
    }
  outSeedDepth = depth;
  outSeedAngle = uAngleTexture != 0 ? texelFetch(uInterestAngle, at, 0).r : uTheta;
}
