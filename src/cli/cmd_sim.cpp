// glint sim: the cycle-approximate SystemC model of the specular units over a vector stream.
#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "cli/cli.h"
#include "eval/sim_report.h"
#include "io/atomic_file.h"
#include "io/vectors.h"
#include "rtl_model/clocked_sim.h"
#include "rtl_model/fast_sim.h"

namespace glint::cli {
namespace {

struct SimOptions {
  std::string vectors;
  std::vector<std::string> units;
  std::string report, dump, vcd, vcd_window, mode = "auto";
  double sink_ready = 1.0;
  std::uint64_t seed = 1;
  std::size_t batch = 4096;
  bool json = false;
};

void write_atomic(const std::string& path, const std::string& text) {
  AtomicOutputFile f(path);
  f.stream() << text;
  f.commit();
}

int run_sim(const SimOptions& o) {
  std::vector<UnitSpec> specs;
  for (const auto& s : o.units.empty() ? unit_names() : o.units)
    specs.push_back(parse_unit_spec(s));
  if (!(o.sink_ready > 0 && o.sink_ready <= 1))
    throw std::invalid_argument("--sink-ready must be in (0, 1]");
  for (const auto* out : {&o.report, &o.dump, &o.vcd}) {
    if (out->empty()) continue;
    std::error_code ec;
    if (std::filesystem::equivalent(o.vectors, *out, ec))
      throw std::invalid_argument(fmt::format("output {} is the input vector file", *out));
    check_output_path(*out);  // before simulating, not after
  }
  const bool clocked = o.mode == "clocked" || (o.mode == "auto" && !o.vcd.empty());
  if (!clocked && !o.vcd.empty())
    throw std::invalid_argument("--vcd needs the clocked mode (--mode clocked or auto)");
  ClockedOptions co;
  co.vcd_path = o.vcd;
  if (!o.vcd_window.empty()) {
    const auto colon = o.vcd_window.find(':');
    try {
      if (colon == std::string::npos) throw std::invalid_argument("no ':'");
      std::size_t used = 0;
      co.vcd_first = std::stoull(o.vcd_window.substr(0, colon), &used);
      if (used != colon) throw std::invalid_argument("first");
      const std::string last = o.vcd_window.substr(colon + 1);
      co.vcd_last = std::stoull(last, &used);
      if (used != last.size() || co.vcd_last < co.vcd_first) throw std::invalid_argument("last");
    } catch (const std::exception&) {
      throw std::invalid_argument(
          fmt::format("--vcd-window '{}': expected FIRST:LAST vector indices with FIRST <= LAST",
                      o.vcd_window));
    }
  }

  VectorReader reader(o.vectors);
  const SlotMap slots = make_slots(reader.header());
  const bool colour = stream_is_coloured(reader.header());
  co.colour_stage = colour;
  co.sink = SinkReady{o.sink_ready, o.seed};
  std::vector<std::unique_ptr<SpecularUnit>> owned;
  std::vector<const SpecularUnit*> units;
  for (const auto& s : specs) {
    owned.push_back(make_unit(s, slots.params));
    units.push_back(owned.back().get());
  }
  std::vector<LaneAccumulator> acc;
  for (const auto* u : units) acc.emplace_back(*u);
  std::vector<std::string> names;
  for (const auto* u : units) names.push_back(u->name());
  const auto labels = unit_labels(names);
  for (std::size_t i = 0; i < units.size(); ++i) acc[i].stats().name = labels[i];

  std::unique_ptr<AtomicOutputFile> dump;
  if (!o.dump.empty()) {
    dump = std::make_unique<AtomicOutputFile>(o.dump);
    dump->stream() << "line,unit,t,t_raw,skipped,fixed_raw,fixed,issue,done,retire\n";
  }
  const bool progress = isatty(STDERR_FILENO);
  std::function<bool(VectorRow&)> next = [&](VectorRow& row) {
    const bool ok = reader.next(row);
    if (progress && ok && (reader.rows_read() & 0xFFFFF) == 0)
      std::fprintf(stderr, "\r%llu vectors", static_cast<unsigned long long>(reader.rows_read()));
    return ok;
  };
  auto dump_row = [&](std::size_t lane, const VectorRow& row, std::int64_t t_raw, bool skipped,
                      std::int64_t out_raw, const ResultTiming& t) {
    dump->stream() << fmt::format(
        "{},{},{:.17g},{},{},{},{:.17g},{},{},{}\n", row.line, acc[lane].stats().name, row.t, t_raw,
        skipped ? 1 : 0, out_raw,
        std::ldexp(static_cast<double>(out_raw), -units[lane]->out_format().frac_bits), t.issue,
        t.done, t.retire);
  };
  std::vector<TimingStats> timing;
  std::uint64_t rows = 0;
  if (clocked) {
    // Each lane reads its own stream (lanes run independently); `reader` only supplied the header.
    auto open = [&]() -> std::unique_ptr<RowStream> {
      return std::make_unique<VectorReaderStream>(o.vectors);
    };
    auto on_result = [&](const LaneOutput& r) {
      const std::size_t slot = slots.slot(r.row);
      acc[r.lane].add(slot, make_reference(slots, slot, r.row.t), r.t_raw, r.skipped, r.out_raw);
      if (dump) dump_row(r.lane, r.row, r.t_raw, r.skipped, r.out_raw, r.timing);
    };
    timing = run_clocked(units, slots, open, co, on_result);
    rows = timing.empty() ? 0 : timing[0].results;
  } else {
    std::function<void(const FastResult&)> on_result;
    if (dump) {
      on_result = [&](const FastResult& r) {
        dump_row(r.lane, *r.row, r.t_raw, r.skipped, r.out_raw, r.timing);
      };
    }
    FastOptions fo;
    fo.sink = co.sink;
    fo.batch = o.batch;
    fo.colour_stage = colour;
    timing = run_fast(units, slots, next, fo, &acc, on_result);
    rows = reader.rows_read();
  }
  if (progress && rows >= 0x100000) std::fprintf(stderr, "\n");

  nlohmann::json report = {{"glint_sim_report", kSimReportVersion},
                           {"vectors_file", std::filesystem::path(o.vectors).filename().string()},
                           {"rows", rows},
                           {"mode", clocked ? "clocked" : "fast"},
                           {"sink_ready", o.sink_ready},
                           {"seed", o.seed},
                           {"slots", slots.params.size()},
                           {"per_light_slots", slots.per_light}};
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t i = 0; i < units.size(); ++i)
    list.push_back(unit_sim_report(*units[i], timing[i], acc[i].stats(), acc[i].digest(), colour));
  report["units"] = list;

