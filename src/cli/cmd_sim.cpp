// glint sim: the cycle-approximate SystemC model of the specular units over a vector stream.
//
// run_sim works in three steps, each its own function: check every option and declare every output
// before any input is read (check_sim_options), build the lanes and run the chosen mode
// (make_lanes, run_clocked_mode / run_fast_mode), then write the outputs (build_report,
// write_outputs). The outputs are one OutputSet, committed only at the end: all or none.
#include <fmt/format.h>
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string_view>

#include "cli/cli.h"
#include "eval/activity.h"
#include "eval/chip_report.h"
#include "eval/energy.h"
#include "eval/parallel.h"
#include "eval/sim_report.h"
#include "io/input_source.h"
#include "io/output_set.h"
#include "io/vectors.h"
#include "rtl_model/clocked_sim.h"
#include "rtl_model/fast_sim.h"
#include "units/lane_cost.h"

namespace glint::cli {
namespace {

struct SimOptions {
  std::string vectors;
  std::vector<std::string> units;
  std::string report, dump, vcd, vcd_window, mode = "auto";
  double sink_ready = 1.0;
  std::uint64_t seed = 1;
  bool seed_given = false;
  std::size_t batch = 4096;
  bool batch_given = false;
  int threads = 0;  // --threads N; 0: every core
  int display_bits = 8;
  Chip chip;  // --chip
  EpsMeasure eps_measure = EpsMeasure::kLuminance;
  std::string activity;  // --activity GATING: empty, none, operand or clock
  std::string node;      // --node: area and critical path at this node too
  bool json = false;
};

// What the options decide before the vector file is opened, and the outputs, declared (checked,
// their temporaries made) before any work. Not movable: clocked_options points at trace.
struct SimPlan {
  SimPlan() = default;
  SimPlan(const SimPlan&) = delete;
  SimPlan& operator=(const SimPlan&) = delete;

