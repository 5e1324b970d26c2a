// Testbench control shared by the lanes of one clocked run (not hardware): errors raised inside
// processes, the end of the run, and the VCD window. Header-only; one instance per run_clocked.
#pragma once

#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <limits>
#include <systemc>

namespace glint::rtl {

class SimControl {
 public:
  static constexpr std::uint64_t kNever = std::numeric_limits<std::uint64_t>::max();

  // An exception thrown inside a process (the row stream, the result callback): the first one is
  // kept, the simulation stops, and run_clocked rethrows it after sc_start returns.
  void fail(std::exception_ptr e) {
    if (!error_) error_ = e;
    stop();
  }
  std::exception_ptr error() const { return error_; }

  // sc_stop once (a second call prints a SystemC warning).
  void stop() {
    if (stopped_) return;
    stopped_ = true;
    sc_core::sc_stop();
  }
  bool stopped() const { return stopped_; }

  // Lanes still running; the run ends one cycle after the last lane retired its last result (so
  // that cycle is traced completely).
  void set_lanes(std::size_t n) { lanes_running_ = n; }
  void lane_done(std::uint64_t cycle) {
    if (lanes_running_ > 0 && --lanes_running_ == 0) done_cycle_ = cycle;
  }
  bool all_done() const { return lanes_running_ == 0; }
  std::uint64_t done_cycle() const { return done_cycle_; }

  // VCD window [first, last] of vector indices. open_window is called (once) when a source presents
  // vector `first`; the window closes one cycle after every lane retired vector `last` (or its
  // stream's last vector).
  void set_window(std::uint64_t first, std::uint64_t last, std::size_t lanes,
                  std::function<void()> open, std::function<void()> close) {
    window_first_ = first;
    window_last_ = last;
    lanes_before_close_ = lanes;
    open_ = std::move(open);
    close_ = std::move(close);
  }
  bool tracing_requested() const { return static_cast<bool>(open_); }
  std::uint64_t window_first() const { return window_first_; }
  std::uint64_t window_last() const { return window_last_; }
  void on_present(std::uint64_t seq) {
    if (seq != window_first_ || window_opened_ || !open_) return;
    if (hold_) {
      pending_open_ = true;
    } else {
      open_window();
    }
  }
  // While held (elaboration: sources present vector 0 before every module exists), an opening is
  // deferred until the hold is released.
  void hold_window(bool hold) {
    hold_ = hold;
    if (!hold_ && pending_open_) {
      pending_open_ = false;
      open_window();
    }
  }
  void open_window() {
    if (window_opened_ || !open_) return;
    window_opened_ = true;
    open_();
  }
  bool window_opened() const { return window_opened_; }
  // A lane has retired the window's last vector (or finished).
  void lane_past_window(std::uint64_t cycle) {
    if (lanes_before_close_ > 0 && --lanes_before_close_ == 0) close_after_ = cycle;
  }
  // Called by the top-level clock process at every edge.
  void on_edge(std::uint64_t cycle) {
    if (close_after_ != kNever && cycle > close_after_ && window_opened_ && !window_closed_) {
      window_closed_ = true;
      close_();
    }
    if (all_done() && cycle > done_cycle_) {
      if (!window_opened_ && open_) {
        // A window that no vector reached still yields a VCD: the final state, traced through the
        // next edge (its initial dump is sampled once this cycle's values have settled).
        open_window();
        return;
      }
      stop();
    }
  }

 private:
  std::exception_ptr error_;
  bool stopped_ = false;
  std::size_t lanes_running_ = 0;
  std::uint64_t done_cycle_ = 0;
  std::uint64_t window_first_ = kNever, window_last_ = kNever;
  std::size_t lanes_before_close_ = 0;
  std::uint64_t close_after_ = kNever;
  bool window_opened_ = false, window_closed_ = false;
  bool hold_ = false, pending_open_ = false;
  std::function<void()> open_, close_;
};

}  // namespace glint::rtl
