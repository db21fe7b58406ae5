#include "cutaway/core/atomic_file.hpp"

#include <unistd.h>

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
    std::ofstream os(tmp, std::ios::binary);
    if (!os) throw Error(path.string(), "", "cannot open for writing");
    write(os);
    os.flush();
    if (!os) throw Error(path.string(), "", "write failed");
  });
}

}  // namespace cutaway
