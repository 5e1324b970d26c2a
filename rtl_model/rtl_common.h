// What every clocked module of the specular lane shares: the clock, the payloads that travel on its
// handshake channels, and the trace helpers (raw fixed-point bits at their true, runtime width).
//
// Clocking convention (the one src/timing.h's recurrences are written in): every module's registers
// are its tick() (ClockedStage), called at each rising edge; cycle c is the c-th rising edge after
// the start of simulation, counted from 0, at time 5 ns + c * 10 ns (so a VCD shows the reset state
// before cycle 0). Each module counts the edges it has seen, so its own counter equals the cycle
// number in every process. A
// transfer on a valid/ready channel happens at edge c when valid and ready are both 1 just before
// it (the signal values visible to processes at edge c); a register written at edge c is visible
// from edge c + 1.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <systemc>
#include <vector>

#include "io/vcd_writer.h"

namespace glint::rtl {

// Cycle c is the rising edge at clock_first_edge() + c * clock_period(): (t_ns - 5) / 10.
inline sc_core::sc_time clock_period() {
  return sc_core::sc_time(10, sc_core::SC_NS);
}
inline sc_core::sc_time clock_first_edge() {
  return sc_core::sc_time(5, sc_core::SC_NS);
}
inline std::uint64_t cycle_time_ns(std::uint64_t cycle) {
  return 5 + 10 * cycle;
}
// The falling edge after cycle c (the clock is high for the first half of each period).
inline std::uint64_t fall_time_ns(std::uint64_t cycle) {
  return cycle_time_ns(cycle) + 5;
}
// The clock's level at time t_ns (low before the first edge).
inline bool clock_high_at_ns(std::uint64_t t_ns) {
  return t_ns >= 5 && (t_ns - 5) % 10 < 5;
}

// A shading request as the source presents it: the stream index, t in the unit's input format
// (quantize_input), the unit slot (SlotMap::slot) and whether it is the stream's last row.
struct Request {
  std::uint64_t seq = 0;
  std::int64_t t_raw = 0;
  std::uint32_t slot = 0;
  bool last = false;

  friend bool operator==(const Request& a, const Request& b) {
    return a.seq == b.seq && a.t_raw == b.t_raw && a.slot == b.slot && a.last == b.last;
  }
};

// A result on its way to the sink (bypass register, compute output, merge head). `issue` and `done`
// are cycle stamps carried for the scoreboard (testbench sideband, not hardware): issue is stamped
// by the comparator / compute input register, done by the merge buffer when the result arrives.
struct Result {
  bool valid = false;
  bool skipped = false;
  bool last = false;
  std::uint32_t slot = 0;
  std::uint64_t seq = 0;
  std::int64_t t_raw = 0;
  std::int64_t value = 0;  // out_raw, from the datapath function
  std::uint64_t issue = 0;
  std::uint64_t done = 0;

  // sc_signal::write compares every value it is given with the last. The stream index first: it
  // differs whenever the value does in a running lane, and it is a whole word, where the flags'
  // bytes, just stored one by one, would be read back as one word (a store-forwarding stall that
  // cost ~5 % of a clocked run in the comparator's bypass write alone).
  friend bool operator==(const Result& a, const Result& b) {
    return a.seq == b.seq && a.valid == b.valid && a.skipped == b.skipped && a.last == b.last &&
           a.slot == b.slot && a.t_raw == b.t_raw && a.value == b.value && a.issue == b.issue &&
           a.done == b.done;
  }
};

std::ostream& operator<<(std::ostream& os, const Request& r);
std::ostream& operator<<(std::ostream& os, const Result& r);

// sc_signal<T> wants an sc_trace overload for its payload; the payloads are traced field by field
// through RawBits mirrors instead (true widths, VcdWriter), so these add nothing.
inline void sc_trace(sc_core::sc_trace_file*, const Request&, const std::string&) {}
inline void sc_trace(sc_core::sc_trace_file*, const Result&, const std::string&) {}

// A raw fixed-point (or integer) value traced with its true bit width, known only at run time:
// the VCD declares exactly `width` bits. Signed formats are kept as two's complement of `width`
// bits. Updated by the process that owns the register; VcdWriter reads it once per cycle.
class RawBits {
 public:
  RawBits(int width, bool is_signed)
      : width_(width),
        is_signed_(is_signed),
        mask_(width >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << width) - 1) {}
  void set(std::int64_t raw) { bits_ = static_cast<std::uint64_t>(raw) & mask_; }
  // set(raw) when `cond` (branch-free: for values that change with an unpredictable valid bit).
  void set_if(bool cond, std::int64_t raw) {
    const std::uint64_t v = static_cast<std::uint64_t>(raw) & mask_;
    bits_ = cond ? v : bits_;
  }
  const std::uint64_t& bits() const { return bits_; }
  int width() const { return width_; }
  bool is_signed() const { return is_signed_; }

