// A pool of threads kept for the whole run, for loops that split the work into many short phases
// (the evaluation engine runs two per window of rows, the vector reader two per block of input):
// starting threads for each phase, as parallel_for does, would cost more than a short phase's
// work. In io/, the lowest layer that works on threads.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace glint {

class ThreadPool {
 public:
  // `threads` workers in all, the caller's among them (1: everything on the caller's thread).
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int threads() const { return static_cast<int>(workers_.size()) + 1; }

  // How long a waiting thread spins before it sleeps.
  static constexpr std::chrono::microseconds kSpin{50};

  // Calls task(i) for i in [0, count), each exactly once, on the pool's threads and the caller's;
  // returns when all have returned. Tasks are handed out in index order. The first exception a
  // task throws is rethrown here once every task has stopped (the rest are not started).
  void run(std::size_t count, const std::function<void(std::size_t)>& task);

 private:
  void work_loop();
  void drain();

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(std::size_t)>* task_ = nullptr;
  std::size_t count_ = 0, next_ = 0, running_ = 0;
  std::uint64_t generation_ = 0;
  bool stop_ = false;
  // Mirrors of generation_ and of "every task of the run has returned", written under the mutex
  // and read without it by the spinning waits.
  std::atomic<std::uint64_t> published_{0};
  std::atomic<bool> finished_{true};
  std::chrono::nanoseconds done_spin_ = kSpin;  // the caller's spin budget (spin_until)
  std::exception_ptr error_;
};

}  // namespace glint
