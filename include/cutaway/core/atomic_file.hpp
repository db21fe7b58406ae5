// cutaway/core/atomic_file.hpp — write a file so that a failure never leaves a partial one.
//
// The content goes to "<path>.tmp-<pid>" first and is renamed over <path> only when the
// writer returned without throwing.
//
//   cutaway::writeFileAtomically("out.json", [&](std::ostream& os) { os << text; });
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>

namespace cutaway {

void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write);

// For writers that need a path (C libraries): `write` receives the temporary path.
void replaceFileAtomically(const std::filesystem::path& path,
                           const std::function<void(const std::filesystem::path&)>& write);

}  // namespace cutaway
