// cutaway/core/atomic_file.hpp — write a file so that a failure never leaves a partial one.
//
// The content goes to "<path>.tmp-<pid>" first and is renamed over <path> only when the
// writer returned without throwing. A path that is a symbolic link has the file it points to
// replaced, as writing through open() would.
//
//   cutaway::writeFileAtomically("out.json", [&](std::ostream& os) { os << text; });
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <ostream>
#include <utility>
#include <vector>

namespace cutaway {

using FileWriter = std::function<void(std::ostream&)>;

void writeFileAtomically(const std::filesystem::path& path, const FileWriter& write);

// Several files replaced together (a folder of AOVs and its index): every content goes to its
// temporary first; only when all were written does each path in turn get its new file (its old
// one kept aside first, and put back if a later path fails). A failure leaves every path as it
// was; a path named twice, or one that is a folder, is refused.
void writeFilesAtomically(const std::vector<std::pair<std::filesystem::path, FileWriter>>& files);

// For writers that need a path (C libraries): `write` receives the temporary path.
void replaceFileAtomically(const std::filesystem::path& path,
                           const std::function<void(const std::filesystem::path&)>& write);

// The folders a writer makes for the files it is about to write: `dir` and those above it that
// are missing (Error if one cannot be made). Until `keep()`, they are removed again, where
// empty, by the destructor and by the handlers of removeTemporariesOnSignals (after the
// temporaries), so that a failed or stopped run leaves no empty folder behind.
class MadeFolders {
 public:
  explicit MadeFolders(const std::filesystem::path& dir);
  ~MadeFolders();
  MadeFolders(const MadeFolders&) = delete;
  MadeFolders& operator=(const MadeFolders&) = delete;
  void keep() { kept_ = true; }

 private:
  void removeEmpty() const;
  struct Slots;
  std::unique_ptr<Slots> slots_;
  std::vector<std::filesystem::path> made_;  // innermost first
  bool kept_ = false;
};

// A program's handlers for SIGTERM, SIGINT and SIGHUP (where it has none of its own) that remove
// the temporaries being written, then end the program as the signal would have.
void removeTemporariesOnSignals();

}  // namespace cutaway
