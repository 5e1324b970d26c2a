#include "rtl_model/compute_pipeline.h"

#include <set>
#include <stdexcept>

namespace glint::rtl {

std::vector<StageSpec> ComputePipeline::generic_stages(int latency) {
  std::vector<StageSpec> s{{"in", 0, 0}};
  for (int k = 1; k <= latency; ++k) s.push_back({"s" + std::to_string(k), k, k});
  return s;
}

bool ComputePipeline::valid_layout(const std::vector<StageSpec>& stages, int latency) {
  int next = 0;
  std::set<std::string> names;
  for (const StageSpec& s : stages) {
    if (s.first != next || s.last < s.first || s.name.empty() || !names.insert(s.name).second)
      return false;
    if (s.name.find_first_of(". []") != std::string::npos) return false;
    next = s.last + 1;
  }
  return next == latency + 1;
}

ComputePipeline::ComputePipeline(sc_core::sc_module_name name, const SpecularUnit& unit,
                                 std::vector<StageSpec> stages, bool tracing)
    : sc_core::sc_module(name),
      clk("clk"),
      in_valid("in_valid"),
      in_request("in_request"),
      ready("ready", true),
      out("out"),
      unit_(unit),
      latency_(unit.timing().latency),
      ii_(unit.timing().ii),
      depth_(static_cast<std::size_t>(unit.timing().latency) + 1),
      stages_(std::move(stages)),
      tracing_(tracing),
      ring_(depth_) {
  if (latency_ < 0 || ii_ < 1)
    throw std::invalid_argument("ComputePipeline: latency >= 0 and II >= 1 required");
  if (!valid_layout(stages_, latency_)) stages_ = generic_stages(latency_);
  const QFormat in = unit.in_format(), outf = unit.out_format();
  for (const StageSpec& s : stages_) {
    traces_.push_back(std::make_unique<StageTrace>(in.width(), in.is_signed, outf.width(),
                                                   outf.is_signed,
                                                   bits_for(std::uint64_t(s.last - s.first))));
  }
  SC_METHOD(tick);
  sensitive << clk.pos();
  dont_initialize();
}

void ComputePipeline::tick() {
  const std::uint64_t c = cycle_++;
  const std::size_t head = head_;
  head_ = head + 1 == depth_ ? 0 : head + 1;

  // Input register (position 0).
  Entry& in = ring_[head];
  const bool start = in_valid.read();
  if (start) {
    if (busy_ > 0) ++violations_;
    in.valid = true;
    in.issue = c;
    in.request = in_request.read();
    ++started_;
  } else {
    in.valid = false;
  }

  // Output register (position L): the request that started L edges ago.
  const Entry& o = ring_[latency_ == 0 ? head : head_];
  Result r;
  if (o.valid) {
    r.valid = true;
    r.last = o.request.last;
    r.slot = o.request.slot;
    r.seq = o.request.seq;
    r.t_raw = o.request.t_raw;
    r.value = unit_.eval(o.request.slot, o.request.t_raw);
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

  if (tracing_) update_traces(head, r.valid ? &r : nullptr);
}

void ComputePipeline::update_traces(std::size_t head, const Result* output) {
  for (std::size_t k = 0; k < stages_.size(); ++k) {
    const StageSpec& s = stages_[k];
    StageTrace& tr = *traces_[k];
    if (s.first == s.last) {
      // One position (most stages): without branches, as `valid` follows the request pattern.
      const std::size_t up = static_cast<std::size_t>(s.first);
      const Entry& e = ring_[head >= up ? head - up : head + depth_ - up];
      tr.valid = e.valid;
      tr.t.set_if(e.valid, e.request.t_raw);
      if (s.last == latency_ && output) tr.result.set(output->value);
      continue;
    }
    tr.valid = false;
    for (int p = s.first; p <= s.last; ++p) {
      const std::size_t up = static_cast<std::size_t>(p);  // < depth_
      const Entry& e = ring_[head >= up ? head - up : head + depth_ - up];
      if (!e.valid) continue;
      tr.valid = true;
      tr.t.set(e.request.t_raw);
      if (s.last > s.first) tr.bit.set(p - s.first);
      break;
    }
    if (s.last == latency_ && output) tr.result.set(output->value);
  }
}

void ComputePipeline::add_traces(VcdWriter& vcd, const std::string& prefix) const {
  for (std::size_t k = 0; k < stages_.size(); ++k) {
    const StageSpec& s = stages_[k];
    const StageTrace& tr = *traces_[k];
    const std::string p = prefix + "." + s.name + ".";
    trace_bool(vcd, tr.valid, p + "valid");
    if (k == 0) trace_bool(vcd, ready, p + "ready");
    trace_raw(vcd, tr.t, p + "t");
    if (s.last > s.first) trace_raw(vcd, tr.bit, p + "bit");
    if (s.last == latency_) trace_raw(vcd, tr.result, p + "result");
  }
}

}  // namespace glint::rtl
