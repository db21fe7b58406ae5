#version 450 core
// A volume of interest as a region of interest (Burns08 §5.1, Burns11 §4.2.2): along the view
// ray through the pixel, the farthest sample whose material the transfer function makes
// visible is the rear of the region, the seed of a cutaway surface grown around it (the
// seed pass's greater-than depth test keeps the farthest over all geometry of interest).
#include "frame/frame_uniforms.glsl"
#include "kinds/volumes/volume_ray.glsl"
layout(location = 2) uniform float uStep;      // world units
layout(location = 16) uniform float uTheta;    // radians
layout(location = 17) uniform vec2 uPassSize;  // the seed buffer's pixels
layout(location = 0) out float outSeedDepth;
layout(location = 1) out float outSeedAngle;
void main() {
  VolumeRay r = volumeRay(gl_FragCoord.xy / uPassSize);
  if (!(r.tIn < r.tOut)) discard;
  // Back to front from the box's far side: the first sample of material is the rear.
  for (float t = r.tOut - 0.5 * uStep; t > r.tIn; t -= uStep) {
    vec3 index = r.o + t * r.d;
    if (texture(uTransfer, transferCoordinates(valueAt(index), index)).a <= 0.0) continue;
    vec4 clip = uViewProjection * vec4(r.origin + t * r.direction, 1.0);
    float depth = clamp(clip.z / clip.w * 0.5 + 0.5, 0.0, 1.0);  // the default depth range
    gl_FragDepth = depth;
    outSeedDepth = depth;
    outSeedAngle = uTheta;
    return;
  }
  discard;
}
