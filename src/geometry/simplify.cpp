#include "cutaway/geometry/simplify.hpp"

#include <algorithm>
#include <cmath>

#include <meshoptimizer.h>

namespace cutaway {
namespace {

// Distance from p to triangle abc: to its plane where p projects inside it, else to the
// nearest of its edges.
float distanceToTriangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b,
                         const glm::vec3& c) {
  const glm::vec3 n = glm::cross(b - a, c - a);
  const float area2 = glm::dot(n, n);
  if (area2 > 0.0f) {
    const glm::vec3 q = p - n * (glm::dot(p - a, n) / area2);
    if (glm::dot(glm::cross(b - a, q - a), n) >= 0.0f &&
        glm::dot(glm::cross(c - b, q - b), n) >= 0.0f &&
        glm::dot(glm::cross(a - c, q - c), n) >= 0.0f)
      return glm::length(p - q);
  }
  const auto toSegment = [&p](const glm::vec3& u, const glm::vec3& v) {
    const glm::vec3 d = v - u;
    const float len2 = glm::dot(d, d);
    const float t = len2 > 0.0f ? std::clamp(glm::dot(p - u, d) / len2, 0.0f, 1.0f) : 0.0f;
    return glm::length(p - (u + t * d));
  };
  return std::min({toSegment(a, b), toSegment(b, c), toSegment(c, a)});
}

// Triangles binned in a uniform grid of cells over a box, for the distance from a point of
// the box to the nearest of them: cells are searched in growing shells around the point's
// until the shell lies farther than the nearest triangle found.
class TriangleGrid {
 public:
  TriangleGrid(const std::vector<glm::vec3>& positions, const std::vector<unsigned>& indices,
               const Bounds& box)
      : positions_(positions), indices_(indices), origin_(box.min) {
    const glm::vec3 size = glm::max(box.max - box.min, glm::vec3(0.0f));
    const std::size_t triangles = indices.size() / 3;
    // About four cells per triangle (measured on CAD parts of long thin triangles: fewer
    // triangles a cell beat fewer cells a triangle), over the box's longest side if it is flat.
    const float longest = std::max({size.x, size.y, size.z});
    float volume = 1.0f;
    int axes = 0;
    for (int k = 0; k < 3; ++k)
      if (size[k] > 1e-6f * longest) volume *= size[k], ++axes;
    cell_ = axes == 0 ? 1.0f
                      : std::max(std::pow(volume / float(4 * std::max<std::size_t>(triangles, 1)),
                                          1.0f / float(axes)),
                                 longest / 256.0f);
    for (int k = 0; k < 3; ++k) cells_[k] = std::max(1, int(std::ceil(size[k] / cell_)));
    start_.assign(std::size_t(cells_.x) * cells_.y * cells_.z + 1, 0);
    // Counted, then filled: each triangle in every cell of its box that its plane passes
    // through (a large slanted triangle fills a slab of cells, not its whole box).
    const float halfDiagonal = 0.5f * std::sqrt(3.0f) * cell_ * 1.01f;  // and rounding
    for (int pass = 0; pass < 2; ++pass) {
      for (std::size_t t = 0; t < triangles; ++t) {
        glm::ivec3 lo, hi;
        cellRange(t, lo, hi);
        const glm::vec3& a = positions_[indices_[3 * t]];
        const glm::vec3 n =
            glm::cross(positions_[indices_[3 * t + 1]] - a, positions_[indices_[3 * t + 2]] - a);
        const float reach = halfDiagonal * glm::length(n);
        for (int z = lo.z; z <= hi.z; ++z)
          for (int y = lo.y; y <= hi.y; ++y)
            for (int x = lo.x; x <= hi.x; ++x) {
              const glm::vec3 centre = origin_ + (glm::vec3(x, y, z) + 0.5f) * cell_;
              if (std::abs(glm::dot(n, centre - a)) > reach) continue;
              const std::size_t c = index({x, y, z});
              if (pass == 0)
                ++start_[c + 1];
              else
                items_[start_[c] + fill_[c]++] = unsigned(t);
            }
      }
      if (pass == 0) {
        for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
        items_.resize(start_.back());
        fill_.assign(start_.size() - 1, 0);
      }
    }
  }

  // The distance, or any distance up to `enough` once one is found within it (what a largest
  // distance so far needs to know).
  float distance(const glm::vec3& p, float enough = 0.0f) const {
    const glm::ivec3 at = cellOf(p);
    float nearest = INFINITY;
    for (int r = 0;; ++r) {
      const glm::ivec3 lo = at - r, hi = at + r;
      // Shell r: the cells of the block (2r + 1)³ around p's cell that are not in shell r − 1.
      for (int z = std::max(lo.z, 0); z <= std::min(hi.z, cells_.z - 1); ++z)
        for (int y = std::max(lo.y, 0); y <= std::min(hi.y, cells_.y - 1); ++y) {
          const bool face = z == lo.z || z == hi.z || y == lo.y || y == hi.y;
          for (int x = std::max(lo.x, 0); x <= std::min(hi.x, cells_.x - 1);
               x += face || x == hi.x ? 1 : hi.x - x) {
            nearest = std::min(nearest, nearestIn(index({x, y, z}), p));
            if (nearest <= enough) return nearest;
          }
        }
      // Cells outside the block lie at least as far as the nearest of its faces with cells
      // beyond it; none: every cell has been searched.
      float beyond = INFINITY;
      for (int k = 0; k < 3; ++k) {
        if (lo[k] > 0) beyond = std::min(beyond, p[k] - (origin_[k] + float(lo[k]) * cell_));
        if (hi[k] < cells_[k] - 1)
          beyond = std::min(beyond, origin_[k] + float(hi[k] + 1) * cell_ - p[k]);
      }
      if (nearest <= std::max(beyond, enough)) return nearest;
    }
  }

