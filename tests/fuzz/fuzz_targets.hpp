// The loaders that read files users did not write themselves, as fuzz targets (issue 16): each
// takes arbitrary bytes as the content of one file and must either load it or throw
// cutaway::Error; anything else (a crash, a sanitizer report, a hang, another exception) is a
// defect. Run under libFuzzer by tests/fuzz/libfuzzer_main.cpp (scripts/fuzz), and replayed
// on the regression corpus tests/data/fuzz/<target>/ by the test suite (test_fuzz_corpus.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace cutaway::fuzz {

struct Target {
  std::string name;       // also the corpus folder's name
  std::string extension;  // the file name's, which picks the reader ("" for the scene text)
  std::string seeds;      // what scripts/fuzz starts its corpus from (globs under the source)
};

const std::vector<Target>& targets();
const Target* findTarget(const std::string& name);

// Loads `size` bytes as the target's file: true when they loaded, false when they were
// refused with cutaway::Error; anything else escapes.
bool run(const Target& target, const std::uint8_t* data, std::size_t size);

}  // namespace cutaway::fuzz
