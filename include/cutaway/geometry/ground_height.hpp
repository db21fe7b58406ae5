// cutaway/geometry/ground_height.hpp — the height of terrain meshes under a point in plan
// (x, z), y up: a uniform grid over the triangles' footprints, so that a city's thousands of
// pipe nodes and shafts query a multi-million-triangle terrain quickly.
//
//   cutaway::GroundHeight ground({&terrainMesh}, {glm::mat4(1.0f)});
//   std::optional<float> y = ground.at({120.0f, -40.0f});   // nullopt: off the terrain
#pragma once

#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "cutaway/geometry/mesh.hpp"

namespace cutaway {

class GroundHeight {
 public:
  // The meshes with their object-to-world transforms.
  GroundHeight(const std::vector<const Mesh*>& meshes, const std::vector<glm::mat4>& transforms);
  // The highest surface above or below (x, z); nullopt where no triangle covers it.
  std::optional<float> at(glm::vec2 xz) const;
  bool empty() const { return triangles_.empty(); }

 private:
  std::vector<glm::vec3> triangles_;  // world corners, three per triangle
  glm::vec2 min_{0.0f}, cellSize_{1.0f};
  int cells_ = 1;
  std::vector<std::vector<unsigned>> grid_;  // triangle indices per cell, rows of z
};

}  // namespace cutaway
