// cutaway/geometry/main_axis.hpp — the main axis of an object (Diepstraten03 §4.2): the axis of
// greatest spread, found as Gottschalk et al. (1996, "OBBTree") find an oriented bounding box.
//
// The covariance is taken over the *surface of the convex hull*, integrated exactly per
// triangle (a uniform, area-weighted sampling of the hull), so neither interior vertices nor
// unevenly sized triangles bias it; its eigenvectors, by decreasing eigenvalue, are the axes.
//
//   cutaway::PrincipalAxes a = cutaway::principalAxes(points);   // throws for flat point sets
//   glm::vec3 mainAxis = a.axes[0];                                // unit, largest spread
#pragma once

#include <array>
#include <vector>

#include "cutaway/geometry/mesh.hpp"

namespace cutaway {

struct PrincipalAxes {
  glm::vec3 center{0.0f};                    // area-weighted mean of the hull surface
  std::array<glm::vec3, 3> axes{};           // unit eigenvectors, right-handed
  std::array<float, 3> eigenvalues{};        // descending: axes[0] is the main axis
  float extentMin = 0.0f, extentMax = 0.0f;  // range of (p − center)·axes[0] over the points
};

// Covariance of a triangle mesh's surface, each triangle a uniform density (Gottschalk96):
//   C_jk = (1/A) Σ_i (A_i / 12) (9 m_ij m_ik + p_ij p_ik + q_ij q_ik + r_ij r_ik) − μ_j μ_k,
// m_i the centroid of triangle (p, q, r)_i, A_i its area, A = Σ A_i, μ = (1/A) Σ A_i m_i.
// Returns μ and C (column-major, symmetric).
struct SurfaceMoments {
  glm::dvec3 mean{0.0};
  glm::dmat3 covariance{0.0};
  double area = 0.0;
};
SurfaceMoments surfaceMoments(const Mesh& mesh);

// Main axes of a point set: the hull (Qhull), its surface moments, their eigen decomposition
// (Eigen). Throws cutaway::Error when the points span no volume.
PrincipalAxes principalAxes(const std::vector<glm::vec3>& points);

}  // namespace cutaway
