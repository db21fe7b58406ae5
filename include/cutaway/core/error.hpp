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

}  // namespace cutaway
