#include "rtl_model/clocked_sim.h"

#include <algorithm>
#include <memory>
#include <stdexcept>

#include "io/output_set.h"
#include "rtl_model/compute_pipeline.h"
#include "rtl_model/result_merge.h"
#include "rtl_model/rtl_common.h"
#include "rtl_model/sc_setup.h"
#include "rtl_model/scoreboard.h"
#include "rtl_model/sim_control.h"
#include "rtl_model/tau_comparator.h"
#include "rtl_model/vcd_trace.h"
#include "rtl_model/vector_source.h"

namespace glint {

namespace rtl {
namespace {

// One lane: source, comparator, compute unit, merge buffer, sink.
class Lane : public sc_core::sc_module {
 public:
  Lane(sc_core::sc_module_name name, std::size_t index, const SpecularUnit& unit,
       const SlotMap& slots, std::unique_ptr<RowStream> stream, const ClockedOptions& options,
       SimControl& control, const std::function<void(const LaneOutput&)>& on_result, bool tracing)
      : sc_core::sc_module(name),
        index_(index),
        stream_(std::move(stream)),
        ring_(static_cast<std::size_t>(unit.timing().buffer_depth) + 2),
        on_result_(on_result) {
    const QFormat out = unit.out_format();
    source_ =
        std::make_unique<VectorSource>("source", *stream_, unit, slots, ring_, control, tracing);
    comparator_ = std::make_unique<TauComparator>("comparator", unit, unit.timing().buffer_depth,
                                                  tracing, CombMode::kSettledByClock);
    compute_ = std::make_unique<ComputePipeline>("compute", unit, tracing);
    merge_ = std::make_unique<ResultMerge>("merge", unit.timing().buffer_depth, out.width(),
                                           out.is_signed, tracing, out.frac_bits,
                                           CombMode::kSettledByClock);
    Scoreboard::Callback cb;
    if (on_result_) {
      cb = [this](const VectorRow& row, const Result& r, const ResultTiming& t) {
        on_result_(LaneOutput{index_, row, r.t_raw, r.skipped, r.value, t});
      };
    }
    sink_ = std::make_unique<Scoreboard>("sink", unit, options.sink, ring_, control, std::move(cb),
                                         source_->empty(), tracing);

    source_->ready(comparator_->src_ready);
    comparator_->src_valid(source_->valid);
    comparator_->src_request(source_->request);
    comparator_->unit_ready(compute_->ready);
    comparator_->credit_return(merge_->credit_return);
    compute_->in_valid(comparator_->compute_valid);
    compute_->in_request(source_->request);
    merge_->bypass_in(comparator_->bypass);
    merge_->compute_in(compute_->out);
    merge_->sink_ready(sink_->ready);
    sink_->head_valid(merge_->head_valid);
    sink_->head(merge_->head);
  }

  // The lane's register stages, ticked at every rising edge.
  void stages(std::vector<ClockedStage*>& out) const {
    out.insert(out.end(),
               {source_.get(), comparator_.get(), compute_.get(), merge_.get(), sink_.get()});
  }
  // Its combinational parts, settled after the ticks (they read registers only, so in any order).
  void combinational(std::vector<Combinational*>& out) const {
    out.insert(out.end(), {comparator_.get(), merge_.get()});
  }

  TimingStats stats() const {
    TimingStats s = sink_->stats();
    s.stall_credit = comparator_->stall_credit();
    s.stall_unit = comparator_->stall_unit();
    return s;
  }
  std::uint64_t mismatches() const {
    return sink_->mismatches() + compute_->violations() + merge_->overflows();
  }
  std::size_t max_occupancy() const { return merge_->max_occupancy(); }

  void add_traces(VcdWriter& vcd, const std::string& prefix) const {
    source_->add_traces(vcd, prefix);
    comparator_->add_traces(vcd, prefix);
    compute_->add_traces(vcd, prefix);
    merge_->add_traces(vcd, prefix);
    sink_->add_traces(vcd, prefix);
  }

