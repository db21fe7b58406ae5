#include "cutaway/core/atomic_file.hpp"

#include <pthread.h>
#include <time.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>
#include <memory>
#include <optional>

#include "cutaway/core/error.hpp"

namespace cutaway {

namespace {

// `path` with a suffix of this process's own: "<path>.<what>-<pid>".
std::filesystem::path beside(const std::filesystem::path& path, const std::string& what) {
  std::filesystem::path p = path;
  p += "." + what + "-" + std::to_string(::getpid());
  return p;
}

// The file a path names: a symbolic link's target (followed as open() would), so that writing
// through a link replaces the file it points to, not the link.
std::filesystem::path followLinks(std::filesystem::path path) {
  namespace fs = std::filesystem;
  for (int hop = 0; hop < 40; ++hop) {  // Linux's own limit on a chain of links
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(path, ec))) return path;
    const fs::path target = fs::read_symlink(path, ec);
    if (ec) return path;
    path = target.is_absolute() ? target : path.parent_path() / target;
  }
  throw Error(path.string(), "", "too many levels of symbolic links");
}

// The file a write to `named` replaces: a link's target. A device, a FIFO or a socket there
// would be replaced by a regular file, not written to: refused.
std::filesystem::path writtenPath(const std::filesystem::path& named) {
  namespace fs = std::filesystem;
  fs::path path = followLinks(named);
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::exists(status) && !fs::is_directory(status) && !fs::is_regular_file(status))
    throw Error(path.string(), "",
                "is not a regular file (a device, a FIFO or a socket): only files are written");
  return path;
}

// The temporaries being written, and the folders made for them, removed by the signal handler a
// program may install (removeTemporariesOnSignals); fixed slots, as a handler may not allocate
// or lock.
constexpr std::size_t kPathBytes = 4096;  // PATH_MAX
struct Pending {
  std::atomic<bool> used{false};
  std::atomic<bool> ready{false};
  std::atomic<bool> folder{false};
  std::atomic<unsigned> version{0};  // odd while `path` is written: the handler's seqlock
  std::array<char, kPathBytes> path{};
};
std::array<Pending, 64> pending;

// Holds one temporary's (or made folder's) name in a slot while it lives.
class PendingFile {
 public:
  explicit PendingFile(const std::filesystem::path& tmp, bool folder = false) {
    const std::string& name = tmp.native();
    if (name.size() >= kPathBytes) return;
    for (Pending& p : pending) {
      bool expected = false;
      if (!p.used.compare_exchange_strong(expected, true)) continue;
      ++p.version;
      std::memcpy(p.path.data(), name.c_str(), name.size() + 1);
      p.folder = folder;
      ++p.version;
      p.ready = true;
      slot_ = &p;
      return;
    }
  }
  ~PendingFile() {
    if (!slot_) return;
    slot_->ready = false;
    slot_->used = false;
  }
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

 private:
  Pending* slot_ = nullptr;
};

// Writers placing their files (renames, and their undoing): a signal waits for them to end, so
// that a set of files is replaced whole or not at all.
std::atomic<int> placing{0};

// Holds SIGTERM, SIGINT and SIGHUP on this thread, and marks the placing for the handler on
// any other thread, while it lives.
class Placing {
 public:
  Placing() {
    sigset_t held;
    sigemptyset(&held);
    for (const int signal : {SIGTERM, SIGINT, SIGHUP}) sigaddset(&held, signal);
    pthread_sigmask(SIG_BLOCK, &held, &before_);
    ++placing;
  }
  ~Placing() {
    --placing;
    pthread_sigmask(SIG_SETMASK, &before_, nullptr);
  }
  Placing(const Placing&) = delete;
  Placing& operator=(const Placing&) = delete;

 private:
  sigset_t before_;
};

