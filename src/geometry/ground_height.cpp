#include "cutaway/geometry/ground_height.hpp"

#include <algorithm>
#include <cmath>

namespace cutaway {

GroundHeight::GroundHeight(const std::vector<const Mesh*>& meshes,
                           const std::vector<glm::mat4>& transforms) {
  Bounds box;
  for (std::size_t m = 0; m < meshes.size(); ++m)
    for (const glm::uvec3& t : meshes[m]->triangles)
      for (int c = 0; c < 3; ++c) {
        const glm::vec3 p = glm::vec3(transforms[m] * glm::vec4(meshes[m]->positions[t[c]], 1.0f));
        triangles_.push_back(p);
        box.extend(p);
      }
  if (triangles_.empty()) return;
  // About one triangle per cell.
  const std::size_t count = triangles_.size() / 3;
  cells_ = std::clamp(int(std::sqrt(double(count))), 1, 4096);
  min_ = {box.min.x, box.min.z};
  cellSize_ = glm::max(glm::vec2(box.max.x - box.min.x, box.max.z - box.min.z) / float(cells_),
                       glm::vec2(1e-6f));
  grid_.resize(std::size_t(cells_) * std::size_t(cells_));
  const auto cell = [&](float v, float lo, float size) {
    return std::clamp(int(std::floor((v - lo) / size)), 0, cells_ - 1);
  };
  for (unsigned t = 0; t < count; ++t) {
    const glm::vec3 *p = &triangles_[3 * std::size_t(t)];
    const float x0 = std::min({p[0].x, p[1].x, p[2].x}), x1 = std::max({p[0].x, p[1].x, p[2].x});
    const float z0 = std::min({p[0].z, p[1].z, p[2].z}), z1 = std::max({p[0].z, p[1].z, p[2].z});
    for (int j = cell(z0, min_.y, cellSize_.y); j <= cell(z1, min_.y, cellSize_.y); ++j)
      for (int i = cell(x0, min_.x, cellSize_.x); i <= cell(x1, min_.x, cellSize_.x); ++i)
        grid_[std::size_t(j) * std::size_t(cells_) + std::size_t(i)].push_back(t);
  }
}

std::optional<float> GroundHeight::at(glm::vec2 xz) const {
  if (triangles_.empty()) return std::nullopt;
  const glm::vec2 g = (xz - min_) / cellSize_;
  if (g.x < 0 || g.y < 0 || g.x > float(cells_) || g.y > float(cells_)) return std::nullopt;
  const int i = std::min(int(g.x), cells_ - 1), j = std::min(int(g.y), cells_ - 1);
  std::optional<float> best;
  for (unsigned t : grid_[std::size_t(j) * std::size_t(cells_) + std::size_t(i)]) {
    const glm::vec3 *p = &triangles_[3 * std::size_t(t)];
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
