#include "cutaway/geometry/ground_height.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "cutaway/core/error.hpp"

namespace cutaway {

GroundHeight::GroundHeight(const std::vector<const Mesh*>& meshes,
                           const std::vector<glm::mat4>& transforms)
    : meshes_(meshes) {
  Bounds box;
  std::size_t triangles = 0;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    pointStart_.push_back(points_.size());
    for (const glm::vec3& p : meshes[m]->positions)
      points_.push_back(glm::vec3(transforms[m] * glm::vec4(p, 1.0f)));
    triangles += meshes[m]->triangleCount();
    if (triangles >= std::size_t(UINT32_MAX))
      throw Error("", "", "a terrain of more than 4294967294 triangles");
    triangleStart_.push_back(std::uint32_t(triangles));
  }
  if (triangles == 0) return;
  // The box of the triangles' corners: a node no triangle keeps may lie anywhere, or be
  // infinite (dropDegenerateTriangles), and would thin out the cells.
  for (std::uint32_t t = 0; t < triangleStart_.back(); ++t)
    for (int c = 0; c < 3; ++c) box.extend(corner(t, c));
  // About one triangle per cell.
  cells_ = std::clamp(int(std::sqrt(double(triangles))), 1, 4096);
  min_ = {box.min.x, box.min.z};
  cellSize_ = glm::max(glm::vec2(box.max.x - box.min.x, box.max.z - box.min.z) / float(cells_),
                       glm::vec2(1e-6f));
  const auto cell = [&](float v, float lo, float size) {
    return std::clamp(int(std::floor((v - lo) / size)), 0, cells_ - 1);
  };
  // The cells under each triangle's footprint, counted, then filled: one list for all cells.
  const auto forEachCell = [&](const auto& f) {
    for (std::uint32_t t = 0; t < triangleStart_.back(); ++t) {
      const glm::vec3 p[3] = {corner(t, 0), corner(t, 1), corner(t, 2)};
      const float x0 = std::min({p[0].x, p[1].x, p[2].x}), x1 = std::max({p[0].x, p[1].x, p[2].x});
      const float z0 = std::min({p[0].z, p[1].z, p[2].z}), z1 = std::max({p[0].z, p[1].z, p[2].z});
      for (int j = cell(z0, min_.y, cellSize_.y); j <= cell(z1, min_.y, cellSize_.y); ++j)
        for (int i = cell(x0, min_.x, cellSize_.x); i <= cell(x1, min_.x, cellSize_.x); ++i)
          f(std::size_t(j) * std::size_t(cells_) + std::size_t(i), t);
    }
  };
  std::vector<std::size_t> start(std::size_t(cells_) * std::size_t(cells_) + 1, 0);
  forEachCell([&](std::size_t c, std::uint32_t) { ++start[c + 1]; });
  std::partial_sum(start.begin(), start.end(), start.begin());
  if (start.back() >= std::size_t(UINT32_MAX))
    throw Error("", "", "a terrain whose triangles span more than 4294967294 grid cells");
  cellStart_.assign(start.begin(), start.end());
  cellTriangles_.resize(start.back());
  forEachCell([&](std::size_t c, std::uint32_t t) { cellTriangles_[start[c]++] = t; });
}

glm::vec3 GroundHeight::corner(std::uint32_t t, int c) const {
  const std::size_t m =
      std::size_t(std::upper_bound(triangleStart_.begin(), triangleStart_.end(), t) -
                  triangleStart_.begin()) -
      1;
  return points_[pointStart_[m] + meshes_[m]->triangle(t - triangleStart_[m])[c]];
}

std::optional<float> GroundHeight::at(glm::vec2 xz) const {
  if (empty()) return std::nullopt;
  const glm::vec2 g = (xz - min_) / cellSize_;
  if (g.x < 0 || g.y < 0 || g.x > float(cells_) || g.y > float(cells_)) return std::nullopt;
  const int i = std::min(int(g.x), cells_ - 1), j = std::min(int(g.y), cells_ - 1);
  const std::size_t here = std::size_t(j) * std::size_t(cells_) + std::size_t(i);
  std::optional<float> best;
  for (std::uint32_t k = cellStart_[here]; k < cellStart_[here + 1]; ++k) {
    const std::uint32_t t = cellTriangles_[k];
    const glm::vec3 p[3] = {corner(t, 0), corner(t, 1), corner(t, 2)};
    // Barycentric coordinates in plan.
    const glm::vec2 a(p[0].x, p[0].z), b(p[1].x, p[1].z), c(p[2].x, p[2].z);
    const float det = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    if (std::abs(det) < 1e-12f) continue;
    const float l1 = ((xz.x - a.x) * (c.y - a.y) - (c.x - a.x) * (xz.y - a.y)) / det;
    const float l2 = ((b.x - a.x) * (xz.y - a.y) - (xz.x - a.x) * (b.y - a.y)) / det;
    const float l0 = 1.0f - l1 - l2, eps = -1e-5f;
    if (l0 < eps || l1 < eps || l2 < eps) continue;
    const float y = l0 * p[0].y + l1 * p[1].y + l2 * p[2].y;
    if (!best || y > *best) best = y;
  }
  return best;
}

}  // namespace cutaway