 private:
  std::size_t index_;
  std::unique_ptr<RowStream> stream_;
  RowRing ring_;
  const std::function<void(const LaneOutput&)>& on_result_;
  std::unique_ptr<VectorSource> source_;
  std::unique_ptr<TauComparator> comparator_;
  std::unique_ptr<ComputePipeline> compute_;
  std::unique_ptr<ResultMerge> merge_;
  std::unique_ptr<Scoreboard> sink_;
};

// The clock, the lanes, the per-edge control (end of run, VCD window, cycle counter) and the VCD
// sampling: once the values of cycle c have settled, at the falling edge after it (and once for the
// reset state, halfway to the first rising edge). The clock is one timed process, edge(), which
// ticks every register stage of every lane (ClockedStage) and then settles every combinational
// part (Combinational), so a cycle is one process activation without delta cycles; no clock signal
// is needed, as nothing reads its level (the VCD draws top.clk from the edge times).
class Top : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(Top);
  Top(sc_core::sc_module_name name, const std::vector<const SpecularUnit*>& units,
      const std::vector<std::string>& labels, const SlotMap& slots,
      const std::function<std::unique_ptr<RowStream>()>& open_stream, const ClockedOptions& options,
      SimControl& control, const std::function<void(const LaneOutput&)>& on_result,
      TraceControl* vcd)
      : sc_core::sc_module(name),
        control_(control),
        vcd_(vcd),
        tracing_(vcd != nullptr),
        cycle_trace_(32, false) {
    for (std::size_t i = 0; i < units.size(); ++i) {
      lanes_.push_back(std::make_unique<Lane>(labels[i].c_str(), i, *units[i], slots, open_stream(),
                                              options, control, on_result, tracing_));
      lanes_.back()->stages(stages_);
      lanes_.back()->combinational(combs_);
    }
    // Initialized (no dont_initialize): its first run settles the reset state and schedules the
    // first edge. One process writes every combinational signal (sc_signal allows one driver).
    SC_METHOD(edge);
    sensitive << edge_event_;
    if (vcd_) {
      SC_METHOD(sample);
      sensitive << sample_event_;
      dont_initialize();
      sample_event_.notify(clock_first_edge() / 2);
    }
  }

  const std::vector<std::unique_ptr<Lane>>& lanes() const { return lanes_; }
  std::uint64_t cycles() const { return cycle_; }

  void add_traces(VcdWriter& vcd, const std::vector<std::string>& labels) const {
    vcd.add_clock("top.clk");
    trace_raw(vcd, cycle_trace_, "top.cycle");
    for (std::size_t i = 0; i < lanes_.size(); ++i) lanes_[i]->add_traces(vcd, "top." + labels[i]);
  }

 private:
  void edge() {
    if (!initialized_) {
      initialized_ = true;
      settle();
      edge_event_.notify(clock_first_edge());
      return;
    }
    const std::uint64_t c = cycle_++;
    if (tracing_) cycle_trace_.set(static_cast<std::int64_t>(c & 0xffffffffu));
    control_.on_edge(c);
    for (ClockedStage* s : stages_) s->tick();
    settle();
    edge_event_.notify(period_);
    if (vcd_) sample_event_.notify(half_period_);  // the falling edge
  }

  void settle() {
    for (Combinational* c : combs_) c->settle();
  }

  void sample() {
    if (cycle_ == 0) {
      vcd_->sample_reset();
    } else {
      vcd_->sample_cycle(cycle_time_ns(cycle_ - 1), fall_time_ns(cycle_ - 1));
    }
  }

  SimControl& control_;
  TraceControl* const vcd_;
  const bool tracing_;
  // sc_time from a value and a unit costs a floating-point conversion: 7 % of a clocked run when
  // made at every edge.
  const sc_core::sc_time period_ = clock_period();
  const sc_core::sc_time half_period_ = clock_period() / 2;
  sc_core::sc_event edge_event_;    // the rising edges
  sc_core::sc_event sample_event_;  // the falling edges (and the reset state's sample)
  bool initialized_ = false;
  std::uint64_t cycle_ = 0;
  RawBits cycle_trace_;
  std::vector<std::unique_ptr<Lane>> lanes_;
  std::vector<ClockedStage*> stages_;  // every lane's, in lane order
  std::vector<Combinational*> combs_;
};

// VCD labels: unit_labels() (the unit's name, or name.k when several lanes share a name) with '_'
// for '.', which separates VCD scopes: hast_1, hast_2.
std::vector<std::string> lane_labels(const std::vector<const SpecularUnit*>& units) {
  std::vector<std::string> names;
  for (const SpecularUnit* u : units) names.push_back(u->name());
  std::vector<std::string> labels = unit_labels(names);
  for (std::string& l : labels) std::replace(l.begin(), l.end(), '.', '_');
  return labels;
}

void quiet_reports() {
  using sc_core::sc_report_handler;
  // "Simulation stopped by user" would go to stdout, which carries glint's results.
  sc_report_handler::set_actions("/OSCI/SystemC", sc_core::SC_INFO, sc_core::SC_DO_NOTHING);
}

}  // namespace
}  // namespace rtl