 private:
  int width_;
  bool is_signed_;
  std::uint64_t mask_;
  std::uint64_t bits_ = 0;
};

// Bits needed to hold values 0..max_value (at least 1).
inline int bits_for(std::uint64_t max_value) {
  int b = 1;
  while (b < 64 && (max_value >> b) != 0) ++b;
  return b;
}

// The traced signals of one module. Every module implements it; TraceControl (vcd_trace.h) calls
// add_traces once when it opens the VCD file.
// A module's registers: tick() is its rising edge. It reads only signals (their values before the
// edge: writes land in SystemC's update phase) and the module's own state, so the ticks of one edge
// may run in any order, and they run in one process: the clock's (clocked_sim.cpp's Top::edge, or a
// test's driver). One SC_METHOD per register stage on an sc_clock's edge costs the kernel an event
// fan-out and a process switch per module per cycle; calling them in one activation halves the
// clocked mode's kernel work and changes no value or cycle.
class ClockedStage {
 public:
  virtual ~ClockedStage() = default;
  virtual void tick() = 0;
};

// The combinational part of a module whose inputs are all registers (the comparator's issue
// decision, the merge buffer's head). In a lane it is settled by the clock's process right after
// the edge's ticks, reading the registers' new values (Register::next), instead of as an SC_METHOD
// sensitive to its inputs: one process activation per cycle and no delta cycles (with those, the
// SystemC kernel's share of a clocked run was ~45 %; without, ~35 %: the clock's timed event and
// the signals' update phase). Its values are the same: a function of the registers after the
// edge, settled before anything reads them (the next edge's ticks, the VCD sample at the falling
// edge).
class Combinational {
 public:
  virtual ~Combinational() = default;
  virtual void settle() = 0;
};

// How a module's combinational part is evaluated: its own SC_METHOD on its inputs (a module driven
// alone, as the module tests do), or settle() called by the clock's process (a lane).
enum class CombMode { kOwnProcess, kSettledByClock };

// A module's output signal: an sc_signal whose value written in this evaluation phase (a register's
// new value, before the update phase makes it current) can be read: next(). After the update, and
// when nothing was written, next() equals read(). Non-virtual reads (current() and next()) are for
// the In ports below.
template <class T>
class Register : public sc_core::sc_signal<T> {
 public:
  using sc_core::sc_signal<T>::sc_signal;
  const T& current() const { return this->m_cur_val; }
  const T& next() const { return this->m_new_val; }
};

// An input port that, when bound to a Register (every channel of a lane), reads it without the
// kernel's virtual read through the port (~5 % of a clocked run for the bool ports alone):
// now() is the value before the edge (what a tick reads), settled() the value after this edge's
// ticks (what a Combinational::settle reads). Bound to a plain sc_signal (a module test's driver),
// both read through the port.
template <class T>
class In : public sc_core::sc_in<T> {
 public:
  using sc_core::sc_in<T>::sc_in;
  const T& now() const { return reg_ ? reg_->current() : this->read(); }
  const T& settled() const { return reg_ ? reg_->next() : this->read(); }
  void end_of_elaboration() override {
    sc_core::sc_in<T>::end_of_elaboration();
    reg_ = dynamic_cast<const Register<T>*>(this->get_interface());
  }
  // Bound to a Register (valid from the end of elaboration): settled() reads the new value.
  bool bound_to_register() const { return reg_ != nullptr; }

 private:
  const Register<T>* reg_ = nullptr;
};

class Traceable {
 public:
  virtual ~Traceable() = default;
  // Registers this module's signals and mirrors under `prefix` (e.g. "top.hast").
  virtual void add_traces(VcdWriter& vcd, const std::string& prefix) const = 0;
};

// Helpers for add_traces implementations. Every traced value is a plain memory location the writer
// samples: a mirror, or the current value of an sc_signal<bool> (read() returns a reference to it).
inline void trace_bool(VcdWriter& vcd, const bool& v, const std::string& name) {
  vcd.add_bool(v, name);
}
inline void trace_bool(VcdWriter& vcd, const sc_core::sc_signal<bool>& v, const std::string& name) {
  vcd.add_bool(v.read(), name);
}
// An input port traces the signal it is bound to.
inline void trace_port(VcdWriter& vcd, const sc_core::sc_in<bool>& port, const std::string& name) {
  vcd.add_bool(port->read(), name);
}
// `frac_bits`: the fraction bits of the value's fixed-point format (QFormat::frac_bits; 0 for
// integers such as counters and indices). The VCD keeps the raw bits; the GTKWave save file shows
// raw * 2^-frac_bits.
inline void trace_raw(VcdWriter& vcd, const RawBits& v, const std::string& name,
                      int frac_bits = 0) {
  vcd.add_bits(v.bits(), v.width(), v.is_signed(), name, frac_bits);
}

}  // namespace glint::rtl
