#include "cutaway/frame/aov.hpp"

#include <epoxy/gl.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>

#include "cutaway/core/atomic_file.hpp"
#include "cutaway/core/error.hpp"

namespace cutaway {

namespace {
nlohmann::json matrixRows(const glm::mat4& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) rows.push_back({m[0][r], m[1][r], m[2][r], m[3][r]});
  return rows;
}
nlohmann::json vec(const glm::vec3& v) {
  return {v.x, v.y, v.z};
}

// The PFM files an earlier index in `dir` lists that `aovs` does not write (another scene's
// AOVs): removed once the new ones are in, so that the folder holds one frame's. Only plain
// names ending in .pfm count; an unreadable index lists none.
std::vector<std::filesystem::path> staleAovFiles(const std::filesystem::path& dir,
                                                 const std::vector<Aov>& aovs) {
  std::vector<std::filesystem::path> stale;
  for (const std::filesystem::path& file : indexedAovFiles(dir))
    if (std::none_of(aovs.begin(), aovs.end(),
                     [&](const Aov& a) { return a.name + ".pfm" == file.filename().string(); }))
      stale.push_back(file);
  return stale;
}
}  // namespace

std::vector<std::filesystem::path> indexedAovFiles(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  std::ifstream in(dir / "aovs.json");
  if (!in) return files;
  const nlohmann::json index = nlohmann::json::parse(in, nullptr, false);
  if (!index.is_object() || !index.contains("aovs") || !index["aovs"].is_array()) return files;
  for (const nlohmann::json& entry : index["aovs"]) {
    if (!entry.is_object() || !entry.contains("file") || !entry["file"].is_string()) continue;
    const std::filesystem::path file = entry["file"].get<std::string>();
    if (file == file.filename() && file.extension() == ".pfm") files.push_back(dir / file);
  }
  return files;
}

std::vector<Aov> readFrameAovs(const Frame& frame) {
  std::vector<Aov> aovs;
  // Image stores (clip mask, cap parity) must land before the read-back.
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  for (const auto& name : frame.aovNames()) {
    const TargetDesc& d = frame.desc(name);
    const int channels = d.aovChannels ? d.aovChannels : 1;
    FloatImage image(d.width, d.height, channels);
    image.data = frame.read(name, channels);
    image.flipVertically();
    aovs.push_back({name, d.meaning, std::move(image)});
  }
  return aovs;
}

void writeAovs(const std::filesystem::path& given, const std::vector<Aov>& aovs,
               const Camera& camera, float aspect,
               std::vector<std::pair<std::filesystem::path, FileWriter>> alongside) {
  // "a/./b/" as "a/b": the folders made below are taken apart again by their parents.
  std::filesystem::path dir = given.lexically_normal();
  if (!dir.has_filename()) dir = dir.parent_path();
  std::error_code ec;
  if (std::filesystem::is_symlink(dir, ec) && !std::filesystem::exists(dir, ec))
    throw Error(dir.string(), "",
                "cannot create AOV directory: it is a symbolic link to " +
                    std::filesystem::read_symlink(dir, ec).string() + ", which does not exist");
  // Removed again (with any folder above it made here) if the writing fails or a signal stops
  // it: no empty folder left behind.
  MadeFolders folders = [&] {
    try {
      return MadeFolders(dir);
    } catch (const Error& e) {
      throw Error(dir.string(), "", "cannot create AOV directory: " + e.reason());
    }
  }();
  nlohmann::json index;
  index["camera"] = {
      {"projection", camera.projection == Projection::Perspective ? "perspective" : "orthographic"},
      {"eye", vec(camera.eye)},
      {"target", vec(camera.target)},
      {"up", vec(camera.up)},
      {"fov", camera.fovY},
      {"height", camera.height},
      {"near", camera.near},
      {"far", camera.far},
      {"view", matrixRows(camera.view())},
      {"projectionMatrix", matrixRows(camera.projectionMatrix(aspect))}};
  index["rowOrder"] = "PFM files store rows bottom to top, as the format requires";
  nlohmann::json list = nlohmann::json::array();
  std::vector<std::pair<std::filesystem::path, FileWriter>> files = std::move(alongside);
  for (const auto& aov : aovs) {
    const std::string file = aov.name + ".pfm";
    files.emplace_back(
        dir / file, [&aov, path = dir / file](std::ostream& os) { writePfm(os, aov.image, path); });
    nlohmann::json entry = {{"name", aov.name},
                            {"file", file},
                            {"width", aov.image.width},
                            {"height", aov.image.height},
                            {"channels", aov.image.channels},
                            {"meaning", aov.meaning}};
    if (!aov.values.empty()) entry["values"] = aov.values;
    list.push_back(std::move(entry));
  }
  index["aovs"] = list;
  files.emplace_back(dir / "aovs.json", [&](std::ostream& os) { os << index.dump(2) << "\n"; });
  // All or nothing (a full disk must not leave new images beside an old index), and no empty
  // folder left behind.
  const std::vector<std::filesystem::path> stale = staleAovFiles(dir, aovs);
  writeFilesAtomically(files);
  folders.keep();
  for (const std::filesystem::path& file : stale) std::filesystem::remove(file, ec);
}

}  // namespace cutaway
