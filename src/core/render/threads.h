// The one way the renderer and its tools fan work out over threads.
#pragma once

#include <functional>
#include <thread>

namespace phonglab {

// Number of threads for `requested` (0 = all hardware threads).
inline int resolve_thread_count(int requested) {
  if (requested > 0) return requested;
  const unsigned hw = std::thread::hardware_concurrency();
  return hw > 0 ? static_cast<int>(hw) : 1;
}

// Runs work(i) for every worker i in [0, n): 0 on the caller's thread, 1 .. n - 1 on helper
// threads that the calling thread keeps between calls (a render pass of a small image takes less
// than starting threads would), and returns when all have finished. n < 1 counts as 1. Each
// calling thread has helpers of its own, so concurrent callers (the previewer's renderers) never
// wait for each other; they end with it.
void run_workers(int n, const std::function<void(int)>& work);

}  // namespace phonglab