  std::vector<UnitSpec> specs;
  bool clocked = false;
  ClockedOptions clocked_options;  // VCD outputs and window; sink comes later
  OutputSet outputs;               // committed together at the end, or none
  OutputFile* report = nullptr;
  OutputFile* dump = nullptr;
  TraceOutputs trace;
  std::optional<Gating> gating;  // --activity
};

// A decimal unsigned 64-bit integer, digits only: no sign (std::stoull would wrap "-1" to
// 2^64 - 1), no overflow.
std::optional<std::uint64_t> parse_u64(std::string_view text) {
  std::uint64_t v = 0;
  if (text.empty() || text.front() < '0' || text.front() > '9') return std::nullopt;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return v;
}

// --vcd-window FIRST:LAST into `co`; throws std::invalid_argument naming the option.
void parse_vcd_window(const std::string& text, ClockedOptions& co) {
  const auto colon = text.find(':');
  const std::string_view all(text);
  const auto first = colon == std::string::npos ? std::nullopt : parse_u64(all.substr(0, colon));
  const auto last = colon == std::string::npos ? std::nullopt : parse_u64(all.substr(colon + 1));
  if (!first || !last || *last < *first)
    throw std::invalid_argument(fmt::format(
        "--vcd-window '{}': expected FIRST:LAST vector indices (0..2^64-1) with FIRST <= LAST",
        text));
  co.vcd_first = *first;
  co.vcd_last = *last;
}

// Every check that needs no input: unit specs, sink, mode and VCD window, then the outputs
// (--report, --dump, --vcd and its save file), declared in plan.outputs before simulating: each
// checked (not a link, device or folder; its folder exists), none the input or another output, at
// most one of them (or --json) on standard output. Options only (the fuzzer): no output declared.
void check_sim_options(const SimOptions& o, SimPlan& plan) {
  plan.specs = specs_for_chip(parse_unit_options(o.units), o.chip);
  if (!o.activity.empty()) {
    try {
      plan.gating = parse_gating(o.activity);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--activity: ") + e.what());
    }
  }
  if (!(o.sink_ready >= kMinSinkReady && o.sink_ready <= 1))
    throw std::invalid_argument(fmt::format(
        "--sink-ready must be in [{}, 1] (a run takes ~vectors / p cycles)", kMinSinkReady));
  plan.clocked = o.mode == "clocked" || (o.mode == "auto" && !o.vcd.empty());
  if (!plan.clocked && !o.vcd.empty())
    throw std::invalid_argument("--vcd needs the clocked mode (--mode clocked or auto)");
  require_backpressure_for_seed(o.seed_given, o.sink_ready);
  // The clocked model takes one request a cycle on one thread: these would be ignored in silence.
  const char* clocked_by = o.mode == "clocked" ? "--mode clocked" : "--vcd (clocked mode)";
  if (plan.clocked && o.batch_given)
    throw std::invalid_argument(
        fmt::format("--batch sets fast mode's requests per time quantum: {} has none", clocked_by));
  if (plan.clocked && o.threads > 0)
    throw std::invalid_argument(
        fmt::format("--threads sets fast mode's threads: {} runs on one", clocked_by));
  if (!o.vcd_window.empty()) {
    parse_vcd_window(o.vcd_window, plan.clocked_options);
    // The window selects what the trace holds: without a trace it would be ignored in silence.
    if (o.vcd.empty())
      throw std::invalid_argument("--vcd-window selects the vectors --vcd traces: it needs --vcd");
  }
  if (options_only()) return;
  OutputSet& out = plan.outputs;
  out.add_input("VECTORS", o.vectors);
  if (o.json) out.claim_stdout("--json");
  if (!o.report.empty()) plan.report = &out.add("--report", o.report, /*allow_stdout=*/true);
  if (!o.dump.empty()) plan.dump = &out.add("--dump", o.dump, /*allow_stdout=*/true);
  if (!o.vcd.empty()) {
    plan.trace = declare_trace_outputs(out, o.vcd, TraceFormat::kByExtension, "--vcd");
    plan.clocked_options.trace_outputs = &plan.trace;
  }
}

// The lanes of one run: a unit per spec, built for the stream's slots, and its accumulator.
struct SimLanes {
  SlotMap slots;
  std::vector<std::unique_ptr<SpecularUnit>> owned;
  std::vector<const SpecularUnit*> units;
  std::vector<LaneAccumulator> acc;       // refers to *owned: built once, never moved out of
  std::vector<ActivityCounter> activity;  // per lane with --activity, else empty
};

void make_lanes(const VectorHeader& header, const std::vector<UnitSpec>& specs, int display_bits,
                const Chip& chip, SimLanes& lanes) {
  try {
    lanes.slots = make_slots(header, chip);
  } catch (const SlotCapacityError& e) {
    refuse_chip(chip, e);  // the stream needs more than the chip holds
  }
  check_lane_slots(specs.size(), lanes.slots);
  for (const auto& s : specs) {
    lanes.owned.push_back(make_unit(s, lanes.slots));
    lanes.units.push_back(lanes.owned.back().get());
  }
  check_contract_codes(lanes.units, lanes.slots);
  check_memo_bytes(lanes.units);
  lanes.acc.reserve(lanes.units.size());
  for (const auto* u : lanes.units) lanes.acc.emplace_back(*u, lanes.slots, display_bits);
  std::vector<std::string> names;
  for (const auto* u : lanes.units) names.push_back(u->name());
  const auto labels = unit_labels(names);
  for (std::size_t i = 0; i < lanes.units.size(); ++i) lanes.acc[i].stats().name = labels[i];
}

// The per-result CSV (--dump). The columns after `retire` (material, light, x, y, as `glint eval`
// dumps them) were added later, at the end, so readers that index the older columns by position
// keep working.
class SimDump {
 public:
  SimDump(OutputFile& file, const VectorHeader& header, const SimLanes& lanes)
      : out_(file.stream()), header_(header), lanes_(lanes) {
    out_ << "line,unit,t,t_raw,skipped,fixed_raw,fixed,issue,done,retire,material,light,"
            "x,y\n";
  }
  void row(std::size_t lane, const VectorRow& row, std::int64_t t_raw, bool skipped,
           std::int64_t out_raw, const ResultTiming& t) {
    out_ << fmt::format(
        "{},{},{:.17g},{},{},{},{:.17g},{},{},{},{},{},{},{}\n", row.line,
        lanes_.acc[lane].stats().name, row.t, t_raw, skipped ? 1 : 0, out_raw,
        std::ldexp(static_cast<double>(out_raw), -lanes_.units[lane]->out_format().frac_bits),
        t.issue, t.done, t.retire, header_.materials[row.material].name, row.light, row.x, row.y);
  }

