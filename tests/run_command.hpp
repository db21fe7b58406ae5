// Running the project's programs from end-to-end tests: a shell command line with stdout and
// stderr captured apart, and a per-process scratch folder.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <system_error>

#include <gtest/gtest.h>

#include "test_label.hpp"

namespace cutaway::test {

// This build's programs run under AddressSanitizer (they are built as the tests are). Its
// allocator reserves terabytes of address space, so `ulimit -v` cannot bound their memory.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

struct Result {
  int exitCode;
  std::string out, err;
};

inline Result runCommand(const std::string& command) {
  usesGl();  // the programs render
  namespace fs = std::filesystem;
  const fs::path errFile =
      fs::temp_directory_path() / ("cutaway-test-err-" + std::to_string(::getpid()));
  FILE* pipe = popen((command + " 2>" + errFile.string()).c_str(), "r");
  std::string out;
  std::array<char, 4096> buffer;
  for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0;)
    out.append(buffer.data(), n);
  const int status = pclose(pipe);
  std::ifstream errStream(errFile);
  std::string err((std::istreambuf_iterator<char>(errStream)), {});
  fs::remove(errFile);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out, err};
}

// Removes `dir` when the process exits, unless a test failed: then its files stay for a look.
inline void removeAtExit(const std::filesystem::path& dir) {
  static struct Folders {
    std::set<std::filesystem::path> dirs;
    ~Folders() {
      if (::testing::UnitTest::GetInstance()->Failed()) return;
      std::error_code ignored;
      for (const auto& d : dirs) std::filesystem::remove_all(d, ignored);
    }
  } folders;
  folders.dirs.insert(dir);
}

// `name` inside a folder of this process's own, `cutaway-<kind>-<pid>` in the temp folder,
// removed at exit (removeAtExit).
inline std::filesystem::path scratchPath(const std::string& kind, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("cutaway-" + kind + "-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  removeAtExit(dir);
  return dir / name;
}

}  // namespace cutaway::test
