#include "cutaway/geometry/grid_lod.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/worker_threads.hpp"

namespace cutaway {

namespace {

// The nodes a level keeps along one axis of a chunk [a0, a1] are a0, a0 + s, …, and a1; the
// last cell starts at the last of them before a1.
int lastCellStart(int a0, int a1, int stride) {
  return a0 + (a1 - a0 - 1) / stride * stride;
}

// Where a node of a chunk's side goes when the side is coarser than the chunk: to the side's
// nearest kept node, a tie broken towards `up` (the side's ends stay). Collapsing nodes along a
// straight border, in order, keeps every triangle that does not touch two sides oriented; at
// a corner the tie-breaks turn like a pinwheel, so that of the two nodes next to a corner one
// at least goes into it, and the corner cell's triangles that touch both sides collapse.
int keptNearest(int a, int a0, int a1, int stride, bool up) {
  const int below = a0 + (a - a0) / stride * stride, above = std::min(below + stride, a1);
  const int toBelow = a - below, toAbove = above - a;
  return toBelow < toAbove || (toBelow == toAbove && !up) ? below : above;
}

}  // namespace

std::optional<GridLod> GridLod::build(const Mesh& mesh) {
  if (!mesh.grid) return std::nullopt;
  const int columns = mesh.grid->columns, rows = mesh.grid->rows;
  if (columns < 2 || rows < 2 ||
      mesh.positions.size() != std::size_t(columns) * std::size_t(rows) ||
      mesh.triangleCount() != 2 * std::size_t(columns - 1) * std::size_t(rows - 1))
    return std::nullopt;
  GridLod lod;
  lod.columns_ = columns, lod.rows_ = rows;
  const auto corners = [&](int c, int r) {
    return std::array<std::uint32_t, 4>{lod.node(c, r), lod.node(c + 1, r), lod.node(c, r + 1),
                                        lod.node(c + 1, r + 1)};
  };
  // The pattern: the layout's for implied triangles, else the first cell's, then every cell
  // checked against it.
  const auto first = corners(0, 0);
  for (int t = 0; t < 2; ++t)
    for (int k = 0; k < 3; ++k) {
      if (mesh.impliedTriangles()) {
        const int corner = mesh.grid->cell[std::size_t(t)][std::size_t(k)];
        if (corner < 0 || corner > 3) return std::nullopt;
        lod.pattern_[std::size_t(t)][std::size_t(k)] = corner;
        continue;
      }
      const auto at = std::find(first.begin(), first.end(), mesh.triangles[std::size_t(t)][k]);
      if (at == first.end()) return std::nullopt;
      lod.pattern_[std::size_t(t)][std::size_t(k)] = int(at - first.begin());
    }
  // Two triangles over the cell's four corners share its diagonal: 0–3 or 1–2.
  int inBoth[4] = {0, 0, 0, 0}, inEither[4] = {0, 0, 0, 0};
  for (int corner = 0; corner < 4; ++corner)
    for (const auto& t : lod.pattern_) {
      const bool in = std::count(t.begin(), t.end(), corner) == 1;
      inBoth[corner] += in, inEither[corner] |= in;
    }
  if (std::count(inEither, inEither + 4, 1) != 4) return std::nullopt;
  lod.mainDiagonal_ = inBoth[0] == 2 && inBoth[3] == 2;
  if (!lod.mainDiagonal_ && !(inBoth[1] == 2 && inBoth[2] == 2)) return std::nullopt;
  std::size_t cell = 0;
  for (int r = 0; r + 1 < rows && !mesh.impliedTriangles(); ++r)
    for (int c = 0; c + 1 < columns; ++c, ++cell) {
      const auto n = corners(c, r);
      for (int t = 0; t < 2; ++t) {
        const glm::uvec3& tri = mesh.triangles[2 * cell + std::size_t(t)];
        for (int k = 0; k < 3; ++k)
          if (tri[k] != n[std::size_t(lod.pattern_[std::size_t(t)][std::size_t(k)])])
            return std::nullopt;
      }
    }

  lod.chunksX_ = (columns - 2) / kChunkCells + 1;
  lod.chunksZ_ = (rows - 2) / kChunkCells + 1;
  lod.errors_.resize(std::size_t(lod.chunkCount()));
  lod.bounds_.resize(std::size_t(lod.chunkCount()));
  // Each chunk's errors against the full grid, shared out to threads chunk by chunk.
  std::atomic<int> next{0};
  const auto work = [&] {
    for (int chunk; (chunk = next.fetch_add(1)) < lod.chunkCount();) {
      const Extent e = lod.extent(chunk);
      auto& errors = lod.errors_[std::size_t(chunk)];
      Bounds& b = lod.bounds_[std::size_t(chunk)];
      for (int r = e.r0; r <= e.r1; ++r)
        for (int c = e.c0; c <= e.c1; ++c) b.extend(mesh.positions[lod.node(c, r)]);
      errors[0] = 0.0f;
      for (int level = 1; level < kLevels; ++level) {
        const int s = 1 << level;
        float worst = errors[std::size_t(level - 1)];
        for (int r = e.r0; r <= e.r1; ++r) {
          const int z0 = std::min(e.r0 + (r - e.r0) / s * s, lastCellStart(e.r0, e.r1, s));
          const int z1 = std::min(z0 + s, e.r1);
          const float v = float(r - z0) / float(z1 - z0);
          for (int c = e.c0; c <= e.c1; ++c) {
            const int x0 = std::min(e.c0 + (c - e.c0) / s * s, lastCellStart(e.c0, e.c1, s));
            const int x1 = std::min(x0 + s, e.c1);
            const float u = float(c - x0) / float(x1 - x0);
            const glm::vec3& p00 = mesh.positions[lod.node(x0, z0)];
            const glm::vec3& p10 = mesh.positions[lod.node(x1, z0)];
            const glm::vec3& p01 = mesh.positions[lod.node(x0, z1)];
            const glm::vec3& p11 = mesh.positions[lod.node(x1, z1)];
            // The point of the level's triangle over (u, v), split as the mesh's cells are.
            glm::vec3 at;
            if (lod.mainDiagonal_)
              at = u >= v ? p00 + u * (p10 - p00) + v * (p11 - p10)
                          : p00 + v * (p01 - p00) + u * (p11 - p01);
            else
              at = u + v <= 1.0f ? p00 + u * (p10 - p00) + v * (p01 - p00)
                                 : p11 + (1.0f - u) * (p01 - p11) + (1.0f - v) * (p10 - p11);
            worst = std::max(worst, glm::length(at - mesh.positions[lod.node(c, r)]));
          }
        }
        errors[std::size_t(level)] = worst;
      }
    }
  };
  runOnThreads(hardwareThreads(8), work);
  return lod;
}

GridLod::Extent GridLod::extent(int chunk) const {
  const int i = chunk % chunksX_, j = chunk / chunksX_;
  return {i * kChunkCells, std::min((i + 1) * kChunkCells, columns_ - 1), j * kChunkCells,
          std::min((j + 1) * kChunkCells, rows_ - 1)};
}

float GridLod::pixelsPerUnit(const View& view, const Bounds& local) {
  // Outside when all eight corners lie beyond one plane of the clip volume.
  const glm::mat4 toClip = view.viewProjection * view.model;
  int outside[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < 8; ++i) {
    const glm::vec4 p =
        toClip * glm::vec4((i & 1) ? local.max.x : local.min.x, (i & 2) ? local.max.y : local.min.y,
                           (i & 4) ? local.max.z : local.min.z, 1.0f);
    outside[0] += p.x<-p.w, outside[1] += p.x> p.w, outside[2] += p.y < -p.w;
    outside[3] += p.y > p.w, outside[4] += p.z<-p.w, outside[5] += p.z> p.w;
  }
  if (std::find(std::begin(outside), std::end(outside), 8) != std::end(outside)) return 0.0f;
  // K of a unit at distance 1 (perspective) or anywhere (orthographic), times the model's
  // largest scale.
  const glm::mat3 m(view.model);
  const float scale = std::max({glm::length(m[0]), glm::length(m[1]), glm::length(m[2])});
  const float k = 0.5f * view.viewportHeight * std::abs(view.projection[1][1]) * scale;
  if (view.projection[2][3] == 0.0f) return k;
  const Bounds w = local.transformed(view.model);
  const float d = glm::length(glm::max(glm::max(w.min - view.eye, view.eye - w.max), 0.0f));
  return d > 0.0f ? k / d : INFINITY;
}

std::vector<std::uint8_t> GridLod::select(const View& view) const {
  std::vector<std::uint8_t> levels(std::size_t(chunkCount()), 0);
  for (int chunk = 0; chunk < chunkCount(); ++chunk) {
    const float pixels = pixelsPerUnit(view, bounds_[std::size_t(chunk)]);
    std::uint8_t& level = levels[std::size_t(chunk)];
    if (pixels == 0.0f) {
      level = kLevels - 1;
    } else if (view.pixelError > 0.0f) {
      while (level + 1 < kLevels &&
             errors_[std::size_t(chunk)][std::size_t(level + 1)] * pixels <= view.pixelError)
        ++level;
    }
  }
  return levels;
}

std::vector<glm::uvec3> GridLod::triangles(const std::vector<std::uint8_t>& levels) const {
  std::vector<glm::uvec3> out;
  const auto levelAt = [&](int i, int j, int own) {
    return i < 0 || j < 0 || i >= chunksX_ || j >= chunksZ_
               ? own
               : std::max(own, int(levels[std::size_t(j * chunksX_ + i)]));
  };
  for (int chunk = 0; chunk < chunkCount(); ++chunk) {
    const int i = chunk % chunksX_, j = chunk / chunksX_;
    const int own = levels[std::size_t(chunk)], s = 1 << own;
    const Extent e = extent(chunk);
    // Strides of the west, east, north (r0) and south (r1) sides.
    const int west = 1 << levelAt(i - 1, j, own), east = 1 << levelAt(i + 1, j, own);
    const int north = 1 << levelAt(i, j - 1, own), south = 1 << levelAt(i, j + 1, own);
    const auto kept = [&](int c, int r) {
      if (c == e.c0 && west > s) r = keptNearest(r, e.r0, e.r1, west, true);
      if (c == e.c1 && east > s) r = keptNearest(r, e.r0, e.r1, east, false);
      if (r == e.r0 && north > s) c = keptNearest(c, e.c0, e.c1, north, false);
      if (r == e.r1 && south > s) c = keptNearest(c, e.c0, e.c1, south, true);
      return node(c, r);
    };
    for (int z0 = e.r0; z0 < e.r1; z0 += s)
      for (int x0 = e.c0; x0 < e.c1; x0 += s) {
        const int x1 = std::min(x0 + s, e.c1), z1 = std::min(z0 + s, e.r1);
        const std::uint32_t n[4] = {kept(x0, z0), kept(x1, z0), kept(x0, z1), kept(x1, z1)};
        for (const auto& t : pattern_) {
          const glm::uvec3 tri(n[t[0]], n[t[1]], n[t[2]]);
          if (tri.x != tri.y && tri.y != tri.z && tri.x != tri.z) out.push_back(tri);
        }
      }
  }
  return out;
}

}  // namespace cutaway
