#include "cutaway/core/atomic_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "cutaway/core/error.hpp"

namespace cutaway {

void replaceFileAtomically(const std::filesystem::path& path,
                           const std::function<void(const std::filesystem::path&)>& write) {
  std::filesystem::path tmp = path;
  tmp += ".tmp-" + std::to_string(::getpid());
  try {
    write(tmp);
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw Error(path.string(), "", "cannot write: " + ec.message());
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw;
  }
}

namespace {

// Writes `path`'s temporary and returns its name; removes it again if the writing failed.
std::filesystem::path writeTemporary(const std::filesystem::path& path, const FileWriter& write) {
  std::filesystem::path tmp = path;
  tmp += ".tmp-" + std::to_string(::getpid());
  try {
    // With the system's reason where it gave one (errno: no space, no permission).
    const auto fail = [&](const std::string& what) {
      throw Error(path.string(), "", errno != 0 ? what + ": " + std::strerror(errno) : what);
    };
    errno = 0;
    std::ofstream os(tmp, std::ios::binary);
    if (!os) fail("cannot open for writing");
    errno = 0;
    write(os);
    os.close();  // flushes: a full disk shows here
    if (!os) fail("write failed");
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw;
  }
  return tmp;
}

}  // namespace

void writeFileAtomically(const std::filesystem::path& path, const FileWriter& write) {
  writeFilesAtomically({{path, write}});
}

void writeFilesAtomically(const std::vector<std::pair<std::filesystem::path, FileWriter>>& files) {
  std::vector<std::filesystem::path> temporaries;
  std::size_t renamed = 0;
  const auto removeTemporaries = [&] {
    std::error_code ignored;
    for (std::size_t i = renamed; i < temporaries.size(); ++i)
      std::filesystem::remove(temporaries[i], ignored);
  };
  try {
    for (const auto& [path, write] : files) temporaries.push_back(writeTemporary(path, write));
    for (; renamed < files.size(); ++renamed) {
      std::error_code ec;
      std::filesystem::rename(temporaries[renamed], files[renamed].first, ec);
      if (ec) throw Error(files[renamed].first.string(), "", "cannot write: " + ec.message());
    }
  } catch (...) {
    removeTemporaries();
    throw;
  }
}

}  // namespace cutaway
