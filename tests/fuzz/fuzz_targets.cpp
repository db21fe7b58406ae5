#include "fuzz_targets.hpp"

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string_view>

#include <stdlib.h>

#include "cutaway/core/error.hpp"
#include "cutaway/core/image.hpp"
#include "cutaway/io/gis_import.hpp"
#include "cutaway/io/mesh_import.hpp"
#include "cutaway/io/raster_terrain.hpp"
#include "cutaway/io/volume_import.hpp"
#include "cutaway/scene/scene.hpp"

namespace cutaway::fuzz {

const std::vector<Target>& targets() {
  static const std::vector<Target> list = {
      {"scene", "", "tests/data/bad/*.json tests/data/render/*.json examples/*.json"},
      {"mesh-obj", ".obj", "tests/data/meshes/*.obj tests/data/render/*.obj"},
      {"mesh-ply", ".ply", "tests/data/fuzz/mesh-ply/*"},
      {"mesh-stl", ".stl", "tests/data/fuzz/mesh-stl/*"},
      {"mesh-glb", ".glb", "tests/data/fuzz/mesh-glb/*"},
      {"mesh-gz", ".obj.gz", "tests/data/fuzz/mesh-gz/*"},
      {"volume-nrrd", ".nrrd", "tests/data/fuzz/volume-nrrd/*"},
      {"volume-mha", ".mha", "tests/data/fuzz/volume-mha/*"},
      {"volume-vtk", ".vtk", "tests/data/fuzz/volume-vtk/*"},
      {"volume-nifti", ".nii", "tests/data/fuzz/volume-nifti/*"},
      {"volume-npy", ".npy", "tests/data/fuzz/volume-npy/*"},
      {"volume-npz", ".npz", "tests/data/fuzz/volume-npz/*"},
      {"raster", ".tif", "tests/data/fuzz/raster/*"},
      {"geojson", ".geojson", "tests/data/networks/*.geojson"},
      {"geopackage", ".gpkg", "tests/data/fuzz/geopackage/*"},
      {"shapefile", ".shp", "tests/data/fuzz/shapefile/*", {".shx", ".dbf", ".prj"}},
      {"volume-raw", ".json", "tests/data/fuzz/volume-raw/*", {".raw"}},
      // A DICOM series: a folder of slices (GDCM), here one or two.
      {"volume-dicom", "/1.dcm", "tests/data/fuzz/volume-dicom/*", {"/2.dcm"}},
      {"png", ".png", "tests/golden/bunny.png tests/data/fuzz/png/*"},
  };
  return list;
}

const Target* findTarget(const std::string& name) {
  for (const Target& t : targets())
    if (t.name == name) return &t;
  return nullptr;
}

namespace {

// A private folder per process, removed at exit: an input is written there as one file per
// target, rewritten each time, and files that inputs name beside it do not exist.
class ScratchFolder {
 public:
  ScratchFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "cutaway-fuzz-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("cannot create " + pattern);
    path_ = pattern;
  }
  ~ScratchFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

std::filesystem::path scratchFile(const std::string& extension) {
  static const ScratchFolder folder;
  return folder.path() / ("input" + extension);
}

void write(const std::filesystem::path& file, std::string_view bytes) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), std::streamsize(bytes.size()));
}

void load(const Target& target, const std::filesystem::path& file) {
  const std::string& n = target.name;
  if (n.starts_with("mesh-")) {
    importMeshNodes(file);
  } else if (n == "volume-dicom") {
    importVolume(file.parent_path());  // the series' folder
  } else if (n.starts_with("volume-")) {
    importVolume(file);
  } else if (n == "geojson" || n == "geopackage" || n == "shapefile") {
    importGisLines(file);
  } else if (n == "raster") {
    importRasterTerrain(file);
  } else if (n == "png") {
    readPng(file);
    readPngGray(file);
  }
}

}  // namespace

bool run(const Target& target, const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  // The readers run here rather than in a child process (cutaway/core/contained.hpp), where
  // neither the sanitizers nor the fuzzer would see a fault.
  const struct InProcess {
    InProcess() { ::setenv("CUTAWAY_IMPORT_CONTAINED", "0", 1); }
    ~InProcess() { ::unsetenv("CUTAWAY_IMPORT_CONTAINED"); }
  } inProcess;
  try {
    if (target.extension.empty()) {
      // Scene text: files it names are looked up beside the tests' data.
      parseScene(std::string(bytes), "fuzz.json", CUTAWAY_TEST_DATA);
      return true;
    }
    const std::filesystem::path file = scratchFile(target.extension);
    std::string_view rest = bytes;
    const auto part = [&rest] {
      const std::size_t end = rest.find(kPartSeparator);
      const std::string_view first = rest.substr(0, end);
      rest = end == std::string_view::npos ? std::string_view()
                                           : rest.substr(end + kPartSeparator.size());
      return first;
    };
    write(file, target.moreParts.empty() ? bytes : part());
    for (const std::string& extension : target.moreParts) {
      const bool present = !rest.empty();
      const std::string_view content = part();
      if (present)
        write(scratchFile(extension), content);
      else
        std::filesystem::remove(scratchFile(extension));
    }
    load(target, file);
    return true;
  } catch (const Error&) {
    return false;  // refused with a message: what bad input must get
  }
}

}  // namespace cutaway::fuzz
