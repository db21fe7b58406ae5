// What every volume program shares (kinds/volumes: the ray caster and the rear hulls of
// volumes of interest): the volume, its transfer function, and the view ray's span through its
// box. Mirrored by volume_ray_cast.cpp. Needs frame_uniforms.glsl.
layout(binding = 1) uniform sampler3D uVolume;  // the values; nearest filter for labels
layout(binding = 2) uniform sampler1D uTransfer;  // colour, opacity over uTransferRange
layout(binding = 3) uniform sampler1D uMaterialImportance;  // importance over uTransferRange
layout(binding = 4) uniform sampler3D uGradient;  // index-space central differences
layout(location = 0) uniform mat4 uWorldToIndex;
layout(location = 1) uniform vec3 uDims;
layout(location = 4) uniform vec2 uTransferRange;  // values of the table's first and last texel

vec3 worldAtWindow(vec2 uv, float depth) {
  vec4 h = uInverseView * (uInverseProjection * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0));
  return h.xyz / h.w;
}

float valueAt(vec3 index) {
  return texture(uVolume, (index + 0.5) / uDims).r;
}

float transferCoordinate(float value) {
  float n = float(textureSize(uTransfer, 0));
  float t = clamp((value - uTransferRange.x) / (uTransferRange.y - uTransferRange.x), 0.0, 1.0);
  return (t * (n - 1.0) + 0.5) / n;  // texel centres at the ends
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
