// Strict JSON reading for the scene format (docs/scene-format.md): every error names the
// file, the JSON pointer and the reason; unknown keys are errors. Shared by every part of the
// scene file: the scene reader (src/scene), the option schemas (core/options.hpp) and the
// techniques' own keys.
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/name_pattern.hpp"
#include "cutaway/core/error.hpp"
#include "cutaway/core/geo_frame.hpp"
#include "cutaway/core/unit_vector.hpp"

namespace cutaway::json_reader {

using json = nlohmann::json;

struct Context {
  std::string file;
  std::filesystem::path baseDir;
  GeoFrame geo;  // read first: GIS layers and rasters anywhere in the file go through it
  [[noreturn]] void fail(const std::string& pointer, const std::string& reason) const {
    throw Error(file, pointer.empty() ? "/" : pointer, reason);
  }
};

// The JSON text, or an error at the line and column where it fails.
inline json parse(const Context& ctx, const std::string& text) {
  // Turn a 1-based byte offset into a line and column a person can find.
  const auto lineColumn = [&text](std::size_t byte) {
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i + 1 < byte && i < text.size(); ++i) {
      if (text[i] == '\n')
        ++line, column = 1;
      else
        ++column;
    }
    return "line " + std::to_string(line) + ", column " + std::to_string(column);
  };
  // nlohmann's lexer ends the input at a NUL byte, and would ignore what follows it; JSON
  // allows none anywhere.
  if (const auto nul = text.find('\0'); nul != std::string::npos)
    throw Error(ctx.file, lineColumn(nul + 1), "invalid JSON: a NUL byte");
  json root;
  try {
    root = json::parse(text);
  } catch (const json::parse_error& e) {
    std::string reason = e.what();
    if (auto p = reason.find(": syntax error"); p != std::string::npos)
      reason = reason.substr(p + 2);
    throw Error(ctx.file, lineColumn(e.byte), "invalid JSON: " + reason);
  } catch (const json::exception& e) {
    // A number too large for a double ("1e999") is out_of_range, not a parse_error, and has
    // no offset: place it at the first occurrence of the literal the message quotes.
    std::string reason = e.what();
    if (auto p = reason.find("] "); p != std::string::npos) reason = reason.substr(p + 2);
    std::string place;
    const auto open = reason.find('\''), close = reason.rfind('\'');
    if (open != std::string::npos && close > open + 1)
      if (const auto at = text.find(reason.substr(open + 1, close - open - 1));
          at != std::string::npos)
        place = lineColumn(at + (close - open - 1));
    throw Error(ctx.file, place, "invalid JSON: " + reason);
  }
  return root;
}

inline std::string typeName(const json& j) {
  return j.type_name();
}

// A key as one JSON pointer token (RFC 6901): "~" → "~0", "/" → "~1".
inline std::string token(const std::string& key) {
  std::string out;
  for (char c : key) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return out;
}

// One JSON object being read: fields are taken by name, and `finish` rejects the rest.
class ObjectReader {
 public:
  ObjectReader(const Context& ctx, const json& j, std::string pointer)
      : ctx_(ctx), j_(j), pointer_(std::move(pointer)) {
    if (!j.is_object()) ctx.fail(pointer_, "expected an object, got " + typeName(j));
  }
  const json* take(const std::string& key) {
    taken_.insert(key);
    const auto it = j_.find(key);
    return it == j_.end() ? nullptr : &*it;
  }
  const json& require(const std::string& key) {
    const json* v = take(key);
    if (!v) ctx_.fail(pointer_, "missing required key " + quote(key));
    return *v;
  }
  bool has(const std::string& key) const { return j_.contains(key); }
  bool taken(const std::string& key) const { return taken_.count(key) != 0; }
  std::string at(const std::string& key) const { return pointer_ + "/" + key; }
  const std::string& pointer() const { return pointer_; }
  void finish() const {
    for (const auto& [key, value] : j_.items())
      if (!taken_.count(key)) {
        std::string known;
        for (const auto& k : taken_) known += (known.empty() ? "" : ", ") + k;
        ctx_.fail(pointer_ + "/" + token(key),
                  "unknown key " + quote(key) + " (expected one of: " + known + ")");
      }
  }

 private:
  const Context& ctx_;
  const json& j_;
  std::string pointer_;
  std::set<std::string> taken_;
};

// The shortest decimal that reads back as d, or as the float d is when it is one, and whole
// numbers in full: messages name the value given (180.0001, not 180; 1073741825, not
// 1.07374e+09) and a float field's value as it was written.
inline std::string decimal(double d) {
  char buffer[32];
  const float f = float(d);
  const auto end = d == std::trunc(d) && std::abs(d) < 1e15
                       ? std::to_chars(buffer, buffer + sizeof buffer, std::int64_t(d)).ptr
                   : double(f) == d ? std::to_chars(buffer, buffer + sizeof buffer, f).ptr
                                    : std::to_chars(buffer, buffer + sizeof buffer, d).ptr;
  return std::string(buffer, end);
}

