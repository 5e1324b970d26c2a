#include "rtl_model/vector_source.h"

#include <stdexcept>
#include <string>

#include "units/common.h"

namespace glint::rtl {

VectorSource::VectorSource(sc_core::sc_module_name name, RowStream& stream,
                           const SpecularUnit& unit, const SlotMap& slots, RowRing& ring,
                           SimControl& control, bool tracing)
    : sc_core::sc_module(name),
      ready("ready"),
      valid("valid", false),
      request("request"),
      stream_(stream),
      unit_(unit),
      slots_(slots),
      ring_(ring),
      control_(control),
      tracing_(tracing),
      quantize_(unit.in_format()),
      unit_slots_(unit.slots()),
      t_trace_(unit.in_format().width(), unit.in_format().is_signed),
      slot_trace_(bits_for(unit.slots() > 0 ? unit.slots() - 1 : 0), false),
      seq_trace_(32, false) {
  have_ahead_ = stream_.next(ahead_);
  load();
}

void VectorSource::load() {
  if (!have_ahead_) {
    valid_ = false;
    valid.write(false);
    return;
  }
  const std::uint64_t seq = presented_++;
  VectorRow& row = ring_.at(seq);
  row = ahead_;
  Request r;
  r.seq = seq;
  r.t_raw = quantize_(row.t);
  const std::size_t slot = slots_.slot(row);
  if (slot >= unit_slots_)
    throw std::out_of_range("VectorSource: row " + std::to_string(row.line) + " maps to slot " +
                            std::to_string(slot) + " of a unit built for " +
                            std::to_string(unit_slots_));
  r.slot = static_cast<std::uint32_t>(slot);
  have_ahead_ = stream_.next(ahead_);
  r.last = !have_ahead_;
  request.write(r);
  valid_ = true;
  valid.write(true);
  if (tracing_) {
    t_trace_.set(r.t_raw);
    slot_trace_.set(r.slot);
    seq_trace_.set(static_cast<std::int64_t>(seq & 0xffffffffu));
  }
  control_.on_present(seq);
}

void VectorSource::tick() {
  if (!valid_ || !ready.now()) return;
  try {
    load();
  } catch (...) {
    control_.fail(std::current_exception());
  }
}

void VectorSource::add_traces(VcdWriter& vcd, const std::string& prefix) const {
  const std::string p = prefix + ".source.";
  trace_bool(vcd, valid, p + "valid");
  trace_port(vcd, ready, p + "ready");
  trace_raw(vcd, t_trace_, p + "t", unit_.in_format().frac_bits);
  trace_raw(vcd, slot_trace_, p + "slot");
  trace_raw(vcd, seq_trace_, p + "seq");
}

}  // namespace glint::rtl
