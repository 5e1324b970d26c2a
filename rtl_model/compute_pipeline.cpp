#include "rtl_model/compute_pipeline.h"

#include <stdexcept>

namespace glint::rtl {

ComputePipeline::StageTrace::StageTrace(const Stage& s, const QFormat& in, int bit_width)
    : t(in.width(), in.is_signed), seq(32, false), bit(bit_width, false) {
  registers.reserve(s.registers.size());
  for (const StageRegister& r : s.registers)
    registers.emplace_back(r.format.width(), r.format.is_signed);
}

ComputePipeline::ComputePipeline(sc_core::sc_module_name name, const SpecularUnit& unit,
                                 bool tracing)
    : sc_core::sc_module(name),
      in_valid("in_valid"),
      in_request("in_request"),
      ready("ready", true),
      out("out"),
      unit_(unit),
      latency_(unit.timing().latency),
      ii_(unit.timing().ii),
      depth_(static_cast<std::size_t>(unit.timing().latency) + 1),
      layout_(unit.stages()),
      tracing_(tracing),
      ring_(depth_) {
  if (latency_ < 1 || ii_ < 1 || layout_.latency() != latency_)
    throw std::invalid_argument(
        "ComputePipeline: latency >= 1, II >= 1 and a stage layout of the same latency required");
  if (tracing_) {
    for (Entry& e : ring_) e.staged.assign(layout_.size(), 0);
    for (const Stage& s : layout_.stages())
      traces_.push_back(std::make_unique<StageTrace>(
          s, unit.in_format(), bits_for(static_cast<std::uint64_t>(s.last - s.first))));
  }
}

void ComputePipeline::tick() {
  const std::uint64_t c = cycle_++;
  const std::size_t head = head_;
  head_ = head + 1 == depth_ ? 0 : head + 1;

  // Input register (position 0).
  Entry& in = ring_[head];
  const bool start = in_valid.now();
  if (start) {
    if (busy_ > 0) ++violations_;
    in.valid = true;
    in.issue = c;
    in.request = in_request.now();
    if (tracing_) unit_.eval_staged(in.request.slot, in.request.t_raw, in.staged.data());
    ++started_;
  } else {
    in.valid = false;
  }

  // Output register (position L): the request that started L edges ago.
  const Entry& o = ring_[head_];
  Result r;
  if (o.valid) {
    r.valid = true;
    r.last = o.request.last;
    r.slot = o.request.slot;
    r.seq = o.request.seq;
    r.t_raw = o.request.t_raw;
    // Traced runs evaluated the request stage by stage at issue: its result register is eval().
    r.value =
        tracing_ ? o.staged[layout_.result_index()] : unit_.eval(o.request.slot, o.request.t_raw);
    r.issue = o.issue;
  }
  if (r.valid || out_active_) {
    out.write(r);
    out_active_ = r.valid;
  }

  // II gate.
  if (start) {
    busy_ = ii_ - 1;
    if (busy_ > 0) ready.write(false);
  } else if (busy_ > 0 && --busy_ == 0) {
    ready.write(true);
  }

  if (tracing_) update_traces(head);
}

void ComputePipeline::update_traces(std::size_t head) {
  const auto& stages = layout_.stages();
  for (std::size_t k = 0; k < stages.size(); ++k) {
    const Stage& s = stages[k];
    StageTrace& tr = *traces_[k];
    // The request in this stage: at its only position, or (an iterative stage) the one of its
    // positions that holds a request.
    const Entry* e = nullptr;
    int position = s.first;
    for (int p = s.first; p <= s.last; ++p) {
      const std::size_t up = static_cast<std::size_t>(p);  // < depth_
      const Entry& candidate = ring_[head >= up ? head - up : head + depth_ - up];
      if (candidate.valid || s.first == s.last) {
        e = &candidate;
        position = p;
        break;
      }
    }
    const bool valid = e != nullptr && e->valid;
    tr.valid = valid;
    if (!valid) continue;  // registers keep their last values, as the hardware's would
    tr.t.set(e->request.t_raw);
    tr.seq.set(static_cast<std::int64_t>(e->request.seq & 0xffffffffu));
    if (s.last > s.first) tr.bit.set(position - s.first);
    if (position == 0) continue;
    const std::int64_t* values = e->staged.data() + layout_.offset(position);
    for (std::size_t r = 0; r < tr.registers.size(); ++r) tr.registers[r].set(values[r]);
  }
}

void ComputePipeline::add_traces(VcdWriter& vcd, const std::string& prefix) const {
  const auto& stages = layout_.stages();
  for (std::size_t k = 0; k < stages.size(); ++k) {
    const Stage& s = stages[k];
    const StageTrace& tr = *traces_[k];
    const std::string p = prefix + "." + s.name + ".";
    trace_bool(vcd, tr.valid, p + "valid");
    if (k == 0) trace_bool(vcd, ready, p + "ready");
    trace_raw(vcd, tr.seq, p + "seq");
    trace_raw(vcd, tr.t, p + "t", unit_.in_format().frac_bits);
    if (s.last > s.first) trace_raw(vcd, tr.bit, p + "bit");
    for (std::size_t r = 0; r < s.registers.size(); ++r)
      trace_raw(vcd, tr.registers[r], p + s.registers[r].name, s.registers[r].format.frac_bits);
  }
}

}  // namespace glint::rtl
