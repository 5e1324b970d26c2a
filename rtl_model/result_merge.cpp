#include "rtl_model/result_merge.h"

#include <algorithm>
#include <stdexcept>

namespace glint::rtl {

ResultMerge::ResultMerge(sc_core::sc_module_name name, int depth, int out_width, bool out_signed,
                         bool tracing, int out_frac_bits, CombMode comb)
    : sc_core::sc_module(name),
      bypass_in("bypass_in"),
      compute_in("compute_in"),
      sink_ready("sink_ready"),
      head_valid("head_valid", false),
      head("head"),
      credit_return("credit_return", false),
      entries_(static_cast<std::size_t>(std::max(depth, 1))),
      tracing_(tracing),
      comb_mode_(comb),
      out_frac_bits_(out_frac_bits),
      result_trace_(out_width, out_signed),
      count_trace_(bits_for(static_cast<std::uint64_t>(std::max(depth, 1))), false) {
  if (depth < 1) throw std::invalid_argument("ResultMerge: depth >= 1 required");
  if (comb_mode_ == CombMode::kOwnProcess) {
    SC_METHOD(settle);
    sensitive << bypass_in << compute_in << changed_;
  }
}

void ResultMerge::end_of_elaboration() {
  if (comb_mode_ == CombMode::kSettledByClock &&
      !(bypass_in.bound_to_register() && compute_in.bound_to_register()))
    throw std::logic_error("ResultMerge: settled by the clock, every input must be a Register");
}

void ResultMerge::settle() {
  const std::uint64_t h = next_seq_;
  const Result& e = entries_[head_entry_];
  bool valid = false;
  std::int64_t value = 0;
  if (e.valid && e.seq == h) {
    head.write(e);
    value = e.value;
    valid = true;
  } else {
    const Result& b = bypass_in.settled();
    const Result& u = compute_in.settled();
    const Result* arriving = (b.valid && b.seq == h) ? &b : (u.valid && u.seq == h) ? &u : nullptr;
    if (arriving) {
      Result r = *arriving;
      r.done = cycle_;  // the coming edge: it arrives there
      head.write(r);
      value = r.value;
      valid = true;
    }
  }
  head_valid.write(valid);
  if (tracing_ && valid) {
    result_trace_.set(value);
    seq_trace_.set(static_cast<std::int64_t>(h & 0xffffffffu));
  }
}

void ResultMerge::tick() {
  const std::uint64_t c = cycle_++;
  const bool retire = head_valid.current() && sink_ready.now();
  bool changed = false;
  const std::size_t n = entries_.size();
  for (const Result* in : {&bypass_in.now(), &compute_in.now()}) {
    if (!in->valid) continue;
    Result& slot = entries_[entry_of(in->seq)];
    if (slot.valid) ++overflows_;
    slot = *in;
    slot.done = c;
    ++count_;
    changed = true;
  }
  max_count_ = std::max(max_count_, count_);
  if (retire) {
    entries_[head_entry_].valid = false;
    --count_;
    ++next_seq_;
    head_entry_ = head_entry_ + 1 == n ? 0 : head_entry_ + 1;
    changed = true;
  }
  if (retire != credit_active_) {
    credit_return.write(retire);
    credit_active_ = retire;
  }
  if (changed && comb_mode_ == CombMode::kOwnProcess) changed_.notify(sc_core::SC_ZERO_TIME);
  if (tracing_) count_trace_.set(static_cast<std::int64_t>(count_));
}

void ResultMerge::add_traces(VcdWriter& vcd, const std::string& prefix) const {
  const std::string p = prefix + ".merge.";
  trace_bool(vcd, head_valid, p + "valid");
  trace_port(vcd, sink_ready, p + "ready");
  trace_raw(vcd, seq_trace_, p + "seq");
  trace_raw(vcd, result_trace_, p + "result", out_frac_bits_);
  trace_raw(vcd, count_trace_, p + "count");
  trace_bool(vcd, credit_return, p + "credit");
}

}  // namespace glint::rtl
