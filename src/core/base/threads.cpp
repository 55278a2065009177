#include "core/base/threads.h"

#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <vector>

namespace phonglab {

namespace {

// Helper threads of one calling thread. A job is published under the mutex with a new
// generation; each helper runs its share once per generation and counts itself out.
class WorkerPool {
 public:
  WorkerPool() = default;
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;
  ~WorkerPool() {
    {
      const std::lock_guard lock(mutex_);
      stop_ = true;
    }
    start_.notify_all();
    for (std::thread& t : helpers_) t.join();
  }

  void run(int n, const std::function<void(int)>& work) {
    grow(n - 1);
    {
      const std::lock_guard lock(mutex_);
      work_ = &work;
      workers_ = n;
      pending_ = n - 1;
      ++generation_;
    }
    start_.notify_all();
    std::exception_ptr error;
    try {
      work(0);
    } catch (...) {
      error = std::current_exception();  // the helpers still use `work`: wait for them first
    }
    std::unique_lock lock(mutex_);
    done_.wait(lock, [&] { return pending_ == 0; });
    work_ = nullptr;
    if (error) std::rethrow_exception(error);
  }

 private:
  void grow(int helpers) {
    while (static_cast<int>(helpers_.size()) < helpers) {
      const int index = static_cast<int>(helpers_.size()) + 1;
      std::uint64_t seen;
      {
        const std::lock_guard lock(mutex_);
        seen = generation_;
      }
      helpers_.emplace_back([this, index, seen] { serve(index, seen); });
    }
  }

  // Helper `index` (worker number `index` of every job with that many workers or more).
  void serve(int index, std::uint64_t seen) {
    for (;;) {
      const std::function<void(int)>* work = nullptr;
      {
        std::unique_lock lock(mutex_);
        start_.wait(lock, [&] { return stop_ || generation_ != seen; });
        if (stop_) return;
        seen = generation_;
        if (index >= workers_) continue;  // a job with fewer workers than helpers
        work = work_;
      }
      (*work)(index);
      {
        const std::lock_guard lock(mutex_);
        --pending_;
      }
      done_.notify_one();
    }
  }

  std::mutex mutex_;
  std::condition_variable start_, done_;
  std::vector<std::thread> helpers_;
  const std::function<void(int)>* work_ = nullptr;
  int workers_ = 0;
  int pending_ = 0;
  std::uint64_t generation_ = 0;
  bool stop_ = false;
};

}  // namespace

void run_workers(int n, const std::function<void(int)>& work) {
  if (n <= 1) {
    work(0);
    return;
  }
  thread_local WorkerPool pool;
  pool.run(n, work);
}

}  // namespace phonglab