 private:
  float nearestIn(std::size_t c, const glm::vec3& p) const {
    float nearest = INFINITY;
    for (std::size_t i = start_[c]; i < start_[c + 1]; ++i) {
      const unsigned* t = &indices_[3 * std::size_t(items_[i])];
      nearest = std::min(
          nearest, distanceToTriangle(p, positions_[t[0]], positions_[t[1]], positions_[t[2]]));
    }
    return nearest;
  }
  glm::ivec3 cellOf(const glm::vec3& p) const {
    return glm::clamp(glm::ivec3(glm::floor((p - origin_) / cell_)), glm::ivec3(0), cells_ - 1);
  }
  std::size_t index(const glm::ivec3& c) const {
    return (std::size_t(c.z) * std::size_t(cells_.y) + std::size_t(c.y)) * std::size_t(cells_.x) +
           std::size_t(c.x);
  }
  void cellRange(std::size_t t, glm::ivec3& lo, glm::ivec3& hi) const {
    const glm::vec3 &a = positions_[indices_[3 * t]], &b = positions_[indices_[3 * t + 1]],
                    &c = positions_[indices_[3 * t + 2]];
    lo = cellOf(glm::min(a, glm::min(b, c)));
    hi = cellOf(glm::max(a, glm::max(b, c)));
  }

  const std::vector<glm::vec3>& positions_;
  const std::vector<unsigned>& indices_;
  glm::vec3 origin_;
  float cell_ = 1.0f;
  glm::ivec3 cells_{1};
  std::vector<std::size_t> start_;
  std::vector<unsigned> fill_, items_;
};

// The one-sided distances both ways, at the vertices of the mesh and at the corners, edge
// midpoints and centroid of each of the version's triangles (whose corners are the mesh's
// vertices, so the version's surface lies in the mesh's box).
float deviation(const std::vector<glm::vec3>& positions, const TriangleGrid& mesh,
                const std::vector<unsigned>& version, const Bounds& box) {
  const TriangleGrid grid(positions, version, box);
  std::vector<bool> used(positions.size(), false);
  for (unsigned v : version) used[v] = true;
  float worst = 0.0f;
  for (std::size_t v = 0; v < positions.size(); ++v)
    if (!used[v]) worst = std::max(worst, grid.distance(positions[v], worst));
  for (std::size_t i = 0; i < version.size(); i += 3) {
    const glm::vec3 &a = positions[version[i]], &b = positions[version[i + 1]],
                    &c = positions[version[i + 2]];
    for (const glm::vec3& p : {(a + b) * 0.5f, (b + c) * 0.5f, (c + a) * 0.5f, (a + b + c) / 3.0f})
      worst = std::max(worst, mesh.distance(p, worst));
  }
  return worst;
}

// The triangles `indices` (into mesh's vertices) as a mesh of the vertices they use.
Mesh compacted(const Mesh& mesh, const std::vector<unsigned>& indices) {
  Mesh out;
  std::vector<unsigned> slot(mesh.positions.size(), ~0u);
  for (unsigned v : indices)
    if (slot[v] == ~0u) {
      slot[v] = unsigned(out.positions.size());
      out.positions.push_back(mesh.positions[v]);
      out.normals.push_back(mesh.normals[v]);
    }
  out.triangles.reserve(indices.size() / 3);
  for (std::size_t i = 0; i < indices.size(); i += 3)
    out.triangles.push_back({slot[indices[i]], slot[indices[i + 1]], slot[indices[i + 2]]});
  analyzeTopology(out);
  return out;
}

}  // namespace

std::vector<SimplifiedMesh> simplifiedVersions(const Mesh& mesh, std::size_t minTriangles) {
  std::vector<SimplifiedMesh> versions;
  if (mesh.grid || mesh.triangles.size() < 2 * minTriangles ||
      mesh.normals.size() != mesh.positions.size())
    return versions;
  std::vector<unsigned> indices;
  indices.reserve(mesh.triangles.size() * 3);
  for (const glm::uvec3& t : mesh.triangles) indices.insert(indices.end(), {t.x, t.y, t.z});
  const std::vector<unsigned> all = indices;
  const Bounds box = mesh.bounds();
  const TriangleGrid whole(mesh.positions, all, box);
  std::vector<unsigned> coarser(indices.size());
  while (indices.size() / 3 >= 2 * minTriangles) {
    // Any error: the triangle count bounds a step; its error is measured after.
    const std::size_t kept =
        meshopt_simplify(coarser.data(), indices.data(), indices.size(), &mesh.positions[0].x,
                         mesh.positions.size(), sizeof(glm::vec3), indices.size() / 2, 1.0f);
    if (kept == 0 || 4 * kept > 3 * indices.size()) break;
    indices.assign(coarser.begin(), coarser.begin() + std::ptrdiff_t(kept));
    Mesh version = compacted(mesh, indices);
    // A closed mesh's cut surfaces and caps need it closed (a step may pinch it).
    if (version.report.watertight != mesh.report.watertight) break;
    versions.push_back({deviation(mesh.positions, whole, indices, box), std::move(version)});
  }
  return versions;
}

}  // namespace cutaway
