// cutaway/render/aov.hpp — writes a frame's intermediate buffers for inspection.
//
// Every AOV becomes DIR/<name>.pfm, and DIR/aovs.json lists, per AOV, its file, size,
// channels and meaning (units and depth conventions), plus the camera matrices so that
// values can be checked from outside.
//
//   cutaway::writeAovs("out/aovs", renderer.readAovs(), camera, aspect);
#pragma once

#include <filesystem>
#include <vector>

#include "cutaway/render/renderer.hpp"

namespace cutaway {

void writeAovs(const std::filesystem::path& dir, const std::vector<Aov>& aovs, const Camera& camera,
               float aspect);

}  // namespace cutaway
