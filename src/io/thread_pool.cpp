#include "io/thread_pool.h"

#include <algorithm>
#include <cstdint>

namespace glint {
namespace {

void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

// Spins until done() or `budget` has passed; the caller then takes the mutex and waits as before
// (the condition is checked again there, so a spin that gives up only costs its time). The budget
// adapts to the waits of its site: kSpin again after a wait that the spin ended, half as long after
// one it did not (down to kMinSpin): a pool whose runs are far apart, such as the vector reader's
// beside the engine's, then stops spinning on the cores the other pool needs.
constexpr std::chrono::nanoseconds kMinSpin{1000};

template <class Done>
void spin_until(const Done& done, std::chrono::nanoseconds& budget) {
  const auto start = std::chrono::steady_clock::now();
  for (unsigned i = 1; !done(); ++i) {
    cpu_relax();
    if (i % 64 == 0 && std::chrono::steady_clock::now() - start >= budget) {
      budget = std::max(kMinSpin, budget / 2);
      return;
    }
  }
  budget = ThreadPool::kSpin;
}

}  // namespace

ThreadPool::ThreadPool(int threads) {
  for (int i = 1; i < threads; ++i) workers_.emplace_back([this] { work_loop(); });
}

ThreadPool::~ThreadPool() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    published_.fetch_add(1, std::memory_order_release);
  }
  wake_.notify_all();
  for (std::thread& t : workers_) t.join();
}

// Takes tasks until none is left. Called with the mutex unlocked.
void ThreadPool::drain() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (next_ < count_) {
    const std::size_t i = next_++;
    ++running_;
    lock.unlock();
    try {
      (*task_)(i);
    } catch (...) {
      lock.lock();
      if (!error_) error_ = std::current_exception();
      next_ = count_;
      lock.unlock();
    }
    lock.lock();
    --running_;
  }
  if (running_ == 0) {
    finished_.store(true, std::memory_order_release);
    done_.notify_all();
  }
}

void ThreadPool::work_loop() {
  std::uint64_t seen = 0;
  std::chrono::nanoseconds budget = kSpin;
  for (;;) {
    spin_until([&] { return published_.load(std::memory_order_acquire) != seen; }, budget);
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
    }
    drain();
  }
}

void ThreadPool::run(std::size_t count, const std::function<void(std::size_t)>& task) {
  if (workers_.empty() || count <= 1) {
    for (std::size_t i = 0; i < count; ++i) task(i);
    return;
  }
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    task_ = &task;
    count_ = count;
    next_ = 0;
    running_ = 0;
    error_ = nullptr;
    ++generation_;
    finished_.store(false, std::memory_order_relaxed);
    published_.store(generation_, std::memory_order_release);
  }
  wake_.notify_all();
  drain();
  spin_until([&] { return finished_.load(std::memory_order_acquire); }, done_spin_);
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [&] { return next_ >= count_ && running_ == 0; });
  task_ = nullptr;
  count_ = 0;
  if (error_) {
    std::exception_ptr e = error_;
    error_ = nullptr;
    lock.unlock();
    std::rethrow_exception(e);
  }
}

}  // namespace glint
