// cutaway/geometry/simplify.hpp — coarser versions of a triangle mesh, for views that can do
// with less detail (the viewer while its view moves, docs/viewer.md).
//
// Each version halves the triangles of the one before by edge collapses ordered by quadric
// error (Garland & Heckbert 1997, through meshoptimizer's simplifier): vertices are kept,
// never moved, so a version is a subset of the mesh's own vertices with their normals, and a
// border or a seam between vertices of one position (a crease's split normals) collapses only
// along itself, so an open mesh keeps its outline. A closed mesh's versions stay closed (a
// step that would open one ends the list: cut surfaces and caps need them closed).
//
//   std::vector<SimplifiedMesh> versions = simplifiedVersions(mesh);   // finest first
//   // draw versions[k].mesh where versions[k].error spans at most τ pixels
#pragma once

#include <cstddef>
#include <vector>

#include "cutaway/geometry/mesh.hpp"

namespace cutaway {

struct SimplifiedMesh {
  // How far the version's surface lies from the mesh's, in the mesh's units, measured both
  // ways: the largest distance from a vertex of the mesh to the version's triangles, and from
  // a corner, edge midpoint or centroid of the version's triangles to the mesh's.
  float error = 0.0f;
  Mesh mesh;
};

// Versions of about 1/2, 1/4, … of the mesh's triangles, finest first, down to about
// `minTriangles`; none for a grid (cutaway/geometry/grid_lod.hpp has its own levels) or a
// mesh of fewer than 2 × minTriangles. A step that cannot remove a quarter of the triangles
// (borders and seams everywhere), or that opens a closed mesh, ends the list.
std::vector<SimplifiedMesh> simplifiedVersions(const Mesh& mesh, std::size_t minTriangles = 64);

}  // namespace cutaway
