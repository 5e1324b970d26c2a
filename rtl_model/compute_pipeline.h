// ComputePipeline: the compute unit of a lane, for every unit kind. It has L + 1 registers,
// L = SpecularUnit::timing().latency: position 0 is the input register (the comparator register of
// the compute path, written at the issue edge a_i), positions 1..L are the unit's stages, and
// position L drives `out`, which the merge buffer samples at the next edge (d_i = a_i + 1 + L,
// src/timing/timing.h). Requests move one position per cycle and never stall (their merge-buffer
// slot was reserved by the credit taken at issue).
//
// Initiation interval II = timing().ii: after starting a request at edge a the unit's registered
// `ready` is low for the edges a + 1 .. a + II - 1 (II = 1: always ready). The comparator issues a
// computed request only when `ready` is high.
//
// The result is SpecularUnit::eval(slot, t_raw), called when the request reaches the output
// register: the module holds timing and tracing only. The stages and their registers are the
// unit's own layout (SpecularUnit::stages()); when tracing, each stage shows the register values
// of the request it holds, from SpecularUnit::eval_staged (computed once, at issue), with the
// request's t and stream index; a stage spanning several positions (an iterative block such as
// the radix-2 divider loop, one request for II cycles) also traces its iteration `bit`.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <systemc>
#include <vector>

#include "rtl_model/rtl_common.h"
#include "units/unit.h"

namespace glint::rtl {

class ComputePipeline : public sc_core::sc_module, public Traceable, public ClockedStage {
 public:
  In<bool> in_valid;       // comparator: start a request at this edge
  In<Request> in_request;  // the source's request register
  Register<bool> ready;    // registered II gate
  Register<Result> out;    // output register (position L)

  ComputePipeline(sc_core::sc_module_name name, const SpecularUnit& unit, bool tracing);

  int latency() const { return latency_; }
  int ii() const { return ii_; }
  const StageLayout& layout() const { return layout_; }
  std::uint64_t started() const { return started_; }
  // Requests offered while the II gate was closed (protocol violations; always 0 when driven by
  // TauComparator).
  std::uint64_t violations() const { return violations_; }

  void add_traces(VcdWriter& vcd, const std::string& prefix) const override;
  void tick() override;

 private:
  struct Entry {
    bool valid = false;
    std::uint64_t issue = 0;
    Request request;
    std::vector<std::int64_t> staged;  // the unit's register values (tracing only)
  };
  struct StageTrace {
    StageTrace(const Stage& s, const QFormat& in, int bit_width);
    bool valid = false;
    RawBits t, seq, bit;
    std::vector<RawBits> registers;
  };

  void update_traces(std::size_t head);

  const SpecularUnit& unit_;
  const int latency_, ii_;
  const std::size_t depth_;  // L + 1
  const StageLayout& layout_;
  const bool tracing_;
  std::vector<Entry> ring_;  // position p at edge c lives in ring_[(c - p) mod depth]
  std::size_t head_ = 0;     // c mod depth for the coming edge c
  std::uint64_t cycle_ = 0;
  int busy_ = 0;  // edges left with the II gate closed
  bool out_active_ = false;
  std::uint64_t started_ = 0, violations_ = 0;
  std::vector<std::unique_ptr<StageTrace>> traces_;
};

}  // namespace glint::rtl
