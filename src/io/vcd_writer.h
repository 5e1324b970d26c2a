// A fast VCD writer for values that live in plain memory (the clocked model's trace mirrors and the
// current values of its sc_signal<bool>s), sampled by the caller once per clock cycle.
//
// SystemC's own writer (sc_create_vcd_trace_file) formats every value change with sprintf/fprintf
// and every time stamp through a std::stringstream, which made it ~95% of a traced run. This one
// compares each registered value with the one last written and formats the changes with table
// lookups into a large buffer written out with fwrite. It knows nothing of SystemC: the caller
// decides when to sample (TraceControl in vcd_trace.h, at every falling clock edge).
//
// The file is IEEE 1364 VCD: every '.' of a registered name opens a $scope level below the root
// scope (scopes and variables in registration order), widths are declared exactly, values are
// written as binary vectors without leading zeros ("b101 id", 0-extended by readers) and 1-bit
// values in scalar form ("1id"). A clock variable is driven by clock() instead of being sampled.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "io/vcd_tally.h"

namespace glint::rtl {

// One traced signal as the GTKWave save file lists it.
struct TracedSignal {
  std::string name;  // hierarchical, e.g. "top.hast.in.t"
  int width = 1;
  bool is_signed = false;
  // Fraction bits of the fixed-point format the raw bits hold (value = raw * 2^-frac_bits); 0 for
  // integers and handshakes. Not in the VCD (which holds raw bits): the save file uses it to show
  // real values.
  int frac_bits = 0;
};

class VcdWriter {
 public:
  // `root_scope` (may be empty: none) encloses every name.
  explicit VcdWriter(std::string root_scope);
  ~VcdWriter();  // closes the file if still open (without reporting errors)

  VcdWriter(const VcdWriter&) = delete;
  VcdWriter& operator=(const VcdWriter&) = delete;

  // Declarations, before header(). Names are hierarchical ("top.hast.in.t"): non-empty
  // components without white space; throws std::invalid_argument otherwise or for a repeated
  // name. The referenced values must stay valid until close().
  void add_clock(const std::string& name);  // 1 bit, written by clock(); at most one
  void add_bool(const bool& value, const std::string& name);
  // `value` holds the raw bits in its low `width` bits (1..64); higher bits are ignored, so a
  // signed value may be stored as its two's complement. `is_signed` and `frac_bits` (the
  // fixed-point format's fraction bits, 0 = integer) are for viewers only (TracedSignal).
  void add_bits(const std::uint64_t& value, int width, bool is_signed, const std::string& name,
                int frac_bits = 0);
  const std::vector<TracedSignal>& signals() const { return signals_; }

  // Takes ownership of `file` (opened for writing; closed by close() or the destructor). A `pipe`
  // (another process reads it, e.g. vcd2fst) is written unbuffered by stdio and with SIGPIPE
  // blocked, so a reader that died makes the writes fail (close() returns false) instead of
  // killing this process.
  void open(std::FILE* file, bool pipe = false);
  // Counts what is written from now on (VcdTally): what a converted copy must hold. Off by
  // default (it reads every byte once more); call after open().
  void tally() { tally_ = std::make_unique<VcdTally>(); }
  // The counts of what was written (before close(): of what was flushed); zero without tally().
  VcdCounts counts() const { return tally_ ? tally_->counts() : VcdCounts{}; }
  bool is_open() const { return file_ != nullptr; }
  // $date, $version, $timescale (1 `timescale_unit`, e.g. "ns"), the scopes and variables.
  void header(const std::string& timescale_unit, const std::string& version);

  // "#time" (times must increase; an equal time is not repeated).
  void time(std::uint64_t t);
  // $dumpvars at `t`: every value, the clock at `clock_level`.
  void dump_all(std::uint64_t t, bool clock_level);
  // The clock's value change (nothing when it already has this level).
  void clock(bool level);
  // Every sampled value that differs from the one last written, under the current time.
  void changes();

  std::uint64_t last_time() const { return last_time_; }
  bool wrote_time() const { return wrote_time_; }
  std::uint64_t bytes_written() const { return flushed_ + pos_; }

  // Writes "#end_time" when it is later than the last time, flushes and closes. Returns false if
  // any write (or the close) failed.
  bool close(std::uint64_t end_time);
  // The errno of the first failed write (or close), 0 if none.
  int error() const { return error_; }

 private:
  struct Var {
    char id[8] = {};  // identifier code followed by '\n'
    std::uint8_t id_len = 0;
    std::uint8_t width = 1;
  };
  struct BoolVar {
    const bool* value;
    bool last;
    Var var;
  };
  struct BitsVar {
    const std::uint64_t* value;
    std::uint64_t mask;
    std::uint64_t last;
    Var var;
  };

  void check_name(const std::string& name);
  void fail(int err) {
    if (!failed_) error_ = err;
    failed_ = true;
  }
  Var next_var(int width);
  void reserve(std::size_t bytes);  // room for `bytes` more in the buffer (flushes if needed)
  void flush();
  void put(const char* s, std::size_t n);
  void put(const std::string& s) { put(s.data(), s.size()); }
  static char* put_id(char* p, const Var& v);
  static char* put_bool(char* p, bool value, const Var& v);
  static char* put_bits(char* p, std::uint64_t value, const Var& v);

  std::string root_;
  std::vector<TracedSignal> signals_;
  std::vector<std::size_t> order_;  // per signal: index into bools_ / bits_ (see is_bool_)
  std::vector<bool> is_bool_;
  std::vector<BoolVar> bools_;
  std::vector<BitsVar> bits_;
  bool has_clock_ = false, clock_level_ = false;
  Var clock_var_;
  std::size_t next_id_ = 0;
  std::size_t max_changes_bytes_ = 0;  // bound on what one changes() writes

  bool header_done_ = false;
  std::FILE* file_ = nullptr;
  bool pipe_ = false;
  bool failed_ = false;
  int error_ = 0;
  std::unique_ptr<char[]> buffer_;
  std::size_t capacity_ = 0, pos_ = 0;
  std::uint64_t flushed_ = 0;
  std::uint64_t last_time_ = 0;
  bool wrote_time_ = false;
  std::unique_ptr<VcdTally> tally_;
};

}  // namespace glint::rtl