extern "C" void removeTemporariesAndDie(int signal) {
  while (placing.load() > 0) {  // a few renames: milliseconds at most
    const timespec pause{0, 1000000};
    nanosleep(&pause, nullptr);
  }
  // The temporaries first, then the made folders, each left empty by those inside it first
  // (a pass for each level a slot may wait on).
  for (std::size_t pass = 0; pass <= pending.size(); ++pass)
    for (Pending& p : pending) {
      // A name copied whole while no thread rewrote its slot (another may free and reuse it).
      const unsigned before = p.version.load();
      if (!p.ready || before % 2 == 1 || p.folder != (pass > 0)) continue;
      char name[kPathBytes];
      std::memcpy(name, p.path.data(), kPathBytes);
      if (p.version.load() == before && p.ready) pass > 0 ? ::rmdir(name) : ::unlink(name);
    }
  std::signal(signal, SIG_DFL);
  std::raise(signal);
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

void removeTemporariesOnSignals() {
  for (const int signal : {SIGTERM, SIGINT, SIGHUP}) {
    struct sigaction now {};
    if (::sigaction(signal, nullptr, &now) != 0 || now.sa_handler != SIG_DFL) continue;
    struct sigaction handler {};
    handler.sa_handler = removeTemporariesAndDie;
    sigemptyset(&handler.sa_mask);
    ::sigaction(signal, &handler, nullptr);
  }
}

void replaceFileAtomically(const std::filesystem::path& named,
                           const std::function<void(const std::filesystem::path&)>& write) {
  const std::filesystem::path path = writtenPath(named);
  // Before the writer runs: a C library's own message would name the temporary.
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : ".";
  if (std::error_code ec; !std::filesystem::is_directory(folder, ec))
    throw Error(
        path.string(), "",
        "cannot write: no folder " + folder.string() + (ec ? " (" + ec.message() + ")" : ""));
  const std::filesystem::path tmp = beside(path, "tmp");
  const PendingFile pendingFile(tmp);
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

struct MadeFolders::Slots {
  std::vector<std::unique_ptr<PendingFile>> folders;
};

MadeFolders::MadeFolders(const std::filesystem::path& dir) : slots_(std::make_unique<Slots>()) {
  std::error_code ec;
  for (std::filesystem::path p = dir; !p.empty() && !std::filesystem::exists(p, ec);
       p = p.parent_path()) {
    made_.push_back(p);
    slots_->folders.push_back(std::make_unique<PendingFile>(p, true));
  }
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    removeEmpty();
    throw Error(dir.string(), "", "cannot create the folder: " + ec.message());
  }
}

MadeFolders::~MadeFolders() {
  if (!kept_) removeEmpty();
}

void MadeFolders::removeEmpty() const {
  std::error_code ignored;
  for (const std::filesystem::path& p : made_) std::filesystem::remove(p, ignored);  // if empty
}

void writeFileAtomically(const std::filesystem::path& path, const FileWriter& write) {
  writeFilesAtomically({{path, write}});
}

void writeFilesAtomically(const std::vector<std::pair<std::filesystem::path, FileWriter>>& named) {
  namespace fs = std::filesystem;
  std::vector<std::pair<fs::path, FileWriter>> files;
  files.reserve(named.size());
  for (const auto& [path, write] : named) files.emplace_back(writtenPath(path), write);
  for (std::size_t i = 0; i < files.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (files[i].first == files[j].first)
        throw Error(files[i].first.string(), "", "named twice among the files written together");
  std::vector<fs::path> temporaries;
  temporaries.reserve(files.size());
  std::vector<std::unique_ptr<PendingFile>> pendingFiles;  // until the temporaries are renamed
  // Each path in turn gets its temporary renamed over it, which replaces it atomically. Where a
  // later path could still fail, its old file is kept first as a backup (a second link to it,
  // or moved aside where the file system has no links), and put back if one does.
  const bool set = files.size() > 1;
  std::vector<bool> backedUp;
  backedUp.reserve(files.size());
  std::size_t placed = 0;
  std::optional<Placing> holding;  // from the first rename to the last removal of a backup
  try {
    for (const auto& [path, write] : files) {
      pendingFiles.push_back(std::make_unique<PendingFile>(beside(path, "tmp")));
      temporaries.push_back(writeTemporary(path, write));
    }
    holding.emplace();
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
