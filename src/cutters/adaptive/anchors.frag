#version 450 core
// Per seed pixel: its cone (src/cutters/adaptive/cutaway_function.cpp, the same equations).
layout(binding = 0) uniform sampler2D uSeedDepth;
layout(binding = 1) uniform sampler2D uSeedAngle;
layout(location = 0) uniform int uEdgeCompression;
layout(location = 1) uniform float uEdgeRegion;
layout(location = 2) uniform int uDirectional;
layout(location = 3) uniform vec3 uFloorNormal;  // view space, unit
layout(location = 4) uniform int uCompensation;
layout(location = 5) uniform int uOrthographic;
// The camera's projection and its inverse, not the frame block's: the surface is also
// computed outside the renderer's frames (cutaway/cutters/adaptive_surface.hpp).
layout(location = 6) uniform mat4 uProjection;
layout(location = 7) uniform mat4 uInverseProjection;
layout(location = 8) uniform float uMinAngle;  // radians: C₂ widens every seed to θ₂ (Burns11 §4.1.3.1)
layout(location = 0) out vec4 outCone;   // z (NDC), mE, mF, seeded
layout(location = 1) out vec2 outFloor;

const float kPi = 3.14159265358979;
const float kMinAngle = 1e-4;
const float kFloorMargin = 2.0 * kPi / 180.0;

float slope(float angle, float z) {
  float t = tan(clamp(angle, kMinAngle, kPi / 2.0 - kMinAngle));
  if (uCompensation == 0) return uProjection[1][1] / t;   // Burns08 §3
  if (uOrthographic != 0) return abs(uProjection[2][2]) / t;
  return -(uProjection[2][2] + z) / t;                     // Burns11 eq. 5.7
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float window = texelFetch(uSeedDepth, p, 0).r;
  if (window <= 0.0) {  // not seeded: the buffer was cleared to the near plane
    outCone = vec4(-1.0, 0.0, 0.0, 0.0);
    outFloor = vec2(0.0);
    return;
  }
  vec2 size = vec2(textureSize(uSeedDepth, 0));
  vec3 ndc = vec3((vec2(p) + 0.5) / size * 2.0 - 1.0, window * 2.0 - 1.0);
  float thetaE = max(texelFetch(uSeedAngle, p, 0).r, uMinAngle);
  if (uEdgeCompression != 0)  // Burns11 eq. 5.8
    thetaE *= clamp((1.0 - abs(ndc.x)) / uEdgeRegion, 0.0, 1.0) *
              clamp((1.0 - abs(ndc.y)) / uEdgeRegion, 0.0, 1.0);
  float thetaF = thetaE;
  vec2 floorDirection = vec2(0.0);
  float floorBound = 0.0;  // the least m_F that keeps the wall off the floor
  if (uDirectional != 0) {
    vec4 h = uInverseProjection * vec4(ndc, 1.0);
    vec3 point = h.xyz / h.w;
    vec3 toEye = uOrthographic != 0 ? vec3(0.0, 0.0, 1.0) : normalize(-point);
    // Eq. 6.1: φ = π/2 − acos(n·v) = asin(n·v), taken as atan2 because GLSL's acos is a
    // low-precision approximation on some drivers (Mesa: ~1e-4).
    float nv = clamp(dot(uFloorNormal, toEye), -1.0, 1.0);
    float phi = atan(nv, sqrt(1.0 - nv * nv));
    // Eq. 6.2, clamped kFloorMargin below φ (see cutaway_function.cpp).
    thetaF = clamp(thetaE, 0.0, max(phi - kFloorMargin, 0.0)) + thetaE * smoothstep(0.0, kPi / 18.0, -phi);
    // Eq. 6.3's n̂_proj: d/dt of the projection of point + t·n (quotient rule).
    vec4 c = uProjection * vec4(point, 1.0), dc = uProjection * vec4(uFloorNormal, 0.0);
    vec2 d = (dc.xy * c.w - c.xy * dc.w) / vec2(uProjection[0][0], uProjection[1][1]);
    float len = length(d);
    if (len > 1e-9) floorDirection = d / len;  // eq. 6.3's n̂_proj
    // m_F no shallower than the floor plane's own slope along n̂_proj (see cutaway_function.cpp).
    if (uCompensation != 0 && uOrthographic == 0 && phi > kFloorMargin) {
      float nDotPoint = dot(uFloorNormal, point);
      float q = dot(uFloorNormal, uInverseProjection[2].xyz) - nDotPoint * uInverseProjection[2].w;
      vec2 gradient = -vec2(uProjection[0][0] * (dot(uFloorNormal, uInverseProjection[0].xyz) -
                                                 nDotPoint * uInverseProjection[0].w),
                            uProjection[1][1] * (dot(uFloorNormal, uInverseProjection[1].xyz) -
                                                 nDotPoint * uInverseProjection[1].w)) / q;
      float floorSlope = dot(gradient, floorDirection);
      if (!isinf(floorSlope) && !isnan(floorSlope) && floorSlope > 0.0)
        floorBound = floorSlope * tan(phi) / tan(phi - kFloorMargin);
    }
  }
  outCone = vec4(ndc.z, slope(thetaE, ndc.z), max(slope(thetaF, ndc.z), floorBound), 1.0);
  outFloor = floorDirection;
}
