// Diepstraten03 §4.2 main axis via Gottschalk, Lin, Manocha 1996 (OBBTree, §4: the
// covariance of the convex hull's surface, integrated over each triangle).
#include "cutaway/geometry/main_axis.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>

#include "cutaway/geometry/convex_hull.hpp"

namespace cutaway {

SurfaceMoments surfaceMoments(const Mesh& mesh) {
  SurfaceMoments m;
  glm::dmat3 second(0.0);  // Σ A_i/12 (9 m mᵀ + p pᵀ + q qᵀ + r rᵀ)
  glm::dvec3 first(0.0);   // Σ A_i m_i
  for (std::size_t i = 0, n = mesh.triangleCount(); i < n; ++i) {
    const glm::uvec3 t = mesh.triangle(i);
    const glm::dvec3 p(mesh.positions[t.x]), q(mesh.positions[t.y]), r(mesh.positions[t.z]);
    const double area = 0.5 * glm::length(glm::cross(q - p, r - p));
    const glm::dvec3 centroid = (p + q + r) / 3.0;
    m.area += area;
    first += area * centroid;
    // outerProduct(a, b)[col][row] = a[row] b[col]; symmetric here.
    second +=
        (area / 12.0) * (9.0 * glm::outerProduct(centroid, centroid) + glm::outerProduct(p, p) +
                         glm::outerProduct(q, q) + glm::outerProduct(r, r));
  }
  if (m.area <= 0.0) return m;
  m.mean = first / m.area;
  m.covariance = second / m.area - glm::outerProduct(m.mean, m.mean);
  return m;
}

PrincipalAxes principalAxes(const std::vector<glm::vec3>& points) {
  // Only the hull matters (Diepstraten03: "vertices of the convex hull"); uniform sampling of
  // its surface is the exact per-triangle integral of surfaceMoments.
  const Mesh hull = convexHull(points);
  const SurfaceMoments moments = surfaceMoments(hull);
  Eigen::Matrix3d c;
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) c(row, col) = moments.covariance[col][row];
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(c);
  // Eigen sorts ascending; the main axis is the largest.
  PrincipalAxes a;
  a.center = glm::vec3(moments.mean);
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d v = solver.eigenvectors().col(2 - i);
    a.axes[std::size_t(i)] = glm::normalize(glm::vec3(float(v.x()), float(v.y()), float(v.z())));
    a.eigenvalues[std::size_t(i)] = float(solver.eigenvalues()(2 - i));
  }
  // Eigenvectors have no sign: pick the one whose largest component is positive so results
  // are stable across platforms, then make the frame right-handed.
  for (auto& axis : a.axes) {
    const glm::vec3 mag = glm::abs(axis);
    const int k = mag.x >= mag.y && mag.x >= mag.z ? 0 : mag.y >= mag.z ? 1 : 2;
    if (axis[k] < 0.0f) axis = -axis;
  }
  a.axes[2] = glm::normalize(glm::cross(a.axes[0], a.axes[1]));
  a.extentMin = 1e30f, a.extentMax = -1e30f;
  for (const auto& p : hull.positions) {
    const float s = glm::dot(p - a.center, a.axes[0]);
    a.extentMin = std::min(a.extentMin, s);
    a.extentMax = std::max(a.extentMax, s);
  }
  return a;
}

}  // namespace cutaway
