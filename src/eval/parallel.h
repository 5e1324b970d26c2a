// Runs independent tasks on a few threads. Each task writes only its own outputs, so results do
// not depend on the thread count or on scheduling: that is what keeps glint's batch evaluation
// and rendering bit-identical for any --threads.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace glint {

// Calls task(i) for i in [0, count) on up to `threads` threads (the caller's among them). The
// first exception a task throws is rethrown here after every thread has stopped.
template <class Task>
void parallel_for(std::size_t count, int threads, const Task& task) {
  const std::size_t workers = std::min<std::size_t>(count, threads > 1 ? threads : 1);
  if (workers <= 1) {
    for (std::size_t i = 0; i < count; ++i) task(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  const auto work = [&] {
    for (std::size_t i = next++; i < count; i = next++) {
      try {
        task(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = count;
      }
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

// The number of threads to use by default: the machine's, at least 1.
inline int default_threads() {
  const unsigned n = std::thread::hardware_concurrency();
  return n > 0 ? static_cast<int>(n) : 1;
}

}  // namespace glint
