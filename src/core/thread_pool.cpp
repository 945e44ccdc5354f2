// thread_pool.cpp - workers that sleep between jobs and pull indices from one atomic counter.
#include "facet/detail/thread_pool.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace facet::detail {

struct ThreadPool::Shared {
  std::mutex mutex;
  std::condition_variable wake, done;
  std::uint64_t generation = 0;  // bumped per job; a worker runs each generation once
  bool stopping = false;
  Task task = nullptr;
  void* context = nullptr;
  std::size_t count = 0;
  std::atomic<std::size_t> next{0};
  int busy_workers = 0;
  std::vector<std::thread> workers;

  void work(int thread) {
    for (std::size_t i = next.fetch_add(1, std::memory_order_relaxed); i < count;
         i = next.fetch_add(1, std::memory_order_relaxed))
      task(context, i, thread);
  }

  void worker_loop(int thread) {
    std::uint64_t seen = 0;
    for (;;) {
      {
        std::unique_lock lock(mutex);
        wake.wait(lock, [&] { return stopping || generation != seen; });
        if (stopping) return;
        seen = generation;
      }
      work(thread);
      std::lock_guard lock(mutex);
      if (--busy_workers == 0) done.notify_one();
    }
  }
};

ThreadPool::ThreadPool(int threads) : threads_(std::max(1, threads)), shared_(std::make_unique<Shared>()) {
  for (int t = 1; t < threads_; ++t) shared_->workers.emplace_back([this, t] { shared_->worker_loop(t); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard lock(shared_->mutex);
    shared_->stopping = true;
  }
  shared_->wake.notify_all();
  for (std::thread& w : shared_->workers) w.join();
}

void ThreadPool::run(std::size_t count, Task task, void* context) {
  Shared& s = *shared_;
  {
    std::lock_guard lock(s.mutex);
    s.task = task;
    s.context = context;
    s.count = count;
    s.next.store(0, std::memory_order_relaxed);
    s.busy_workers = static_cast<int>(s.workers.size());
    ++s.generation;
  }
  s.wake.notify_all();
  s.work(0);
  std::unique_lock lock(s.mutex);
  s.done.wait(lock, [&] { return s.busy_workers == 0; });
}

}  // namespace facet::detail
