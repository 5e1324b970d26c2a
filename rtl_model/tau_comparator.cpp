#include "rtl_model/tau_comparator.h"

#include <stdexcept>

#include "units/common.h"

namespace glint::rtl {

TauComparator::TauComparator(sc_core::sc_module_name name, const SpecularUnit& unit, int credits,
                             bool tracing, CombMode comb)
    : sc_core::sc_module(name),
      src_valid("src_valid"),
      src_request("src_request"),
      unit_ready("unit_ready"),
      credit_return("credit_return"),
      src_ready("src_ready", false),
      compute_valid("compute_valid", false),
      bypass("bypass"),
      unit_(unit),
      tracing_(tracing),
      comb_mode_(comb),
      credits_(credits),
      tau_trace_(unit.in_format().width() + 1, true),  // -1 (never skip) .. raw_max
      credits_trace_(bits_for(static_cast<std::uint64_t>(credits)), false),
      bypass_t_trace_(unit.in_format().width(), unit.in_format().is_signed),
      bypass_result_trace_(unit.out_format().width(), unit.out_format().is_signed) {
  if (credits < 1) throw std::invalid_argument("TauComparator: at least one credit required");
  tau_.reserve(unit.slots());
  for (std::size_t s = 0; s < unit.slots(); ++s) tau_.push_back(unit.tau_raw(s));
  credits_trace_.set(credits_);

  if (comb_mode_ == CombMode::kOwnProcess) {
    SC_METHOD(settle);
    sensitive << src_valid << src_request << unit_ready << credit_return << credits_changed_;
  }
}

void TauComparator::end_of_elaboration() {
  if (comb_mode_ == CombMode::kSettledByClock &&
      !(src_valid.bound_to_register() && src_request.bound_to_register() &&
        unit_ready.bound_to_register() && credit_return.bound_to_register()))
    throw std::logic_error("TauComparator: settled by the clock, every input must be a Register");
}

void TauComparator::settle() {
  const bool valid = src_valid.settled();
  const Request& r = src_request.settled();
  const bool skip = valid && tau_skip(r.t_raw, tau_[r.slot]);
  const bool credit_ok = credits_ > 0 || credit_return.settled();
  const bool unit_ok = unit_ready.settled();
  skip_ = skip;
  credit_ok_ = credit_ok;
  src_ready.write(credit_ok && (skip || unit_ok));
  compute_valid.write(valid && credit_ok && !skip && unit_ok);
  if (tracing_) {
    skip_trace_ = skip;
    if (valid) tau_trace_.set(tau_[r.slot]);
  }
}

void TauComparator::tick() {
  const std::uint64_t c = cycle_++;
  bool changed = false;
  if (credit_return.now()) {
    ++credits_;
    changed = true;
  }
  const bool valid = src_valid.now();
  const bool issue = valid && src_ready.current();
  Result b;
  if (issue) {
    --credits_;
    changed = true;
    ++issued_;
    if (held_ > 0) {
      (held_by_credit_ ? stall_credit_ : stall_unit_) += held_;
      held_ = 0;
    }
    if (skip_) {
      const Request& r = src_request.now();
      b.valid = true;
      b.skipped = true;
      b.last = r.last;
      b.slot = r.slot;
      b.seq = r.seq;
      b.t_raw = r.t_raw;
      b.value = unit_.eval_with_skip(r.slot, r.t_raw);
      b.issue = c;
    }
  } else if (valid) {
    ++held_;
    held_by_credit_ = !credit_ok_;
  }
  if (b.valid || bypass_active_) {
    bypass.write(b);
    bypass_active_ = b.valid;
  }
  if (changed && comb_mode_ == CombMode::kOwnProcess)
    credits_changed_.notify(sc_core::SC_ZERO_TIME);
  if (tracing_) {
    issue_trace_ = issue;
    stall_trace_ = valid && !issue;
    credits_trace_.set(credits_);
    bypass_valid_trace_ = b.valid;
    if (b.valid) {
      bypass_t_trace_.set(b.t_raw);
      bypass_seq_trace_.set(static_cast<std::int64_t>(b.seq & 0xffffffffu));
      bypass_result_trace_.set(b.value);
    }
  }
}

void TauComparator::add_traces(VcdWriter& vcd, const std::string& prefix) const {
  const std::string p = prefix + ".comparator.";
  const int in_frac = unit_.in_format().frac_bits;
  trace_raw(vcd, tau_trace_, p + "tau", in_frac);
  trace_bool(vcd, skip_trace_, p + "skip");
  trace_bool(vcd, issue_trace_, p + "issue");
  trace_bool(vcd, stall_trace_, p + "stall");
  trace_raw(vcd, credits_trace_, p + "credits");
  trace_bool(vcd, compute_valid, p + "compute_valid");
  trace_port(vcd, unit_ready, p + "compute_ready");
  const std::string b = prefix + ".bypass.";
  trace_bool(vcd, bypass_valid_trace_, b + "valid");
  trace_raw(vcd, bypass_seq_trace_, b + "seq");
  trace_raw(vcd, bypass_t_trace_, b + "t", in_frac);
  trace_raw(vcd, bypass_result_trace_, b + "result", unit_.out_format().frac_bits);
}

}  // namespace glint::rtl
