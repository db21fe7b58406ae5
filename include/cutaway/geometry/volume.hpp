// cutaway/geometry/volume.hpp — a scalar volume on a regular grid, placed in the world.
//
// Voxel (i, j, k) holds values[i + dims.x·(j + dims.y·k)]; its centre lies at
// indexToWorld·(i, j, k, 1), so a scanner's spacing and orientation (NIfTI's qform/sform, a
// DICOM series' patient orientation) put the volume in millimetres beside the scene's meshes.
// Values keep the file's units (Hounsfield units, raw intensities, labels), stored as float.
//
//   cutaway::Volume v = cutaway::importVolume("/usr/share/mricron/templates/ch2.nii.gz");
//   float centre = v.at(v.dims / 2);   // a T1 intensity
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cutaway/geometry/mesh.hpp"

namespace cutaway {

struct Volume {
  glm::ivec3 dims{0};
  std::vector<float> values;     // dims.x·dims.y·dims.z, i fastest
  glm::mat4 indexToWorld{1.0f};  // voxel index → world (mm for scanner data)
  std::string voxelType;         // as stored in the file: "u8", "i16", "u16", "f32", …
  float minValue = 0.0f, maxValue = 0.0f;

  std::size_t voxelCount() const { return std::size_t(dims.x) * dims.y * dims.z; }
  float at(glm::ivec3 v) const {
    return values[std::size_t(v.x) +
                  std::size_t(dims.x) * (std::size_t(v.y) + std::size_t(dims.y) * v.z)];
  }
  // The world lengths of one step along i, j and k.
  glm::vec3 spacing() const {
    return {glm::length(glm::vec3(indexToWorld[0])), glm::length(glm::vec3(indexToWorld[1])),
            glm::length(glm::vec3(indexToWorld[2]))};
  }
  // The box the voxels' cells fill, in index space: [−½, dims − ½] on each axis.
  Bounds indexBounds() const {
    Bounds b;
    b.extend(glm::vec3(-0.5f));
    b.extend(glm::vec3(dims) - 0.5f);
    return b;
  }
  Bounds bounds() const { return indexBounds().transformed(indexToWorld); }
  // Recomputes minValue and maxValue from the finite values; false when there is none.
  bool updateRange();
};

}  // namespace cutaway