inline double number(const Context& ctx, const json& j, const std::string& ptr, double lo, double hi) {
  if (!j.is_number()) ctx.fail(ptr, "expected a number, got " + typeName(j));
  const double v = j.get<double>();
  if (!(v >= lo && v <= hi)) {
    ctx.fail(ptr, "value " + decimal(v) + " is outside [" + decimal(lo) + ", " + decimal(hi) + "]");
  }
  return v;
}

inline int integer(const Context& ctx, const json& j, const std::string& ptr, int lo, int hi) {
  if (!j.is_number_integer()) ctx.fail(ptr, "expected an integer, got " + typeName(j));
  return int(number(ctx, j, ptr, lo, hi));
}

inline bool boolean(const Context& ctx, const json& j, const std::string& ptr) {
  if (!j.is_boolean()) ctx.fail(ptr, "expected true or false, got " + typeName(j));
  return j.get<bool>();
}

// A string; NUL is refused (no name, file or pattern holds one, and a file name would be cut
// at it: "cube.obj\u0000.png" opened cube.obj).
inline std::string string(const Context& ctx, const json& j, const std::string& ptr) {
  if (!j.is_string()) ctx.fail(ptr, "expected a string, got " + typeName(j));
  std::string s = j.get<std::string>();
  if (const std::size_t at = s.find('\0'); at != std::string::npos)
    ctx.fail(ptr, "the string holds a NUL character (at " + std::to_string(at) + ")");
  return s;
}

// A name that name patterns are matched against (objects, groups, proxies, volumes, networks):
// at most kMaxNameLength characters (core/name_pattern.hpp), and not empty unless `mayBeEmpty`
// (a group: "" is none).
inline std::string name(const Context& ctx, const json& j, const std::string& ptr,
                        const std::string& what, bool mayBeEmpty = false) {
  std::string s = string(ctx, j, ptr);
  if (s.empty() && !mayBeEmpty) ctx.fail(ptr, what + " name must not be empty");
  if (s.size() > kMaxNameLength)
    ctx.fail(ptr, what + " name of " + std::to_string(s.size()) + " characters (at most " +
                      std::to_string(kMaxNameLength) + ")");
  return s;
}

inline std::string oneOf(const Context& ctx, const json& j, const std::string& ptr,
                  const std::vector<std::string>& names) {
  const std::string v = string(ctx, j, ptr);
  for (const auto& n : names)
    if (n == v) return v;
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  ctx.fail(ptr, "unknown value " + quote(v) + " (expected one of: " + list + ")");
}

// What an array of the wrong length, or a value that is no array, is: "1 element", "5 elements",
// "a string".
inline std::string sizeOrType(const json& j) {
  if (!j.is_array()) return typeName(j);
  return std::to_string(j.size()) + (j.size() == 1 ? " element" : " elements");
}

inline glm::dvec3 dvec3(const Context& ctx, const json& j, const std::string& ptr,
                        double lo = -1e30, double hi = 1e30) {
  if (!j.is_array() || j.size() != 3)
    ctx.fail(ptr, "expected an array of 3 numbers, got " + sizeOrType(j));
  glm::dvec3 v;
  for (int i = 0; i < 3; ++i)
    v[i] = number(ctx, j[std::size_t(i)], ptr + "/" + std::to_string(i), lo, hi);
  return v;
}

inline glm::vec3 vec3(const Context& ctx, const json& j, const std::string& ptr, double lo = -1e30,
                      double hi = 1e30) {
  return glm::vec3(dvec3(ctx, j, ptr, lo, hi));
}

inline glm::vec3 color(const Context& ctx, const json& j, const std::string& ptr) {
  return vec3(ctx, j, ptr, 0.0, 1.0);
}

// Any length but zero ([1e20, 1e20, 0] was taken for a zero vector: core/unit_vector.hpp).
inline glm::vec3 direction(const Context& ctx, const json& j, const std::string& ptr) {
  const std::optional<glm::vec3> unit = unitVector(dvec3(ctx, j, ptr, -1e30, 1e30));
  if (!unit) ctx.fail(ptr, "a direction must not be the zero vector");
  return *unit;
}

// A regular expression given as text: ECMAScript, as the format uses, limited in length and
// nesting (core/name_pattern.hpp).
inline std::regex regex(const Context& ctx, const std::string& pattern, const std::string& ptr) {
  try {
    return compileNamePattern(pattern);
  } catch (const std::invalid_argument& e) {
    ctx.fail(ptr, e.what());
  }
}

inline std::regex regex(const Context& ctx, const json& j, const std::string& ptr) {
  return regex(ctx, string(ctx, j, ptr), ptr);
}

// The shortest decimal that reads back as the same float, for writing: 35 stays 35, not
// 35.000000000000001, and a loader's float of it is bit-identical.
inline double exact(float f) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, f).ptr;
  double d = 0;
  std::from_chars(buffer, end, d);
  return d;
}

}  // namespace cutaway::json_reader
