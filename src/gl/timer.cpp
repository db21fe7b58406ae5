#include "cutaway/gl/timer.hpp"

#include <cassert>
#include <cmath>

namespace cutaway::gl {

void PassTimer::begin(const std::string& pass) {
  assert(!active_ && "GL_TIME_ELAPSED queries cannot nest");
  if (names_.size() == pool_.size()) pool_.push_back(Query::create(GL_TIME_ELAPSED));
  glBeginQuery(GL_TIME_ELAPSED, pool_[names_.size()].id());
  if (flushAfterBegin_) glFlush();
  names_.push_back(pass);
  begun_.push_back(std::chrono::steady_clock::now());
  active_ = true;
}

void PassTimer::end() {
  assert(active_);
  glEndQuery(GL_TIME_ELAPSED);
  active_ = false;
}

std::vector<std::pair<std::string, double>> PassTimer::collect() {
  assert(!active_);
  std::vector<std::pair<std::string, double>> result;
  for (std::size_t i = 0; i < names_.size(); ++i) {
    GLuint64 ns = 0;
    glGetQueryObjectui64v(pool_[i].id(), GL_QUERY_RESULT, &ns);
    // A pass cannot take longer than the wall clock from its begin to its result. llvmpipe
    // gives a new renderer's first query the time since boot (its start left at 0): unknown.
    const double ms = double(ns) * 1e-6;
    const double wall =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begun_[i])
            .count();
    result.emplace_back(names_[i], ms <= wall * 1.5 + 5.0 ? ms : std::nan(""));
  }
  names_.clear();
  begun_.clear();
  return result;
}

void PassTimer::restart() {
  assert(!active_);
  names_.clear();
  begun_.clear();
}

}  // namespace cutaway::gl
