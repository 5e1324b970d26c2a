// ColourMultiply: the optional stage that scales the highlight by the specular colour x light
// colour, built only when the stream's lights or materials are coloured (ClockedOptions::
// colour_stage). It adds one register to the computed path: L_effective = L + 1
// (clocked_timing() in clocked_sim.h); skipped results (0 in every channel) bypass it.
//
// The colour channels are out of scope of the scalar contract: the model carries the scalar
// result (SpecularUnit::eval) through unchanged, so the stage changes timing only.
#pragma once

#include <string>
#include <systemc>
#include <vector>

#include "rtl_model/rtl_common.h"

namespace glint::rtl {

class ColourMultiply : public sc_core::sc_module, public Traceable, public ClockedStage {
 public:
  In<Result> in;
  Register<Result> out;

  // `out_frac_bits`: the result format's fraction bits, for the trace's real-valued display only.
  ColourMultiply(sc_core::sc_module_name name, int out_width, bool out_signed, bool tracing,
                 int out_frac_bits = 0)
      : sc_core::sc_module(name),
        in("in"),
        out("out"),
        tracing_(tracing),
        out_frac_bits_(out_frac_bits),
        result_trace_(out_width, out_signed) {}

  void add_traces(VcdWriter& vcd, const std::string& prefix) const override {
    const std::string p = prefix + ".colour.";
    trace_bool(vcd, valid_trace_, p + "valid");
    trace_raw(vcd, seq_trace_, p + "seq");
    trace_raw(vcd, result_trace_, p + "result", out_frac_bits_);
  }

 private:
  void tick() override {
    const Result& r = in.now();
    if (r.valid || active_) {
      out.write(r);
      active_ = r.valid;
    }
    if (tracing_) {
      valid_trace_ = r.valid;
      if (r.valid) {
        result_trace_.set(r.value);
        seq_trace_.set(static_cast<std::int64_t>(r.seq & 0xffffffffu));
      }
    }
  }

  const bool tracing_;
  const int out_frac_bits_;
  bool active_ = false;
  bool valid_trace_ = false;
  RawBits result_trace_;
  RawBits seq_trace_{32, false};
};

}  // namespace glint::rtl
