// cutaway/geometry/ground_height.hpp — the height of terrain meshes under a point in plan
// (x, z), y up: a uniform grid over the triangles' footprints, so that a city's thousands of
// pipe nodes and shafts query a multi-million-triangle terrain quickly.
//
//   cutaway::GroundHeight ground({&terrainMesh}, {glm::mat4(1.0f)});
//   std::optional<float> y = ground.at({120.0f, -40.0f});   // nullopt: off the terrain
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "cutaway/geometry/mesh.hpp"

namespace cutaway {

class GroundHeight {
 public:
  // The meshes with their object-to-world transforms; the meshes must outlive it (it keeps
  // their world positions, and reads their triangles in place).
  GroundHeight(const std::vector<const Mesh*>& meshes, const std::vector<glm::mat4>& transforms);
  // The highest surface above or below (x, z); nullopt where no triangle covers it.
  std::optional<float> at(glm::vec2 xz) const;
  bool empty() const { return triangleStart_.back() == 0; }

 private:
  // Corner c of triangle t, counted across the meshes, in world space.
  glm::vec3 corner(std::uint32_t t, int c) const;

  std::vector<const Mesh*> meshes_;
  std::vector<std::size_t> pointStart_;          // per mesh: its first world position
  std::vector<std::uint32_t> triangleStart_{0};  // per mesh and one past: its first triangle
  std::vector<glm::vec3> points_;                // the meshes' positions in world space
  glm::vec2 min_{0.0f}, cellSize_{1.0f};
  int cells_ = 1;
  // The triangles per cell (rows of z), cell i's from cellStart_[i] to cellStart_[i + 1].
  std::vector<std::uint32_t> cellStart_, cellTriangles_;
};

}  // namespace cutaway
