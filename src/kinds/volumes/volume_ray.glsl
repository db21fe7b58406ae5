// What every volume program shares (kinds/volumes: the ray caster and the rear hulls of
// volumes of interest): the volume, its transfer function, and the view ray's span through its
// box. Mirrored by volume_ray_cast.cpp. Needs frame_uniforms.glsl.
layout(binding = 1) uniform sampler3D uVolume;  // the values; nearest filter for labels
// The transfer function's table: value along s over uTransferRange, gradient magnitude along t
// over uGradientRange (one row: a function of the value alone).
layout(binding = 2) uniform sampler2D uTransfer;  // colour, opacity
layout(binding = 3) uniform sampler2D uMaterialImportance;
layout(binding = 4) uniform sampler3D uGradient;  // index-space central differences
layout(location = 0) uniform mat4 uWorldToIndex;
layout(location = 1) uniform vec3 uDims;
layout(location = 4) uniform vec2 uTransferRange;  // values of the table's first and last texel
layout(location = 11) uniform mat3 uGradientToWorld;  // transpose of the inverse linear part
layout(location = 18) uniform vec2 uGradientRange;   // gradient magnitudes of its first, last row

vec3 worldAtWindow(vec2 uv, float depth) {
  vec4 h = uInverseView * (uInverseProjection * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0));
  return h.xyz / h.w;
}

float valueAt(vec3 index) {
  return texture(uVolume, (index + 0.5) / uDims).r;
}

// The world gradient of the values at an index-space point (value units per world unit): the
// voxels' central differences, interpolated.
vec3 gradientAt(vec3 index) {
  return uGradientToWorld * texture(uGradient, (index + 0.5) / uDims).xyz;
}

// The table coordinates of a value with the gradient magnitude at `index` (fetched only for a
// two-dimensional function: TRANSFER_2D), texel centres at the ends.
vec2 transferCoordinates(float value, vec3 index) {
  vec2 n = vec2(textureSize(uTransfer, 0));
  float s = clamp((value - uTransferRange.x) / (uTransferRange.y - uTransferRange.x), 0.0, 1.0);
  float t = 0.0;
#ifdef TRANSFER_2D
  t = clamp((length(gradientAt(index)) - uGradientRange.x) / (uGradientRange.y - uGradientRange.x),
            0.0, 1.0);
#endif
  return (vec2(s, t) * (n - 1.0) + 0.5) / n;
}

// The view ray through uv (window coordinates over the drawn viewport, in [0, 1]): world
// origin on the near plane and unit direction, the same ray in index space (o + t·d for the
// same t), and its span [tIn, tOut] through the box [−½, dims − ½] in front of the eye.
struct VolumeRay {
  vec3 origin, direction, o, d;
  float tIn, tOut;
};
VolumeRay volumeRay(vec2 uv) {
  VolumeRay r;
  r.origin = worldAtWindow(uv, 0.0);
  r.direction = normalize(worldAtWindow(uv, 1.0) - r.origin);
  r.o = (uWorldToIndex * vec4(r.origin, 1.0)).xyz;
  r.d = mat3(uWorldToIndex) * r.direction;
  vec3 inv = 1.0 / r.d;
  vec3 a = (vec3(-0.5) - r.o) * inv, b = (uDims - 0.5 - r.o) * inv;
  r.tIn = max(max(min(a.x, b.x), min(a.y, b.y)), max(min(a.z, b.z), 0.0));
  r.tOut = min(min(max(a.x, b.x), max(a.y, b.y)), max(a.z, b.z));
  return r;
}