 private:
  std::ostream& out_;
  const VectorHeader& header_;
  const SimLanes& lanes_;
};

struct SimRun {
  std::vector<TimingStats> timing;  // per lane
  std::uint64_t rows = 0;
};

// Clocked mode: per-cycle processes. Each lane reads its own stream (lanes run independently);
// the caller's reader only supplied the header.
SimRun run_clocked_mode(const SimOptions& o, ClockedOptions co, const RereadableInput& input,
                        SimLanes& lanes, SimDump* dump) {
  co.sink = SinkReady{o.sink_ready, o.seed};
  auto open = [&]() -> std::unique_ptr<RowStream> {
    return std::make_unique<VectorReaderStream>(input.open());
  };
  auto on_result = [&](const LaneOutput& r) {
    const std::size_t slot = lanes.slots.slot(r.row);
    lanes.acc[r.lane].add(slot, make_reference(lanes.slots, slot, r.row.t), r.t_raw, r.skipped,
                          r.out_raw);
    if (dump) dump->row(r.lane, r.row, r.t_raw, r.skipped, r.out_raw, r.timing);
    if (!lanes.activity.empty()) lanes.activity[r.lane].add(slot, r.t_raw);
  };
  SimRun run;
  run.timing = run_clocked(lanes.units, lanes.slots, open, co, on_result);
  run.rows = run.timing.empty() ? 0 : run.timing[0].results;
  return run;
}

// Fast mode: transaction level with temporal decoupling, fed by `reader`.
SimRun run_fast_mode(const SimOptions& o, VectorReader& reader, SimLanes& lanes, SimDump* dump,
                     bool progress) {
  const int threads = o.threads > 0 ? o.threads : default_threads();
  // Blocks of rows parsed on the threads (VectorReader::next_block): the same rows, line numbers
  // and errors as a row at a time.
  std::uint64_t shown = 0;
  std::function<bool(std::vector<VectorRow>&)> next = [&](std::vector<VectorRow>& rows) {
    const bool ok = reader.next_block(rows, threads);
    if (progress && ok && (reader.rows_read() >> 20) != shown) {
      shown = reader.rows_read() >> 20;
      std::fprintf(stderr, "\r%llu vectors", static_cast<unsigned long long>(reader.rows_read()));
    }
    return ok;
  };
  // A result at a time (the engine's row-at-a-time path) only for what needs each one.
  std::function<void(const FastResult&)> on_result;
  if (dump || !lanes.activity.empty()) {
    on_result = [&](const FastResult& r) {
      if (dump) dump->row(r.lane, *r.row, r.t_raw, r.skipped, r.out_raw, r.timing);
      if (!lanes.activity.empty()) lanes.activity[r.lane].add(lanes.slots.slot(*r.row), r.t_raw);
    };
  }
  FastOptions fo;
  fo.sink = SinkReady{o.sink_ready, o.seed};
  fo.batch = o.batch;
  fo.threads = threads;
  SimRun run;
  run.timing = run_fast_blocks(lanes.units, lanes.slots, next, fo, &lanes.acc, on_result);
  run.rows = reader.rows_read();
  return run;
}

// The JSON report (schema in src/eval/sim_report.md): run settings, then one entry per lane.
nlohmann::json build_report(const SimOptions& o, bool clocked, const SimLanes& lanes,
                            const SimRun& run) {
  nlohmann::json report = {{"glint_sim_report", kSimReportVersion},
                           {"vectors_file", std::filesystem::path(o.vectors).filename().string()},
                           {"rows", run.rows},
                           {"mode", clocked ? "clocked" : "fast"},
                           {"sink_ready", o.sink_ready},
                           {"seed", o.seed},
                           {"pixel_measure", pixel_measure_json(lanes.slots)},
                           {"slots", lanes.slots.params.size()},
                           {"per_light_slots", lanes.slots.per_light},
                           {"datapath_groups", lanes.slots.groups.size()},
                           {"chip", chip_json(o.chip, lanes.slots)}};
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t i = 0; i < lanes.units.size(); ++i) {
    list.push_back(unit_sim_report(*lanes.units[i], run.timing[i], lanes.acc[i].stats(),
                                   lanes.acc[i].digest(), !o.node.empty()));
    if (lanes.activity.empty()) continue;
    const LaneActivity& a = lanes.activity[i].activity();
    list.back()["activity"] = activity_json(a);
    // With a node as well: the stream's energy (the same count as glint render's).
    if (const EnergyWeights* w = o.node.empty() ? nullptr : find_energy(o.node))
      list.back()["energy"] = energy_json(lane_energy(unit_cost(*lanes.units[i]), a, *w));
  }
  report["units"] = list;
  return report;
}

// Writes --report, commits every output (all or none), then prints the report (JSON or table) on
// stdout; the table on stderr when an output is standard output.
void write_outputs(const SimOptions& o, SimPlan& plan, std::uint64_t rows,
                   const nlohmann::json& report, const SlotMap& lanes_slots) {
  const bool clocked = plan.clocked;
  if (plan.report) plan.report->stream() << report.dump(2) << "\n";
  plan.outputs.commit();
  if (o.json) {
    print_json(report);
    return;
  }
  std::ostream& out = plan.outputs.writes_stdout() ? std::cerr : std::cout;
  out << fmt::format("{}: {} vectors, {} mode, sink ready {}{}; {}\n", o.vectors, rows,
                     clocked ? "clocked" : "fast", o.sink_ready,
                     o.vcd.empty() ? "" : ", VCD " + o.vcd, pixel_measure_line(lanes_slots))
      << chip_line(report.at("chip")) << format_sim_table(report);
  for (const auto& u : report["units"]) {
    out << fmt::format("  {}: {}\n", u["unit"].get<std::string>(), u["spec"].get<std::string>());
    // Beside the lane's area_ge: what it stands for in shared hardware (sfu), stated as such.
    const nlohmann::json& e = u.at("elaboration");
    if (const auto share = e.find("hardware_share"); share != e.end())
      out << fmt::format("    {}\n", (*share)["statement"].get<std::string>());
    if (const auto a = u.find("activity"); a != u.end())
      out << "    " << format_activity(*a) << "\n";
    if (const auto e = u.find("energy"); e != u.end()) out << "    " << format_energy(*e) << "\n";
    if (u.contains("node")) out << "    " << node_line(u.at("node")) << "\n";
  }
}

int run_sim(const SimOptions& o) {
  SimPlan plan;
  check_sim_options(o, plan);
  if (options_only()) return kExitOk;
  // The clocked model reads the stream once per lane: standard input or a pipe is kept in an
  // anonymous temporary file (input_source.h); fast mode reads it once, as it comes.
  std::unique_ptr<RereadableInput> input;
  std::unique_ptr<VectorReader> reader;
  if (plan.clocked) {
    input = std::make_unique<RereadableInput>(o.vectors);
    reader = input->open();
  } else {
    reader = std::make_unique<VectorReader>(o.vectors);
  }
  SimLanes lanes;
  try {
    make_lanes(with_eps_measure(reader->header(), o.eps_measure), plan.specs, o.display_bits,
               o.chip, lanes);
  } catch (const ResourceLimitError& e) {
    refuse_size(o.vectors, e);  // more slots or contract work than a run may take
  }
  if (plan.gating)
    for (const SpecularUnit* u : lanes.units) lanes.activity.emplace_back(*u, *plan.gating);
  std::unique_ptr<SimDump> dump;
  if (plan.dump) dump = std::make_unique<SimDump>(*plan.dump, reader->header(), lanes);
  const bool progress = isatty(STDERR_FILENO);
  const SimRun run = plan.clocked
                         ? run_clocked_mode(o, plan.clocked_options, *input, lanes, dump.get())
                         : run_fast_mode(o, *reader, lanes, dump.get(), progress);
  if (progress && run.rows >= 0x100000) std::fprintf(stderr, "\n");
  write_outputs(o, plan, run.rows, build_report(o, plan.clocked, lanes, run), lanes.slots);
  return kExitOk;
}

}  // namespace

