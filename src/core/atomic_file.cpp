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

void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write) {
  replaceFileAtomically(path, [&](const std::filesystem::path& tmp) {
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
  });
}

}  // namespace cutaway
