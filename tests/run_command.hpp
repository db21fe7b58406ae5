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
#include <string>

#include "test_label.hpp"

namespace cutaway::test {

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

// `name` inside a folder of this process's own, `cutaway-<kind>-<pid>` in the temp folder.
inline std::filesystem::path scratchPath(const std::string& kind, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("cutaway-" + kind + "-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

}  // namespace cutaway::test
