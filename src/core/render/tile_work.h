// Work spread over threads item by item, as render_pass spreads its tiles (internal to core/render).
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <vector>

#include "core/render/render.h"
#include "core/base/threads.h"

namespace phonglab {

// work(i, counts) for i in [0, count), each on one of the threads; `counts` is the worker's own.
// Returns false when `cancel` or `stop` ended it early.
template <class Work>
bool for_each_index(std::size_t count, int threads, const std::atomic<bool>* cancel, std::atomic<bool>& stop,
                    std::vector<RayCounts>& counts, Work&& work) {
  const int n = std::max(1, std::min(resolve_thread_count(threads), static_cast<int>(count)));
  counts.assign(static_cast<std::size_t>(n), RayCounts{});
  std::atomic<std::size_t> next{0};
  run_workers(n, [&](int worker) {
    for (;;) {
      if ((cancel && cancel->load(std::memory_order_relaxed)) || stop.load(std::memory_order_relaxed)) {
        stop.store(true, std::memory_order_relaxed);
        return;
      }
      const std::size_t i = next.fetch_add(1, std::memory_order_relaxed);
      if (i >= count) return;
      work(i, counts[static_cast<std::size_t>(worker)]);
    }
  });
  return !stop.load();
}

}  // namespace phonglab
