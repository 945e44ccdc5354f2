// thread_pool.cpp - workers that spin briefly, then sleep, between jobs and pull indices from one atomic counter.
#include "core/thread_pool.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace facet::detail {

namespace {

// Waits for `ready` by spinning for a few tens of microseconds before the caller falls back to sleeping on a
// condition variable. A frame runs several short jobs back to back (vertices, setup, tiles, per batch); waking a
// sleeping thread costs a futex round trip of 10-100 us on a virtual machine, which would otherwise be paid at
// every job boundary. Returns false when the budget ran out first.
template <class Ready>
bool spin_until(Ready&& ready) {
  constexpr auto kBudget = std::chrono::microseconds(40);
  const auto start = std::chrono::steady_clock::now();
  for (int i = 1;; ++i) {
    if (ready()) return true;
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
    if (i % 64 == 0 && std::chrono::steady_clock::now() - start > kBudget) return ready();
  }
}

}  // namespace

struct ThreadPool::Shared {
  std::mutex mutex;
  std::condition_variable wake, done;
  // Written under the mutex (so sleepers cannot miss a change) and read without it while spinning.
  std::atomic<std::uint64_t> generation{0};  // bumped per job; a worker runs each generation once
  std::atomic<bool> stopping{false};
  Task task = nullptr;
  void* context = nullptr;
  std::size_t count = 0;
  std::atomic<std::size_t> next{0};
  std::atomic<int> busy_workers{0};
  std::vector<std::thread> workers;

  void work(int thread) {
    for (std::size_t i = next.fetch_add(1, std::memory_order_relaxed); i < count;
         i = next.fetch_add(1, std::memory_order_relaxed))
      task(context, i, thread);
  }

  void worker_loop(int thread) {
    std::uint64_t seen = 0;
    const auto has_work = [&] {
      return stopping.load(std::memory_order_acquire) || generation.load(std::memory_order_acquire) != seen;
    };
    for (;;) {
      if (!spin_until(has_work)) {
        std::unique_lock lock(mutex);
        wake.wait(lock, has_work);
      }
      if (stopping.load(std::memory_order_acquire)) return;
      seen = generation.load(std::memory_order_acquire);
      work(thread);
      if (busy_workers.fetch_sub(1, std::memory_order_acq_rel) == 1) {
        std::lock_guard lock(mutex);
        done.notify_one();
      }
    }
  }
};

ThreadPool::ThreadPool(int threads) : threads_(std::max(1, threads)), shared_(std::make_unique<Shared>()) {
  for (int t = 1; t < threads_; ++t) shared_->workers.emplace_back([this, t] { shared_->worker_loop(t); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard lock(shared_->mutex);
    shared_->stopping.store(true, std::memory_order_release);
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
    s.busy_workers.store(static_cast<int>(s.workers.size()), std::memory_order_relaxed);
    s.generation.fetch_add(1, std::memory_order_release);
  }
  s.wake.notify_all();
  s.work(0);
  const auto all_done = [&] { return s.busy_workers.load(std::memory_order_acquire) == 0; };
  if (spin_until(all_done)) return;
  std::unique_lock lock(s.mutex);
  s.done.wait(lock, all_done);
}

}  // namespace facet::detail