void add_sim_command(CLI::App& app, int& status) {
  auto o = std::make_shared<SimOptions>();
  CLI::App* sub = app.add_subcommand(
      "sim", "Cycle-approximate SystemC simulation of units side by side on a vector file");
  sub->add_option("VECTORS", o->vectors, "Vector file (see traces/README.md); - for stdin")
      ->required();
  sub->add_option("--unit", o->units,
                  fmt::format("Unit SPEC NAME[:key=value,...] (repeatable, at most {}; default: "
                              "the default set, which glint units marks); timing keys: buffer, "
                              "schlick divider",
                              kMaxUnitOptions));
  sub->add_option("--report", o->report,
                  "Write the JSON report to this file (atomically; - for stdout)");
  sub->add_option("--dump", o->dump, "Per-result CSV with cycle stamps (atomically; - for stdout)");
  sub->add_option("--vcd", o->vcd,
                  "VCD trace (clocked mode) + GTKWave save file beside it; .fst: FST; - : VCD "
                  "on stdout (no save file)");
  sub->add_option("--vcd-window", o->vcd_window,
                  "FIRST:LAST vector indices to trace (0..2^64-1, FIRST <= LAST; needs --vcd)");
  sub->add_option("--mode", o->mode, "fast | clocked | auto (clocked when --vcd is given)")
      ->check(CLI::IsMember({"fast", "clocked", "auto"}))
      ->capture_default_str();
  sub->add_option("--sink-ready", o->sink_ready,
                  "Probability the sink is ready in a cycle, in [0.01, 1] (a run takes ~vectors / "
                  "P cycles)")
      ->capture_default_str();
  add_seed_option(sub, o->seed, o->seed_given);
  sub->add_option("--batch", o->batch,
                  "Fast mode: requests per time quantum (1..16777216; with --dump, else at least "
                  "262144)")
      ->check(CLI::Range(1, 1 << 24))
      ->capture_default_str();
  add_threads_option(sub, o->threads);
  add_display_bits_option(sub, o->display_bits);
  add_chip_option(sub, o->chip);
  add_eps_measure_option(sub, o->eps_measure);
  sub->add_option(
      "--activity", o->activity,
      "GATING: also count each lane's register bit toggles and clocked bits per stage "
      "on the stream (a result at a time: slower); what a skipped request does: none "
      "(fed to the datapath), operand (held out of it, as glint rtl's lane), clock "
      "(held out and clock-gated); with --node, also the energy per request at the node");
  add_node_option(sub, o->node);
  sub->add_flag("--json", o->json, "Print the report as one JSON document on stdout");
  sub->callback([sub, o, &status] {
    o->batch_given = sub->count("--batch") > 0;
    status = guarded([&] { return run_sim(*o); });
  });
}

}  // namespace glint::cli
