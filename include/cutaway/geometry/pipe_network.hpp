// cutaway/geometry/pipe_network.hpp — sub-terrain tubular networks (Konev et al. 2018): pipes
// as polylines of nodes with a radius, a wall thickness and a water level, cut open along a
// stretch; shafts as vertical thick-walled cylinders. The CPU side of §§5–7: the billboard
// frame of eqs. 4–7, the tube normals of eqs. 8–11, the proxy tests of eqs. 12–16 and the
// shaft wedge of §7, mirrored by the shaders in src/render/pipes and src/cutters/{pipe_opening,
// shaft_wedge}; and the meshes (tessellated pipes, shafts, joints) built from a network.
//
//   cutaway::PipeNetwork net;
//   net.pipes.push_back({.nodes = {{0, -2, 0}, {10, -2, 0}, {20, -2.5f, 5}}, .radius = 0.5f});
//   addJunctionShafts(net, {.radius = 0.6f}, [](glm::vec2) { return 0.0f; });
//   std::vector<glm::vec3> u = billboardUp(net.pipes[0].nodes, eye);   // eqs. 4–7
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cutaway/geometry/mesh.hpp"

namespace cutaway {

struct Pipe {
  std::vector<glm::vec3> nodes;  // the axis, scene units; consecutive nodes distinct
  float radius = 0.5f;           // r_out
  float wallThickness = 0.08f;   // r_out − r_in, in (0, r_out]
  float waterLevel = 0.0f;       // depth of the water above the inner bottom, in [0, 2 r_in]
  // The opened stretch as arc-length distances from the first node (§6: an object-aligned
  // box cut removes the upper half there); none: the pipe is closed.
  std::optional<glm::vec2> cut;
  std::int64_t featureId = -1;  // the GIS feature it came from, −1 when given inline
  float innerRadius() const { return radius - wallThickness; }
  float length() const;
};

struct Shaft {
  glm::vec3 bottom{0.0f};  // centre of the floor
  float top = 0.0f;        // height of the rim (y)
  float radius = 0.6f;     // outer
  float wallThickness = 0.1f;
  float waterLevel = 0.0f;  // water depth above the floor
  float innerRadius() const { return radius - wallThickness; }
};

struct PipeNetwork {
  std::string name;
  std::vector<Pipe> pipes;
  std::vector<Shaft> shafts;
  glm::vec3 color{0.72f, 0.45f, 0.3f};        // outside of pipes and shafts
  glm::vec3 insideColor{0.9f, 0.86f, 0.75f};  // §6: another base colour inside
  glm::vec3 cutColor{0.2f, 0.75f, 0.25f};     // §6: contrasting cut surface
  // Water colour-coded by the fill ratio (water depth over the inner diameter), §6.4.
  glm::vec3 waterLow{0.55f, 0.85f, 0.95f}, waterHigh{0.05f, 0.2f, 0.65f};
  float shaftOpening = 0.3f;  // §7 coefficient: discard where n·v (height ignored) exceeds it
  float radiusScale = 1.0f;   // §5: every radius times this, at run time
  // Billboards (§5) or, for comparison (Table 1), tessellated pipes as a mesh object.
  enum class Mode { Billboards, Mesh } mode = Mode::Billboards;
  Bounds bounds() const;
};

// Eqs. 4–7: the unit direction û_i from node P_i to its billboard quad's upper vertex for a
// viewer at `eye` (v̂_i = P_i − eye, normalised), û_i = v̂_i × n̂ with n̂ the segment direction
// at the ends and the normalised mean of the two segment directions between (the twist that
// joins the quads). The lower vertex is −û_i (eq. 7). Orthographic views pass `viewDirection`
// instead: the same v̂ at every node.
std::vector<glm::vec3> billboardUp(const std::vector<glm::vec3>& nodes, const glm::vec3& eye);
std::vector<glm::vec3> billboardUpOrthographic(const std::vector<glm::vec3>& nodes,
                                               const glm::vec3& viewDirection);
// Eqs. 8–10: the face normal F_a of the quad between nodes i and i+1, the normalised mean of
// its ends' û crossed with its segment direction n̂_i; it faces the viewer.
glm::vec3 billboardFaceNormal(const glm::vec3& u0, const glm::vec3& u1, const glm::vec3& n);
// Eq. 11 at a point of the quad: `across` in [−1, 1] from the lower to the upper edge. The
// vertex normals ±û (N_u = û, N_l = −û: pointing away from the axis) are interpolated
// linearly to N, then N_f = (N + F_a)/|N + F_a|.
glm::vec3 tubeNormal(const glm::vec3& u0, const glm::vec3& u1, float along, float across,
                     const glm::vec3& faceNormal);

// §6.1–6.2: what the proxy geometry's two passes do with a fragment.
enum class ProxyAction { Discard, CutSurface, MarkInside };
// Eqs. 12–14 on the end triangles: d = |(u, v) − (0.5, 0.5)|, the outer wall at d_out = 0.5
// and the inner at d_in = 0.5·r_in/r_out (the paper's d_in = r_in/r_out would put the inner
// circle outside the outer one for thin walls: the texture scale is 0.5/r_out for both).
// Pass 1 (T1) draws the cut surface on the ring, pass 2 (T2) marks the inside.
float proxyTriangleDistance(glm::vec2 uv);
ProxyAction proxyTriangle(int pass, float d, float innerRadius, float outerRadius);
// Eqs. 15–16 on the quads along the cut: v in [0, 1] across the pipe's full diameter 2 r_out,
// so the wall takes t = (r_out − r_in)/(2 r_out) of it at each side (the paper's t divides by
// r_out, which would draw the walls twice as thick). Pass 1 (Q2) draws the cut surface on
// the walls, pass 2 (Q1) marks the inside between them.
ProxyAction proxyQuad(int pass, float v, float innerRadius, float outerRadius);

// The nodes of `pipe` between arc lengths range.x and range.y (from its first node), the ends
// interpolated; `arcs` receives each point's arc length. Fewer than two points: the range
// misses the pipe.
std::vector<glm::vec3> cutStretch(const Pipe& pipe, glm::vec2 range,
                                  std::vector<float>* arcs = nullptr);

// §7: a shaft fragment with outward radial normal n is removed when n·v, both with their
// height ignored and normalised, exceeds the opening coefficient; v points to the eye.
bool shaftWedgeRemoves(const glm::vec3& normal, const glm::vec3& toEye, float coefficient);

// Konev18 §9's weakness: billboards look flat through sharp bends. Splits every pipe at the
// nodes where the direction turns by more than `maxBendDegrees` and returns those nodes (with
// the pipe's radius) as joints, to be covered by meshed spheres. A cut stretch follows its
// pipe's pieces.
struct Joint {
  glm::vec3 position;
  float radius;
};
std::vector<Joint> splitSharpBends(PipeNetwork& network, float maxBendDegrees);

// Konev18 §9's other weakness: where two cut-open stretches meet (junctions, crossings), their
// stencil areas interfere. Keeps the cut of the more important pipe (larger radius, then the
// earlier one) and trims the other's stretch to end `margin` + both radii away from the
// meeting point; returns how many stretches were trimmed.
int resolveCutIntersections(PipeNetwork& network, float margin);

// Shafts at pipe ends and junctions (node positions shared by pipe ends or shared by several
// pipes, to `weldDistance`): the floor just under the lowest pipe there, the rim at the
// terrain height `groundAt(x, z)`.
struct ShaftDefaults {
  float radius = 0.6f, wallThickness = 0.1f, waterLevel = 0.0f;
  bool ends = true;  // also at pipe ends that meet no other pipe
  float weldDistance = 0.05f;
};
void addJunctionShafts(PipeNetwork& network, const ShaftDefaults& defaults,
                       const std::function<float(glm::vec2)>& groundAt);

// §7: pipes open into the shafts they reach. A pipe end within a shaft (inside its inner
// radius in plan, between its floor and rim) is moved back along the pipe to the inner wall,
// so that the opened shaft shows its inside and water instead of the pipes crossing it; the
// cut stretch keeps its place along the pipe. Returns how many ends moved. A pipe lying
// wholly inside a shaft is left as it is.
int trimAtShafts(PipeNetwork& network);

// Meshes of a network (scene units): tessellated pipes with mitred rings at the nodes (the
// comparison of Table 1), the shafts' outer and inner cylinders (open at the top, the outer
// with a floor; normals outward on both, as §7 shades them), and spheres for the joints.
Mesh pipeMesh(const PipeNetwork& network, int sides = 16);
Mesh shaftMesh(const PipeNetwork& network, bool inner, int sides = 32);
Mesh jointMesh(const std::vector<Joint>& joints, int rings = 8, int sides = 16);

}  // namespace cutaway
