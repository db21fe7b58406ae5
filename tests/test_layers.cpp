// The layers of docs/architecture.md hold: every C++ `#include "…"` of src/ and include/
// points down the list or within its own layer, plug-ins do not include each other, and the
// scene model includes no technique's implementation. (GLSL includes are not checked: the
// shared GLSL of the frame and of the shadow lookup is included across plug-ins by design.)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

namespace fs = std::filesystem;

namespace {

const fs::path kRoot = CUTAWAY_SOURCE_DIR;

struct Layer {
  int rank;
  std::string group;  // within a rank, groups that must not include each other ("" = any)
};

// `path` relative to the source tree: "src/…" or "include/cutaway/…".
Layer layerOf(const std::string& path) {
  const bool isPublic = path.rfind("include/cutaway/", 0) == 0;
  const std::string rel = path.substr(isPublic ? 16 : 4);
  const std::string top = rel.substr(0, rel.find('/'));
  const auto is = [&](std::initializer_list<const char*> names) {
    for (const char* n : names)
      if (rel == n) return true;
    return false;
  };
  if (top == "core") return {0, ""};
  if (top == "gl" || top == "geometry" || top == "fields") return {1, top};
  if (top == "io") return {2, ""};
  if (is({"scene/scene_json.cpp", "scene/scene_writer.cpp", "scene/scene_writer.hpp",
          "scene/network_json.cpp", "scene/network_json.hpp"}) ||
      top == "render")
    return {8, ""};
  if (top == "scene") return {3, ""};
  // A technique's public header: its options and pure functions, at the scene model's level.
  if (isPublic && (top == "cutters" || top == "styles" || top == "kinds")) return {3, ""};
  if (top == "frame") return {4, ""};
  if (is({"cutters/cutter.hpp", "kinds/kind.hpp", "kinds/member_options.hpp", "styles/style.hpp"}))
    return {5, ""};
  if (rel.rfind("cutters/registry", 0) == 0 || rel.rfind("styles/registry", 0) == 0)
    return {7, ""};
  if (top == "cutters" || top == "styles" || top == "kinds") {
    const std::size_t second = rel.find('/', top.size() + 1);
    return {6, rel.substr(0, second)};  // "cutters/adaptive"
  }
  ADD_FAILURE() << "no layer for " << path << " (add it to docs/architecture.md and here)";
  return {99, ""};
}

struct Include {
  std::string file, target;
  int line;
};

std::vector<Include> includes() {
  std::vector<Include> out;
  const std::regex include(R"(^\s*#include\s+"([^"]+)\")");
  for (const char* root : {"src", "include/cutaway"})
    for (const auto& e : fs::recursive_directory_iterator(kRoot / root)) {
      const std::string ext = e.path().extension().string();
      if (ext != ".cpp" && ext != ".hpp") continue;
      const std::string file = fs::relative(e.path(), kRoot).string();
      std::ifstream in(e.path());
      int n = 0;
      for (std::string line; std::getline(in, line);) {
        ++n;
        std::smatch m;
        if (!std::regex_search(line, m, include)) continue;
        const std::string name = m[1];
        const std::string target = name.rfind("cutaway/", 0) == 0 ? "include/" + name : "src/" + name;
        if (fs::exists(kRoot / target)) out.push_back({file, target, n});
      }
    }
  return out;
}

}  // namespace

TEST(Layers, EveryIncludePointsDownOrWithinItsLayer) {
  const auto all = includes();
  ASSERT_GT(all.size(), 200u);
  for (const Include& i : all) {
    const Layer from = layerOf(i.file), to = layerOf(i.target);
    EXPECT_LE(to.rank, from.rank) << i.file << ":" << i.line << " includes " << i.target
                                  << ", a layer above it";
    if (to.rank == from.rank && !from.group.empty())
      EXPECT_EQ(to.group, from.group) << i.file << ":" << i.line << " includes " << i.target
                                      << " of another " << (from.rank == 6 ? "plug-in" : "folder");
  }
}

TEST(Layers, TheCheckSeesAViolation) {
  EXPECT_GT(layerOf("src/cutters/registry.cpp").rank, layerOf("src/cutters/cutter.hpp").rank);
  EXPECT_GT(layerOf("src/cutters/box_cut/box_cut.cpp").rank, layerOf("src/frame/frame.cpp").rank);
  EXPECT_NE(layerOf("src/cutters/box_cut/box_cut.cpp").group,
            layerOf("src/cutters/adaptive/surface_passes.hpp").group);
  EXPECT_LT(layerOf("include/cutaway/scene/scene.hpp").rank,
            layerOf("src/cutters/adaptive/adaptive_cutaway.hpp").rank);
}
