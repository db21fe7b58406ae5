#include "kinds/volumes/volume_blocks.hpp"

#include <algorithm>
#include <limits>

namespace cutaway {

BlockRanges blockRanges(const Volume& v) {
  BlockRanges out;
  const glm::ivec3 grid = (v.dims + kVolumeBlock - 1) / kVolumeBlock;
  out.grid = grid;
  const auto block = [&](glm::ivec3 b) {
    return std::size_t(b.x) + std::size_t(grid.x) * (std::size_t(b.y) + std::size_t(grid.y) * b.z);
  };
  const std::size_t blocks = std::size_t(grid.x) * grid.y * grid.z;
  std::vector<float> lo(blocks, std::numeric_limits<float>::infinity()), hi(blocks, -lo[0]);
  std::size_t n = 0;
  for (int k = 0; k < v.dims.z; ++k)
    for (int j = 0; j < v.dims.y; ++j)
      for (int i = 0; i < v.dims.x; ++i, ++n) {
        const std::size_t b = block(glm::ivec3(i, j, k) / kVolumeBlock);
        lo[b] = std::min(lo[b], v.values[n]), hi[b] = std::max(hi[b], v.values[n]);
      }
  out.range.resize(blocks);
  for (int z = 0; z < grid.z; ++z)
    for (int y = 0; y < grid.y; ++y)
      for (int x = 0; x < grid.x; ++x) {
        float a = std::numeric_limits<float>::infinity(), b = -a;
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const glm::ivec3 q(x + dx, y + dy, z + dz);
              if (glm::any(glm::lessThan(q, glm::ivec3(0))) ||
                  glm::any(glm::greaterThanEqual(q, grid)))
                continue;
              a = std::min(a, lo[block(q)]), b = std::max(b, hi[block(q)]);
            }
        out.range[block({x, y, z})] = {a, b};
      }
  return out;
}

}  // namespace cutaway
