// libFuzzer's entry for the fuzz targets (fuzz_targets.hpp), the target named by the
// environment variable CUTAWAY_FUZZ_TARGET (scripts/fuzz sets it). A target's dictionary is
// tests/fuzz/<target>.dict when there is one (JSON for the scene and GeoJSON, glTF for GLB).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "fuzz_targets.hpp"

namespace {

const cutaway::fuzz::Target& target() {
  static const cutaway::fuzz::Target* t = [] {
    const char* name = std::getenv("CUTAWAY_FUZZ_TARGET");
    const cutaway::fuzz::Target* found = name ? cutaway::fuzz::findTarget(name) : nullptr;
    if (!found) {
      std::fprintf(stderr, "cutaway-fuzz: set CUTAWAY_FUZZ_TARGET to one of:");
      for (const auto& t : cutaway::fuzz::targets()) std::fprintf(stderr, " %s", t.name.c_str());
      std::fprintf(stderr, "\n");
      std::exit(2);
    }
    return found;
  }();
  return *t;
}

}  // namespace

// CUTAWAY_FUZZ_TARGET=list: the targets and their seeds, one per line (for scripts/fuzz).
// Otherwise the target's dictionary joins the arguments, which libFuzzer parses after this.
extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  const char* name = std::getenv("CUTAWAY_FUZZ_TARGET");
  if (name && std::string(name) == "list") {
    for (const auto& t : cutaway::fuzz::targets())
      std::printf("%s\t%s\n", t.name.c_str(), t.seeds.c_str());
    std::exit(0);
  }
  const std::string dictionary = CUTAWAY_FUZZ_DIR "/" + target().name + ".dict";
  bool given = false;
  for (int i = 1; i < *argc; ++i) given = given || std::string((*argv)[i]).starts_with("-dict=");
  if (!given && std::filesystem::exists(dictionary)) {
    static std::vector<char*> arguments(*argv, *argv + *argc);
    static std::string flag = "-dict=" + dictionary;
    arguments.push_back(flag.data());
    arguments.push_back(nullptr);
    *argc += 1;
    *argv = arguments.data();
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  cutaway::fuzz::run(target(), data, size);
  return 0;
}
