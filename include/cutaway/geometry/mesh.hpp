// cutaway/geometry/mesh.hpp — indexed triangle meshes and the checks cutters rely on.
//
// Cut surfaces (Burns08 §4.1, Trapp13 §5, Diepstraten03) are only meaningful for watertight
// meshes, so every mesh carries a topology report: a mesh is watertight when, after welding
// vertices at equal positions, every edge is shared by exactly two triangles that traverse it
// in opposite directions (closed, manifold, consistently oriented).
//
//   cutaway::Mesh m = cutaway::makeBox({0,0,0}, {1,1,1});
//   cutaway::MeshReport r = cutaway::analyzeTopology(m);   // r.watertight == true
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

namespace cutaway {

// How far from the origin a scene's coordinates (its parts, the camera) may lie: beyond, 32-bit
// floats overflow the view's squared distances and the camera turns NaN (a blank image).
constexpr float kMaxSceneReach = 1e15f;
// The least a scene's part may measure across (and a volume's voxel): below, 32-bit floats
// underflow the squared lengths of its normals and gradients (shading lost near 1e-20).
constexpr double kMinSceneDetail = 1e-15;
// How far p lies from the origin along an axis: what kMaxSceneReach bounds.
inline float sceneReach(const glm::vec3& p) {
  return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
}

struct Bounds {
  glm::vec3 min{1e30f}, max{-1e30f};
  bool empty() const { return min.x > max.x; }
  void extend(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void extend(const Bounds& b) {
    if (!b.empty()) extend(b.min), extend(b.max);
  }
  glm::vec3 center() const { return (min + max) * 0.5f; }
  // In double: the squares of a box 1e-20 across underflow in float.
  float radius() const {
    return empty() ? 0.0f : float(glm::length(glm::dvec3(max) - glm::dvec3(min)) * 0.5);
  }
  Bounds transformed(const glm::mat4& m) const;
};

struct MeshReport {
  std::size_t droppedDegenerate = 0;  // zero-area triangles removed
  bool normalsComputed = false;       // true when the source had no normals
  std::size_t boundaryEdges = 0;      // edges used by one triangle
  std::size_t nonManifoldEdges = 0;   // edges used by three or more triangles
  std::size_t misorientedEdges = 0;   // edges used twice in the same direction
  bool watertight = false;
  bool windingReversed = false;  // closed and wound inward in the file: turned (orientOutward)
};

// A mesh whose nodes form a grid: `columns × rows` positions row by row, and two triangles
// per cell, cell by cell, every cell split and wound alike (terrains). Renderers then draw it
// with a level of detail (cutaway/geometry/grid_lod.hpp). The triangles may be stored, or
// left implied (`Mesh::triangles` empty): then each cell's two are `cell`'s, by its corners
// 0 = (c, r), 1 = (c + 1, r), 2 = (c, r + 1), 3 = (c + 1, r + 1), and a large terrain keeps
// no index per triangle (Mesh::triangleCount, Mesh::triangle read either way).
struct GridLayout {
  int columns = 0, rows = 0;
  std::array<std::array<int, 3>, 2> cell{{{0, 1, 2}, {1, 3, 2}}};
};

struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // one per position
  std::vector<glm::uvec3> triangles;  // empty for a grid whose layout implies them
  MeshReport report;
  std::optional<GridLayout> grid;  // checked where it is used: edits may have broken it

  // The triangles, stored or implied by the grid (none when the grid and the positions
  // disagree).
  bool impliedTriangles() const {
    return grid && triangles.empty() && grid->columns > 1 && grid->rows > 1 &&
           positions.size() == std::size_t(grid->columns) * std::size_t(grid->rows);
  }
  std::size_t triangleCount() const {
    return impliedTriangles() ? 2 * std::size_t(grid->columns - 1) * std::size_t(grid->rows - 1)
                              : triangles.size();
  }
  glm::uvec3 triangle(std::size_t i) const {
    if (!impliedTriangles()) return triangles[i];
    const std::size_t cell = i / 2, cells = std::size_t(grid->columns - 1);
    const std::size_t c = cell % cells, r = cell / cells, columns = std::size_t(grid->columns);
    const std::size_t corner[4] = {r * columns + c, r * columns + c + 1, (r + 1) * columns + c,
                                   (r + 1) * columns + c + 1};
    const std::array<int, 3>& t = grid->cell[i % 2];
    // A corner outside 0–3 reads as another (GridLod refuses such a layout).
    return {unsigned(corner[t[0] & 3]), unsigned(corner[t[1] & 3]), unsigned(corner[t[2] & 3])};
  }

  Bounds bounds() const;
  // Appends `other` transformed by `m` (normals by its inverse transpose), its triangles
  // stored; the result is no grid.
  void append(const Mesh& other, const glm::mat4& m);
};

// The next two work on stored triangles (meshes read from files), not on implied ones.
// Removes triangles of zero area in float arithmetic (repeated indices, coincident vertices,
// exactly collinear vertices, or non-finite positions); returns how many were removed.
// Thin but valid triangles stay: removing slivers would open holes in closed meshes.
std::size_t dropDegenerateTriangles(Mesh& mesh);
// Area-weighted vertex normals (a triangle contributes its unnormalised cross product) that
// stay sharp at creases: a corner averages only the faces around its position whose normals
// lie within `creaseAngle` degrees of its own face's, and vertices are split where corners
// of one position end with different normals. Positions and topology are unchanged.
void computeVertexNormals(Mesh& mesh, float creaseAngle = 40.0f);
// Edge topology after welding equal positions; fills the edge counts and `watertight`.
void analyzeTopology(Mesh& mesh);
// A watertight mesh (analyzeTopology first) wound inward, as CAD exports and marching cubes
// may give, has a negative signed volume: its triangles are turned, and its normals where
// they followed the winding, so that front faces are its outside (what the cutters' back-face
// cut surfaces, walls and parity caps read). Sets `windingReversed`; true when it turned.
bool orientOutward(Mesh& mesh);

// Ray parameters t > 0 at which origin + t·direction meets the mesh's triangles
// (Möller & Trumbore 1997), unsorted; the references that GPU tests compare against.
std::vector<float> rayHits(const Mesh& mesh, const glm::vec3& origin, const glm::vec3& direction);

// Axis-aligned box with outward-facing triangles and flat normals (24 vertices).
Mesh makeBox(const glm::vec3& min, const glm::vec3& max);

}  // namespace cutaway
