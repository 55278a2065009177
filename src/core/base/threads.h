// The one way the renderer and its tools fan work out over threads.
#pragma once

#include <exception>
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

// Runs `a` on a thread of its own and `b` on this one, and returns when both are done; an
// exception from either (out of memory, say) is rethrown here, `b`'s first. Where there are no
// threads (the web page's WebAssembly without pthreads), `b` and then `a` on this one.
template <class A, class B>
void in_parallel(A&& a, B&& b) {
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
  b();
  a();
#else
  std::exception_ptr a_error;
  std::thread thread([&] {
    try {
      a();
    } catch (...) {
      a_error = std::current_exception();
    }
  });
  try {
    b();
  } catch (...) {
    thread.join();
    throw;
  }
  thread.join();
  if (a_error) std::rethrow_exception(a_error);
#endif
}

}  // namespace phonglab
