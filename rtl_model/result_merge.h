// ResultMerge: the in-order merge of bypassed and computed results, a buffer of B entries.
//
// A result arrives at edge d_i (its bypass or output register was written at d_i - 1) and is kept
// in the entry of its stream index modulo B; the comparator's credits (one per entry, returned
// through `credit_return` at the edge after the retire) guarantee an entry is free, so the buffer
// never overflows and the lane stalls at issue instead when it is full.
//
// The head (the oldest unretired result, in stream order) is combinational: the stored entry, or
// the result arriving at the coming edge (flow-through), so a result can retire at its done cycle.
// It retires at an edge where head_valid && sink ready.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <systemc>
#include <vector>

#include "rtl_model/rtl_common.h"

namespace glint::rtl {

class ResultMerge : public sc_core::sc_module,
                    public Traceable,
                    public ClockedStage,
                    public Combinational {
 public:
  In<Result> bypass_in;
  In<Result> compute_in;
  In<bool> sink_ready;

  Register<bool> head_valid;     // combinational
  Register<Result> head;         // combinational (meaningful when head_valid)
  Register<bool> credit_return;  // registered: retired at the previous edge

  SC_HAS_PROCESS(ResultMerge);
  // `out_frac_bits`: the result format's fraction bits, for the trace's real-valued display only.
  // `comb`: as TauComparator's (kSettledByClock: the inputs are Registers, settle() the caller's).
  ResultMerge(sc_core::sc_module_name name, int depth, int out_width, bool out_signed, bool tracing,
              int out_frac_bits = 0, CombMode comb = CombMode::kOwnProcess);

  int depth() const { return static_cast<int>(entries_.size()); }
  std::size_t occupancy() const { return count_; }
  std::size_t max_occupancy() const { return max_count_; }
  std::uint64_t overflows() const { return overflows_; }  // always 0 with credit flow control
  std::uint64_t retired() const { return next_seq_; }

  void add_traces(VcdWriter& vcd, const std::string& prefix) const override;
  void tick() override;
  void settle() override;

 private:
  void end_of_elaboration() override;

  // The entry of stream index `seq`: seq mod B, from the head's entry when seq is within B of the
  // head (always, with credits), so the buffer's lookups, up to three a cycle, need no division.
  std::size_t entry_of(std::uint64_t seq) const {
    const std::uint64_t ahead = seq - next_seq_;
    const std::size_t n = entries_.size();
    if (ahead >= n) return static_cast<std::size_t>(seq % n);
    const std::size_t e = head_entry_ + static_cast<std::size_t>(ahead);
    return e >= n ? e - n : e;
  }

  std::vector<Result> entries_;
  std::uint64_t next_seq_ = 0;  // stream index of the head
  std::size_t head_entry_ = 0;  // next_seq_ mod B
  std::size_t count_ = 0, max_count_ = 0;
  std::uint64_t overflows_ = 0;
  std::uint64_t cycle_ = 0;
  bool credit_active_ = false;
  sc_core::sc_event changed_;  // kOwnProcess: the entries are an input of settle()
  const bool tracing_;
  const CombMode comb_mode_;
  const int out_frac_bits_;
  RawBits result_trace_, count_trace_;
  RawBits seq_trace_{32, false};  // the head's request id
};

}  // namespace glint::rtl
