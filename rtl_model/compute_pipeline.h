// ComputePipeline: the generic compute unit every datapath's module is built on. It has L + 1
// registers, L = SpecularUnit::timing().latency: position 0 is the input register (the comparator
// register of the compute path, written at the issue edge a_i), positions 1..L are the unit's
// stages, and position L drives `out`, which the merge buffer samples at the next edge
// (d_i = a_i + 1 + L, src/timing.h). Requests move one position per cycle and never stall (their
// merge-buffer slot was reserved by the credit taken at issue).
//
// Initiation interval II = timing().ii: after starting a request at edge a the unit's registered
// `ready` is low for the edges a + 1 .. a + II - 1 (II = 1: always ready). The comparator issues a
// computed request only when `ready` is high.
//
// The result is SpecularUnit::eval(slot, t_raw), called when the request reaches the output
// register: the module holds timing and tracing only. Named stages (StageSpec) map positions to
// the hardware's parts for the VCD; a stage may span several positions (an iterative block such
// as the radix-2 divider loop, one request for II cycles), and then traces its iteration `bit`.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <systemc>
#include <vector>

#include "rtl_model/rtl_common.h"
#include "units/catalogue.h"

namespace glint::rtl {

struct StageSpec {
  std::string name;
  int first = 0;  // register positions [first, last], 0 = input register, L = output register
  int last = 0;
};

class ComputePipeline : public sc_core::sc_module, public Traceable {
 public:
  sc_core::sc_in<bool> clk;
  sc_core::sc_in<bool> in_valid;       // comparator: start a request at this edge
  sc_core::sc_in<Request> in_request;  // the source's request register
  sc_core::sc_signal<bool> ready;      // registered II gate
  sc_core::sc_signal<Result> out;      // output register (position L)

  SC_HAS_PROCESS(ComputePipeline);
  // `stages` must cover positions 0..L contiguously in order; otherwise generic names are used.
  ComputePipeline(sc_core::sc_module_name name, const SpecularUnit& unit,
                  std::vector<StageSpec> stages, bool tracing);

  int latency() const { return latency_; }
  int ii() const { return ii_; }
  const std::vector<StageSpec>& stages() const { return stages_; }
  std::uint64_t started() const { return started_; }
  // Requests offered while the II gate was closed (protocol violations; always 0 when driven by
  // TauComparator).
  std::uint64_t violations() const { return violations_; }

  // "in", "s1" .. "sL".
  static std::vector<StageSpec> generic_stages(int latency);
  // True when `stages` covers 0..latency contiguously, each stage non-empty, names unique.
  static bool valid_layout(const std::vector<StageSpec>& stages, int latency);

  void add_traces(VcdWriter& vcd, const std::string& prefix) const override;

 private:
  struct Entry {
    bool valid = false;
    std::uint64_t issue = 0;
    Request request;
  };
  struct StageTrace {
    StageTrace(int t_width, bool t_signed, int r_width, bool r_signed, int bit_width)
        : t(t_width, t_signed), result(r_width, r_signed), bit(bit_width, false) {}
    bool valid = false;
    RawBits t, result, bit;
  };

  void tick();
  void update_traces(std::size_t head, const Result* output);

  const SpecularUnit& unit_;
  const int latency_, ii_;
  const std::size_t depth_;  // L + 1
  std::vector<StageSpec> stages_;
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
