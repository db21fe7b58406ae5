// cutaway/gl/timer.hpp — GPU time of named passes with GL_TIME_ELAPSED queries.
//
// Only one GL_TIME_ELAPSED query may be active at a time, so passes are timed one after
// another, never nested. On Mesa's llvmpipe, a query that is begun but not flushed measures
// nothing useful (the commands are queued until the next flush), so `begin` flushes there.
//
//   cutaway::gl::PassTimer timer(info.software);
//   timer.begin("geometry"); drawScene(); timer.end();
//   for (auto& [name, ms] : timer.collect()) std::printf("%s %.3f ms\n", name.c_str(), ms);
#pragma once

#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "cutaway/gl/objects.hpp"

namespace cutaway::gl {

class PassTimer {
 public:
  explicit PassTimer(bool flushAfterBegin) : flushAfterBegin_(flushAfterBegin) {}
  void begin(const std::string& pass);
  void end();
  // Waits for all queries begun since the last collect or restart and returns (pass,
  // milliseconds; NaN where the driver's result exceeds the wall clock since the pass began,
  // as llvmpipe's first query in a renderer does).
  std::vector<std::pair<std::string, double>> collect();
  // Forgets the passes not collected: their queries are begun again by the next passes, so
  // frames that nobody collects keep one query per pass.
  void restart();

 private:
  bool flushAfterBegin_;
  std::vector<Query> pool_;
  std::vector<std::string> names_;
  std::vector<std::chrono::steady_clock::time_point> begun_;
  bool active_ = false;
};

}  // namespace cutaway::gl
