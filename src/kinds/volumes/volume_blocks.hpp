// The value range of each block of a volume's voxels, for skipping empty space: what any
// trilinear sample in a block can interpolate lies within its range (the block's voxels and
// those of the 26 blocks around it, a sample reaching at most one voxel beyond its block).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "cutaway/geometry/volume.hpp"

namespace cutaway {

constexpr int kVolumeBlock = 8;  // voxels per block edge (volume.frag's kBlock)

struct BlockRanges {
  glm::ivec3 grid{0};  // blocks per axis
  std::vector<glm::vec2>
      range;  // per block, i fastest: least and largest value (NaN voxels: lo > hi)
};
BlockRanges blockRanges(const Volume& volume);

}  // namespace cutaway
