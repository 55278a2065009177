// The one way the renderer and its tools fan work out over threads.
#pragma once

#include <algorithm>
#include <thread>
#include <vector>

namespace phonglab {

// Number of threads for `requested` (0 = all hardware threads).
inline int resolve_thread_count(int requested) {
  if (requested > 0) return requested;
  const unsigned hw = std::thread::hardware_concurrency();
  return hw > 0 ? static_cast<int>(hw) : 1;
}

// Runs work(i) for every worker i in [0, n): 1 .. n - 1 on threads of their own, 0 on the
// caller's; returns when all have finished. n < 1 counts as 1.
template <class Work>
void run_workers(int n, const Work& work) {
  std::vector<std::thread> pool;
  pool.reserve(static_cast<std::size_t>(std::max(0, n - 1)));
  for (int i = 1; i < n; ++i) pool.emplace_back([&work, i] { work(i); });
  work(0);
  for (std::thread& t : pool) t.join();
}

}  // namespace phonglab
