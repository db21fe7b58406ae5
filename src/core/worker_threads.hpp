// Work shared out to threads: each runs `work`, which takes its part from a common queue (an
// atomic counter) until none is left.
#pragma once

#include <algorithm>
#include <functional>
#include <system_error>
#include <thread>
#include <vector>

namespace cutaway {

// Runs `work` on `threads` threads, this one among them, and waits for them all. A thread that
// cannot be started leaves its part to the others.
inline void runOnThreads(int threads, const std::function<void()>& work) {
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) {
    try {
      pool.emplace_back(work);
    } catch (const std::system_error&) {
      break;
    }
  }
  work();
  for (std::thread& t : pool) t.join();
}

// The threads worth starting here: the hardware's, at most `most`.
inline int hardwareThreads(int most) {
  return int(std::clamp(std::thread::hardware_concurrency(), 1u, unsigned(std::max(most, 1))));
}

}  // namespace cutaway
