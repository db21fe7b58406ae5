#include "cutaway/core/atomic_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "cutaway/core/error.hpp"

namespace cutaway {

namespace {

// `path` with a suffix of this process's own: "<path>.<what>-<pid>".
std::filesystem::path beside(const std::filesystem::path& path, const std::string& what) {
  std::filesystem::path p = path;
  p += "." + what + "-" + std::to_string(::getpid());
  return p;
}

// Writes `path`'s temporary and returns its name; removes it again if the writing failed.
std::filesystem::path writeTemporary(const std::filesystem::path& path, const FileWriter& write) {
  const std::filesystem::path tmp = beside(path, "tmp");
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

void replaceFileAtomically(const std::filesystem::path& path,
                           const std::function<void(const std::filesystem::path&)>& write) {
  const std::filesystem::path tmp = beside(path, "tmp");
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

void writeFileAtomically(const std::filesystem::path& path, const FileWriter& write) {
  writeFilesAtomically({{path, write}});
}

void writeFilesAtomically(const std::vector<std::pair<std::filesystem::path, FileWriter>>& files) {
  namespace fs = std::filesystem;
  for (std::size_t i = 0; i < files.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (files[i].first == files[j].first)
        throw Error(files[i].first.string(), "", "named twice among the files written together");
  std::vector<fs::path> temporaries;
  temporaries.reserve(files.size());
  // Each path in turn gets its temporary renamed over it, which replaces it atomically. Where a
  // later path could still fail, its old file is kept first as a backup (a second link to it,
  // or moved aside where the file system has no links), and put back if one does.
  const bool set = files.size() > 1;
  std::vector<bool> backedUp;
  backedUp.reserve(files.size());
  std::size_t placed = 0;
  try {
    for (const auto& [path, write] : files) temporaries.push_back(writeTemporary(path, write));
    for (; placed < files.size(); ++placed) {
      const fs::path& path = files[placed].first;
      std::error_code ec;
      const fs::file_status status = fs::symlink_status(path, ec);  // not_found sets ec too
      ec.clear();
      if (fs::is_directory(status)) throw Error(path.string(), "", "is a directory, not a file");
      const bool backup = set && fs::exists(status);
      if (backup) {
        fs::create_hard_link(path, beside(path, "old"), ec);
        if (ec) ec.clear(), fs::rename(path, beside(path, "old"), ec);
      }
      if (!ec) {
        backedUp.push_back(backup);
        fs::rename(temporaries[placed], path, ec);
      }
      if (ec) throw Error(path.string(), "", "cannot write: " + ec.message());
    }
  } catch (...) {
    std::error_code ignored;
    for (std::size_t i = 0; i < backedUp.size(); ++i) {
      const fs::path& path = files[i].first;
      if (backedUp[i]) {
        fs::rename(beside(path, "old"), path, ignored);
        fs::remove(beside(path, "old"), ignored);  // still there if it was `path`'s own link
      } else if (i < placed) {
        fs::remove(path, ignored);
      }
    }
    for (std::size_t i = placed; i < temporaries.size(); ++i) fs::remove(temporaries[i], ignored);
    throw;
  }
  std::error_code ignored;
  for (std::size_t i = 0; i < files.size(); ++i)
    if (backedUp[i]) fs::remove(beside(files[i].first, "old"), ignored);
}

}  // namespace cutaway
