// cutaway/geometry/grid_lod.hpp — chunked level of detail for meshes laid out on a grid of
// nodes (terrains from rasters, the benchmark city's ground).
//
// The grid is cut into square chunks of kChunkCells × kChunkCells cells. Level l of a chunk
// keeps every 2^l-th node along each axis (and the chunk's last), and its geometric error
// ε_l is the largest distance between a node of the full grid and the level's surface at the
// same grid coordinates. A view draws each chunk at the coarsest level whose error projects
// to at most τ pixels, ρ = ε K / d (Ulrich 2002, "Rendering massive terrains using chunked
// level of detail control": K = viewport height / (2 tan(fovY / 2)), d the distance from the
// eye to the chunk's box). Where neighbours differ, the finer chunk's border takes the coarser
// one's nodes, so the surface stays closed: no cracks, no T-junctions, no skirts.
//
//   Mesh terrain = ...;                      // terrain.grid = GridLayout{columns, rows}
//   std::optional<GridLod> lod = GridLod::build(terrain);
//   std::vector<std::uint8_t> levels = lod->select(view);
//   std::vector<glm::uvec3> drawn = lod->triangles(levels);   // indices into terrain's nodes
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "cutaway/geometry/mesh.hpp"

namespace cutaway {

class GridLod {
 public:
  static constexpr int kChunkCells = 64;
  static constexpr int kLevels = 7;  // strides 1, 2, …, 64: the coarsest chunk is one cell

  // The mesh's grid, checked: nothing when `mesh.grid` is absent or its stored triangles are
  // not two per cell, cell by cell, all split and wound alike, or its layout's `cell` does not
  // split a cell in two (then the mesh is drawn whole).
  static std::optional<GridLod> build(const Mesh& mesh);

  struct View {
    glm::mat4 model{1.0f};  // the mesh's object transform
    glm::mat4 viewProjection{1.0f};
    glm::mat4 projection{1.0f};   // perspective or orthographic
    glm::vec3 eye{0.0f};          // world space
    float viewportHeight = 1.0f;  // pixels
    float pixelError = 0.5f;      // τ; 0 keeps every triangle
  };
  // Pixels on screen per unit of the object's space at the nearest point of `local` (a box in
  // the object's space): K / d times the model's largest scale; 0 when the box lies wholly
  // outside the view frustum.
  static float pixelsPerUnit(const View& view, const Bounds& local);
  // A level per chunk (row by row): the coarsest whose projected error is at most τ. Chunks
  // wholly outside the view frustum take the coarsest level (they still cast shadows).
  std::vector<std::uint8_t> select(const View& view) const;
  // The triangles of the chunks at `levels`, in the mesh's winding and diagonal; a chunk's
  // side takes the coarser of its and its neighbour's level.
  std::vector<glm::uvec3> triangles(const std::vector<std::uint8_t>& levels) const;

  int chunkCount() const { return chunksX_ * chunksZ_; }
  // ε_l of a chunk, non-decreasing in l.
  float error(int chunk, int level) const {
    return errors_[std::size_t(chunk)][std::size_t(level)];
  }
  const Bounds& chunkBounds(int chunk) const { return bounds_[std::size_t(chunk)]; }

 private:
  GridLod() = default;
  struct Extent {
    int c0, c1, r0, r1;  // node columns and rows, both ends included
  };
  Extent extent(int chunk) const;
  std::uint32_t node(int c, int r) const {
    return std::uint32_t(r) * std::uint32_t(columns_) + std::uint32_t(c);
  }

  int columns_ = 0, rows_ = 0, chunksX_ = 0, chunksZ_ = 0;
  // The cell's two triangles as corners 0 = (c, r), 1 = (c+1, r), 2 = (c, r+1), 3 = (c+1, r+1).
  std::array<std::array<int, 3>, 2> pattern_{};
  bool mainDiagonal_ = false;  // the cell is split from corner 0 to 3 (else from 1 to 2)
  std::vector<std::array<float, kLevels>> errors_;
  std::vector<Bounds> bounds_;
};

}  // namespace cutaway