  if (dump) dump->commit();
  if (!o.report.empty()) write_atomic(o.report, report.dump(2) + "\n");
  if (o.json) {
    print_json(report);
  } else {
    std::cout << fmt::format("{}: {} vectors, {} mode, sink ready {}{}\n", o.vectors, rows,
                             clocked ? "clocked" : "fast", o.sink_ready,
                             o.vcd.empty() ? "" : ", VCD " + o.vcd)
              << format_sim_table(report);
    for (const auto& u : report["units"])
      std::cout << fmt::format("  {}: {}\n", u["unit"].get<std::string>(),
                               u["spec"].get<std::string>());
  }
  return kExitOk;
}

}  // namespace

void add_sim_command(CLI::App& app, int& status) {
  auto o = std::make_shared<SimOptions>();
  CLI::App* sub = app.add_subcommand(
      "sim", "Cycle-approximate SystemC simulation of units side by side on a vector file");
  sub->add_option("VECTORS", o->vectors, "Vector file (see traces/README.md)")->required();
  sub->add_option("--unit", o->units,
                  "Unit SPEC NAME[:key=value,...] (repeatable; default all five); timing keys: "
                  "buffer, schlick divider");
  sub->add_option("--report", o->report, "Write the JSON report to this file (atomically)");
  sub->add_option("--dump", o->dump, "Per-result CSV with cycle stamps (atomically)");
  sub->add_option("--vcd", o->vcd, "VCD trace (clocked mode) + GTKWave save file beside it");
  sub->add_option("--vcd-window", o->vcd_window, "FIRST:LAST vector indices to trace");
  sub->add_option("--mode", o->mode, "fast | clocked | auto (clocked when --vcd is given)")
      ->check(CLI::IsMember({"fast", "clocked", "auto"}))
      ->capture_default_str();
  sub->add_option("--sink-ready", o->sink_ready, "Probability the sink is ready in a cycle")
      ->capture_default_str();
  sub->add_option("--seed", o->seed, "Seed of the sink backpressure pattern")
      ->capture_default_str();
  sub->add_option("--batch", o->batch, "Fast mode: requests per time quantum")
      ->check(CLI::Range(1, 1 << 24))
      ->capture_default_str();
  sub->add_flag("--json", o->json, "Print the report as one JSON document on stdout");
  sub->callback([o, &status] { status = guarded([&] { return run_sim(*o); }); });
}

}  // namespace glint::cli