std::vector<TimingStats> run_clocked(const std::vector<const SpecularUnit*>& units,
                                     const SlotMap& slots,
                                     const std::function<std::unique_ptr<RowStream>()>& open_stream,
                                     const ClockedOptions& options,
                                     const std::function<void(const LaneOutput&)>& on_result,
                                     ClockedRunInfo* info) {
  using namespace rtl;
  if (units.empty()) throw std::invalid_argument("run_clocked: no units");
  for (const SpecularUnit* u : units) {
    if (!u) throw std::invalid_argument("run_clocked: null unit");
    const UnitTiming t = u->timing();
    if (t.latency < 0 || t.ii < 1 || t.buffer_depth < 1)
      throw std::invalid_argument("run_clocked: unit " + u->name() + " has invalid timing");
    if (u->slots() < slots.params.size())
      throw std::invalid_argument("run_clocked: unit " + u->name() +
                                  " has fewer slots than the "
                                  "stream");
  }
  if (!(options.sink.probability > 0.0))
    throw std::invalid_argument("run_clocked: sink ready probability must be > 0");
  if (options.vcd_first > options.vcd_last)
    throw std::invalid_argument("run_clocked: VCD window FIRST:LAST needs FIRST <= LAST");
  if (sc_core::sc_get_status() != sc_core::SC_ELABORATION ||
      sc_core::sc_start_of_simulation_invoked())
    throw std::logic_error(
        "run_clocked: SystemC has already simulated in this process (one "
        "elaboration per process)");

  quiet_systemc_banner();
  quiet_reports();

  // The trace's files: the caller's outputs, or our own, committed after a successful run.
  std::unique_ptr<OutputSet> own_outputs;
  TraceOutputs own_trace;
  const TraceOutputs* trace = options.trace_outputs;
  if (!trace && !options.vcd_path.empty()) {
    own_outputs = std::make_unique<OutputSet>();
    own_trace = declare_trace_outputs(*own_outputs, options.vcd_path, options.trace_format, "");
    trace = &own_trace;
  }
  const bool tracing = trace != nullptr;
  const std::vector<std::string> labels = lane_labels(units);
  SimControl control;
  control.set_lanes(units.size());

  std::unique_ptr<Top> top;
  std::unique_ptr<TraceControl> vcd;
  if (tracing) {
    vcd = std::make_unique<TraceControl>(*trace, [&](VcdWriter& w) { top->add_traces(w, labels); });
    control.set_window(
        options.vcd_first, options.vcd_last, units.size(), [&] { vcd->open(); },
        [&] { vcd->close(); });
  }
  control.hold_window(true);  // sources present vector 0 during elaboration
  top = std::make_unique<Top>("top", units, labels, slots, open_stream, options, control, on_result,
                              vcd.get());
  control.hold_window(false);

  sc_core::sc_start();
  resync_sanitizer_stack();
  if (control.error()) std::rethrow_exception(control.error());

  std::vector<TimingStats> stats;
  std::uint64_t mismatches = 0;
  for (const auto& lane : top->lanes()) {
    stats.push_back(lane->stats());
    mismatches += lane->mismatches();
  }
  if (info) {
    info->labels = labels;
    info->mismatches.clear();
    info->max_occupancy.clear();
    for (const auto& lane : top->lanes()) {
      info->mismatches.push_back(lane->mismatches());
      info->max_occupancy.push_back(lane->max_occupancy());
    }
    info->sim_cycles = top->cycles();
  }
  if (vcd) {
    vcd->commit();
    if (info) {
      info->vcd_path = vcd->vcd_path();
      info->gtkw_path = vcd->gtkw_path();
      info->fst = vcd->fst();
      info->vcd_start_ns = vcd->start_ns();
      info->traced.clear();
      for (const TracedSignal& s : vcd->signals()) info->traced.push_back(s.name);
    }
  }
  if (mismatches)
    throw std::logic_error("run_clocked: " + std::to_string(mismatches) +
                           " results differ from the datapath (model error)");
  if (own_outputs) own_outputs->commit();
  return stats;
}

TraceOutputs declare_trace_outputs(OutputSet& outputs, const std::string& path, TraceFormat format,
                                   const std::string& option) {
  TraceOutputs t;
  t.path = path;
  t.fst = format == TraceFormat::kFst ||
          (format == TraceFormat::kByExtension && rtl::is_fst_path(path));
  const std::string name = option.empty() ? "trace" : option;
  if (path == "-") {
    if (t.fst)
      throw OutputError(name +
                        " -: an FST needs a file (vcd2fst seeks in it); standard output "
                        "takes a VCD");
    t.trace = &outputs.add(name, path, /*allow_stdout=*/true);
    return t;
  }
  t.trace = t.fst ? &outputs.add_produced(name, path) : &outputs.add(name, path);
  t.save = &outputs.add(name + "'s save file", rtl::TraceControl::gtkw_path(path));
  return t;
}

}  // namespace glint
