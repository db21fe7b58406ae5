// Name patterns: ECMAScript regular expressions over object names and groups (a scene file's
// "nodes" and "overrides", `--importance PATTERN=I`). std::regex compiles by recursion, one
// level per group and per term of a sequence, so a pattern nested or chained thousands deep
// exhausts the stack: patterns are limited in length and nesting before they are compiled.
// Its default matcher backtracks, by recursion: "(a*)*b" against 26 a's ran for minutes, and a
// name of 16,000 characters overflowed an 8 MiB stack against "(a|b)*". Patterns are therefore
// matched by libstdc++'s breadth-first matcher (`__polynomial`: time pattern × name, no
// recursion per character), which has no back-references; the names a scene file gives stay
// limited in length (a mesh file's node names are within Assimp's 1,024).
#pragma once

#include <algorithm>
#include <cstddef>
#include <regex>
#include <stdexcept>
#include <string>

#include "cutaway/core/error.hpp"

namespace cutaway {

constexpr std::size_t kMaxNamePatternLength = 1024;
constexpr int kMaxNamePatternNesting = 64;
constexpr std::size_t kMaxNameLength = 1024;

#if defined(__GLIBCXX__)
constexpr std::regex::flag_type kNamePatternSyntax =
    std::regex::ECMAScript | std::regex_constants::__polynomial;
#else
#error \
    "name patterns need libstdc++'s polynomial-time std::regex matcher (std::regex_constants::__polynomial)"
#endif

// The pattern as a message names it unquoted (a file field): cut after 60 characters, as
// cutaway::quote cuts it.
inline std::string shortNamePattern(const std::string& pattern) {
  return pattern.size() > 60 ? pattern.substr(0, 60) + "…" : pattern;
}

// The compiled pattern; throws std::invalid_argument with the reason (naming the pattern).
inline std::regex compileNamePattern(const std::string& pattern) {
  if (pattern.size() > kMaxNamePatternLength)
    throw std::invalid_argument("regular expression of " + std::to_string(pattern.size()) +
                                " characters (at most " + std::to_string(kMaxNamePatternLength) +
                                "): " + quote(pattern));
  int depth = 0, deepest = 0;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] == '\\')
      ++i;  // an escaped character nests nothing
    else if (pattern[i] == '(' || pattern[i] == '[')
      deepest = std::max(deepest, ++depth);
    else if (pattern[i] == ')' || pattern[i] == ']')
      --depth;
  }
  if (deepest > kMaxNamePatternNesting)
    throw std::invalid_argument("regular expression nests deeper than " +
                                std::to_string(kMaxNamePatternNesting) +
                                " groups: " + quote(pattern));
  try {
    return std::regex(pattern, kNamePatternSyntax);
  } catch (const std::regex_error& e) {
    // libstdc++'s own words for a pattern of too many states ask to rebuild it larger.
    throw std::invalid_argument(
        "invalid regular expression " + quote(pattern) + ": " +
        (e.code() == std::regex_constants::error_space
             ? "it needs more states than a pattern may have (repeat less, e.g. a smaller {n})"
             : e.what()));
  }
}

}  // namespace cutaway
