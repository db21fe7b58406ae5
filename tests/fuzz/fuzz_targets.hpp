// The loaders that read files users did not write themselves, as fuzz targets (issue 16): each
// takes arbitrary bytes as the content of one file (or of a file set) and must either load it or
// throw cutaway::Error; anything else (a crash, a sanitizer report, a hang, another exception) is a
// defect. Run under libFuzzer by tests/fuzz/libfuzzer_main.cpp (scripts/fuzz), and replayed
// on the regression corpus tests/data/fuzz/<target>/ by the test suite (test_fuzz_corpus.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace cutaway::fuzz {

struct Target {
  std::string name;       // also the corpus folder's name
  // The file name's, which picks the reader ("" for the scene text); "/name" puts the file in
  // a folder of its own, which the reader is given (a DICOM series).
  std::string extension;
  std::string seeds;      // what scripts/fuzz starts its corpus from (globs under the source)
  // A file set (a Shapefile's .shp/.shx/.dbf, a raw volume's header and data): the input is
  // split at kPartSeparator, its first part written with `extension`, the next ones with
  // these; a part the input lacks is a file that does not exist.
  std::vector<std::string> moreParts = {};
};

inline constexpr std::string_view kPartSeparator = "\n--cutaway-fuzz-part--\n";

const std::vector<Target>& targets();
const Target* findTarget(const std::string& name);

// Loads `size` bytes as the target's file: true when they loaded, false when they were
// refused with cutaway::Error; anything else escapes.
bool run(const Target& target, const std::uint8_t* data, std::size_t size);

}  // namespace cutaway::fuzz
