// cutaway/frame/aov.hpp — a frame's intermediate buffers (AOVs), and writing them for
// inspection.
//
// Every AOV becomes DIR/<name>.pfm, and DIR/aovs.json lists, per AOV, its file, size,
// channels, meaning (units and depth conventions) and the frame's numbers it depends on, plus
// the camera matrices, so that values can be checked from outside.
//
//   cutaway::writeAovs("out/aovs", renderer.readAovs(), camera, aspect);
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "cutaway/core/atomic_file.hpp"
#include "cutaway/core/image.hpp"
#include "cutaway/frame/frame.hpp"
#include "cutaway/scene/camera.hpp"

namespace cutaway {

struct Aov {
  std::string name;     // file stem, e.g. "depth"
  std::string meaning;  // what a texel holds, with units and conventions
  FloatImage image;     // rows top to bottom
  // Numbers of the frame that recomputing the texels from outside needs (e.g. the cutaway
  // buffer's pixel size in view-plane units), by name; written as "values" in aovs.json.
  std::map<std::string, double> values = {};
};

// The frame's targets that have a meaning, in declaration order, rows top-down.
std::vector<Aov> readFrameAovs(const Frame& frame);

// The image files an AOV folder's index (DIR/aovs.json) lists: those a later writeAovs into it
// replaces or removes; any other file there stays. Empty without a readable index.
std::vector<std::filesystem::path> indexedAovFiles(const std::filesystem::path& dir);

// Written all or none (core/atomic_file.hpp), together with `alongside` (the frame's picture:
// a failure leaves no new picture beside old AOVs either); the files the folder's index listed
// that these AOVs do not hold are removed, other files stay.
void writeAovs(const std::filesystem::path& dir, const std::vector<Aov>& aovs, const Camera& camera,
               float aspect,
               std::vector<std::pair<std::filesystem::path, FileWriter>> alongside = {});

}  // namespace cutaway
