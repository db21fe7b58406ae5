// cutaway/core/error.hpp — the one error type for bad input, I/O and GPU failures.
//
// Errors caused by data (a scene file, a mesh, an image) say what went wrong, where
// (file and a place inside it: a JSON pointer, a line) and why. The CLI prints
// `Error::what()` on one line and exits non-zero. Programmer errors are asserts instead.
//
//   throw cutaway::Error("scene.json", "/objects/2/role", "unknown role \"foo\"");
//   // what(): scene.json: /objects/2/role: unknown role "foo"
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace cutaway {

class Error : public std::runtime_error {
 public:
  Error(const std::string& file, const std::string& place, const std::string& reason)
      : std::runtime_error(format(file, place, reason)),
        file_(file),
        place_(place),
        reason_(reason) {}
  explicit Error(const std::string& reason) : Error("", "", reason) {}

  const std::string& file() const { return file_; }
  const std::string& place() const { return place_; }
  const std::string& reason() const { return reason_; }

 private:
  static std::string format(const std::string& file, const std::string& place,
                            const std::string& reason) {
    std::string s;
    if (!file.empty()) s += file + ": ";
    if (!place.empty()) s += place + ": ";
    s += reason;
    // what() is read as a C string: a NUL in a quoted name or value would end the message.
    for (std::size_t at = 0; (at = s.find('\0', at)) != std::string::npos; at += 2)
      s.replace(at, 1, "\\0");
    return s;
  }
  std::string file_, place_, reason_;
};

// User text as a message shows it, in double quotes: cut after 60 characters, so that a
// 100 KB name or value does not fill the terminal (the place around it says which one), and a
// NUL as \0 (a message passed on through what() would end there).
inline std::string quote(std::string_view text) {
  std::string q(1, '"');  // appended, not "\"" + …: GCC 12 warns on that (-Wrestrict)
  for (const char c : text.substr(0, 60)) {
    if (c == '\0')
      q += "\\0";
    else
      q += c;
  }
  if (text.size() > 60) q += "…";
  q += '"';
  return q;
}

}  // namespace cutaway
