// A pipe network's data for the billboard and proxy programs (src/render/pipes): the per-pipe
// buffer and the network's uniforms. Mirrors src/kinds/pipes/pipe_renderer.cpp.
struct PipeRecord {
  vec4 radii;  // x: r_out, y: wall thickness, z: water depth above the inner bottom, w: global id
  vec4 cut;    // x, y: the opened stretch in arc length; z: 1 if the pipe is cut open
};
layout(std430, binding = SSBO_PIPES) readonly buffer Pipes { PipeRecord uPipes[]; };
layout(location = 30) uniform float uRadiusScale;  // §5: radii changed at run time
layout(location = 31) uniform vec3 uPipeColor;
layout(location = 32) uniform vec3 uInsideColor;
layout(location = 33) uniform vec3 uPipeCutColor;
layout(location = 34) uniform vec3 uWaterLow;
layout(location = 35) uniform vec3 uWaterHigh;
layout(location = 36) uniform int uNetworkObjectId;

float outerRadius(int pipe) { return uPipes[pipe].radii.x * uRadiusScale; }
float innerRadius(int pipe) {
  return (uPipes[pipe].radii.x - uPipes[pipe].radii.y) * uRadiusScale;
}
bool inCutStretch(int pipe, float arc) {
  vec4 c = uPipes[pipe].cut;
  return c.z != 0.0 && arc >= c.x && arc <= c.y;
}
// The "up" of a cut perpendicular to the pipe's slope (§6.2: the proxy quads are built with
// it instead of the view direction).
vec3 cutUp(vec3 direction) {
  vec3 u = vec3(0.0, 1.0, 0.0) - direction.y * direction;
  return dot(u, u) < 1e-8 ? normalize(cross(direction, vec3(1.0, 0.0, 0.0))) : normalize(u);
}
// §6.4: water colour-coded by the fill ratio (water depth over the inner diameter).
vec3 waterColor(float depth, float innerR) {
  return mix(uWaterLow, uWaterHigh, clamp(depth / max(2.0 * innerR, 1e-6), 0.0, 1.0));
}
// Pipe classes written to the pipeClass AOV.
const float kClassOutside = 0.25, kClassInside = 0.5, kClassCut = 0.75, kClassWater = 1.0;
