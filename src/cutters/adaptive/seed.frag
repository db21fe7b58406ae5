#version 450 core
// Burns08 §5.1 / Burns11 §5.1.2: the region of interest's rear hull, kept by the greater-than
// depth test, seeds the cutaway surface; the object's local angle θ (Burns11 §6.2.1) is
// written beside it.
layout(location = 16) uniform float uTheta;  // radians
layout(location = 0) out float outSeedDepth;  // window depth of the rear hull
layout(location = 1) out float outSeedAngle;
void main() {
  outSeedDepth = gl_FragCoord.z;
  outSeedAngle = uTheta;
}
