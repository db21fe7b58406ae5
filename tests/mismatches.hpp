// The failing cases of a pixel-by-pixel comparison: how many, and the first few with both
// values, so that a failure prints what was expected and what came (issue 17).
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace cutaway::test {

class Mismatches {
 public:
  // Counts a case the caller's tolerance failed: at pixel (x, y), `expected` against `actual`.
  void add(int x, int y, double expected, double actual) {
    if (shown_.size() < kShown) shown_.push_back({x, y, expected, actual});
    ++count_;
  }
  int count() const { return count_; }

  friend std::ostream& operator<<(std::ostream& out, const Mismatches& m) {
    out << m.count_ << " mismatches";
    for (const Case& c : m.shown_)
      out << "; at (" << c.x << ", " << c.y << ") expected " << c.expected << ", got " << c.actual;
    return out << (m.count_ > int(m.shown_.size()) ? "; …" : "");
  }

 private:
  static constexpr std::size_t kShown = 5;
  struct Case {
    int x, y;
    double expected, actual;
  };
  std::vector<Case> shown_;
  int count_ = 0;
};

}  // namespace cutaway::test
