// TauComparator: Källberg's early-out in front of the compute unit, and the lane's issue logic.
//
// Combinational part (re-evaluated whenever its inputs settle after an edge): skip = t <= tau[slot]
// (tau_skip, the datapath comparator, with the per-slot thresholds SpecularUnit::tau_raw), and the
// issue condition for the next edge
//     ready = credit available && (skip || compute unit ready),
// where a credit is available when the counter is non-zero or the merge buffer returned one at the
// previous edge (a credit freed at retire cycle r is usable at r + 1), and the compute unit's
// ready is its registered II gate. `ready` goes to the source; `compute_valid` (valid && ready &&
// !skip) starts the compute unit, whose input register is the comparator register of the compute
// path.
//
// Clocked part, at an edge where valid && ready ("issue", cycle a_i of src/timing.h): take a
// credit; a skipped request goes into the bypass register (result eval_with_skip = 0, done at a_i +
// 1). Cycles in which a request is held count as stalls, all of one request's held cycles charged
// to the credit when the credit still blocked in its last held cycle, else to the compute unit --
// the attribution rule of TimingEngine (credit constraint >= unit constraint).
#pragma once

#include <cstdint>
#include <string>
#include <systemc>
#include <vector>

#include "rtl_model/rtl_common.h"
#include "units/catalogue.h"

namespace glint::rtl {

class TauComparator : public sc_core::sc_module,
                      public Traceable,
                      public ClockedStage,
                      public Combinational {
 public:
  In<bool> src_valid;
  In<Request> src_request;
  In<bool> unit_ready;     // compute unit can start a request at this edge
  In<bool> credit_return;  // merge buffer retired a result at the previous edge

  Register<bool> src_ready;      // combinational: the request issues at this edge
  Register<bool> compute_valid;  // combinational: it issues to the compute unit
  Register<Result> bypass;       // bypass register: skipped requests

  SC_HAS_PROCESS(TauComparator);
  // `comb`: kSettledByClock (a lane) needs every input bound to a Register; settle() is then the
  // caller's, after each edge's ticks and once before the first edge.
  TauComparator(sc_core::sc_module_name name, const SpecularUnit& unit, int credits, bool tracing,
                CombMode comb = CombMode::kOwnProcess);

  const std::vector<std::int64_t>& tau_table() const { return tau_; }
  std::uint64_t stall_credit() const { return stall_credit_; }
  std::uint64_t stall_unit() const { return stall_unit_; }
  std::uint64_t issued() const { return issued_; }
  int credits() const { return credits_; }

  void add_traces(VcdWriter& vcd, const std::string& prefix) const override;
  void tick() override;
  void settle() override;

 private:
  void end_of_elaboration() override;

  const SpecularUnit& unit_;
  std::vector<std::int64_t> tau_;
  const bool tracing_;
  const CombMode comb_mode_;
  int credits_;
  sc_core::sc_event credits_changed_;  // kOwnProcess: the credit counter is an input of settle()

  // Decided by comb() for the coming edge.
  bool skip_ = false;
  bool credit_ok_ = true;

  std::uint64_t cycle_ = 0;
  std::uint64_t issued_ = 0;
  std::uint64_t held_ = 0;  // cycles the presented request has been held so far
  bool held_by_credit_ = false;
  std::uint64_t stall_credit_ = 0, stall_unit_ = 0;
  bool bypass_active_ = false;

  // Trace mirrors.
  RawBits tau_trace_, credits_trace_, bypass_t_trace_, bypass_result_trace_;
  RawBits bypass_seq_trace_{32, false};  // the request id, as the source and every stage show it
  bool skip_trace_ = false, issue_trace_ = false, stall_trace_ = false, bypass_valid_trace_ = false;
};

}  // namespace glint::rtl
