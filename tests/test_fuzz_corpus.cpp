// The fuzz targets' corpus (tests/data/fuzz/<target>/): small seeds and every input that
// scripts/fuzz found to crash, hang or escape with another exception, replayed: each must load
// or be refused with cutaway::Error (CI replays them under ASan and UBSan too); the seeds named
// valid-* must load, so that fuzzing starts from files the readers accept.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "fuzz/fuzz_targets.hpp"

namespace fs = std::filesystem;

class FuzzCorpus : public ::testing::TestWithParam<std::string> {};

TEST_P(FuzzCorpus, EveryInputLoadsOrIsRefused) {
  const cutaway::fuzz::Target* target = cutaway::fuzz::findTarget(GetParam());
  ASSERT_NE(target, nullptr);
  const fs::path dir = fs::path(CUTAWAY_TEST_DATA) / "fuzz" / target->name;
  std::vector<fs::path> inputs;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file()) inputs.push_back(e.path());
  if (target->name == "scene" || target->name == "mesh-obj" || target->name == "geojson") {
    // Seeded from the tests' own files (fuzz_targets.cpp); their corpus folder may be empty.
  } else {
    EXPECT_FALSE(inputs.empty()) << "no seeds in " << dir;
  }
  for (const fs::path& input : inputs) {
    SCOPED_TRACE(input.string());
    std::ifstream in(input, std::ios::binary);
    const std::vector<char> bytes{std::istreambuf_iterator<char>(in), {}};
    const bool loaded = cutaway::fuzz::run(
        *target, reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    if (input.filename().string().starts_with("valid-")) EXPECT_TRUE(loaded);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Targets, FuzzCorpus,
    [] {
      std::vector<std::string> names;
      for (const auto& t : cutaway::fuzz::targets()) names.push_back(t.name);
      return ::testing::ValuesIn(names);
    }(),
    [](const auto& info) {
      std::string name = info.param;
      for (char& c : name)
        if (c == '-') c = '_';
      return name;
    });
