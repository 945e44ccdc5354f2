// thread_pool.hpp - a fixed set of worker threads that run index ranges; the calling thread works too.
#pragma once

#include <cstddef>
#include <memory>

namespace facet::detail {

class ThreadPool {
 public:
  // `threads` counts the calling thread: 1 (or 0) runs everything inline, n starts n - 1 workers.
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int size() const { return threads_; }

  // Calls body(index, thread) for every index in [0, count), each exactly once, spread over the threads, and
  // returns when all are done. `thread` is in [0, size()). Indices are handed out dynamically, so results must not
  // depend on which thread ran an index. The body is passed by reference: no allocation per call.
  template <class Body>
  void parallel_for(std::size_t count, Body&& body) {
    if (count == 0) return;
    if (threads_ <= 1 || count == 1) {
      for (std::size_t i = 0; i < count; ++i) body(i, 0);
      return;
    }
    run(
        count, [](void* context, std::size_t index, int thread) { (*static_cast<Body*>(context))(index, thread); },
        const_cast<void*>(static_cast<const void*>(&body)));
  }

 private:
  using Task = void (*)(void* context, std::size_t index, int thread);
  void run(std::size_t count, Task task, void* context);

  struct Shared;
  int threads_;
  std::unique_ptr<Shared> shared_;
};

}  // namespace facet::detail
