// glint rtl: synthesizable Verilog-2005 of one lane of a unit (tau comparator, the unit's
// pipeline, merge buffer, valid/ready handshakes), its timing constraints (SDC), a self-checking
// testbench and its vectors.
//
// The testbench's requests are every input code 0..1.0 of every slot (slot by slot), then, with
// --vectors, the file's rows in order; what each must give and when comes from the same C++ the
// rest of glint runs: SpecularUnit::eval_with_skip for the result, TimingEngine (src/timing/
// timing.h) under the --sink-ready pattern for the edges it is accepted at and leaves at.
#include <fmt/format.h>

#include <iostream>

#include "cli/cli.h"
#include "cli/rtl_input.h"
#include "hdl/sdc.h"
#include "io/output_set.h"
#include "timing/timing.h"
#include "units/catalogue.h"
#include "units/common.h"

namespace glint::cli {
namespace {

// A testbench run stays within this many requests (~64 bytes of vector file each: 1 GiB).
constexpr std::size_t kMaxTbVectors = std::size_t{1} << 24;

struct RtlOptions {
  std::string spec;
  RtlInputOptions input;
  std::string out_dir;
  double sink_ready = 1.0;
  std::uint64_t seed = 1;
  bool seed_given = false;
  bool no_sweep = false;
  bool json = false;
  double clock_period_ns = hdl::kDefaultClockPeriodNs;
};

std::vector<hdl::TbVector> tb_vectors(const RtlDesign& d, const RtlOptions& o) {
  const SpecularUnit& u = *d.unit;
  std::vector<hdl::TbVector> v;
  const std::int64_t one = u.in_format().raw_one();
  const auto add = [&](std::int64_t t, std::size_t slot) {
    if (v.size() >= kMaxTbVectors)
      throw std::invalid_argument(fmt::format(
          "the testbench would hold more than {} requests ({} slots x {} input codes{}): use "
          "--no-sweep or a narrower input format",
          kMaxTbVectors, u.slots(), one + 1, o.input.vectors.empty() ? "" : ", plus the rows"));
    hdl::TbVector x;
    x.t = t;
    x.slot = static_cast<std::uint32_t>(slot);
    x.skipped = u.skip(slot, t);
    x.result = u.eval_with_skip(slot, t);
    v.push_back(x);
  };
  if (!o.no_sweep)
    for (std::size_t s = 0; s < u.slots(); ++s)
      for (std::int64_t t = 0; t <= one; ++t) add(t, s);
  if (!o.input.vectors.empty()) {
    VectorReader reader(o.input.vectors);
    VectorRow row;
    while (reader.next(row)) add(quantize_input(row.t, u.in_format()), d.slots.slot(row));
  }
  if (v.empty())
    throw std::invalid_argument("--no-sweep without --vectors rows: the testbench has no request");
  TimingEngine timing(u.timing(), SinkReady{o.sink_ready, o.seed});
  for (hdl::TbVector& x : v) {
    const ResultTiming r = timing.next(x.skipped);
    x.issue = r.issue;
    x.retire = r.retire;
  }
  return v;
}

int run_rtl(const RtlOptions& o) {
  const UnitSpec spec = parse_unit_spec(o.spec);
  check_rtl_input(o.input);
  if (!(o.sink_ready >= kMinSinkReady && o.sink_ready <= 1))
    throw std::invalid_argument(fmt::format("--sink-ready must be in [{}, 1]", kMinSinkReady));
  require_backpressure_for_seed(o.seed_given, o.sink_ready);
  // Without the sweep the testbench holds only the rows of --vectors (a scene or --material gives
  // slots, not rows).
  if (o.no_sweep && o.input.vectors.empty())
    throw std::invalid_argument(
        "--no-sweep leaves only the rows of --vectors in the testbench: it needs --vectors");
  if (o.out_dir.empty()) throw std::invalid_argument("-o DIR: the folder to write into");
  if (options_only()) return kExitOk;
  OutputSet out;
  if (!o.input.vectors.empty()) out.add_input("--vectors", o.input.vectors);
  if (!o.input.scene.empty()) out.add_input("--scene", o.input.scene);
  if (o.json) out.claim_stdout("--json");
  out.make_folder("-o", o.out_dir);
  // One module a file, named after it (verilator -Wall's DECLFILENAME).
  const std::string base = o.out_dir + "/glint_" + spec.name;
  OutputFile& lane = out.add("-o", base + "_lane.v");
  OutputFile& datapath = out.add("-o", base + "_datapath.v");
  OutputFile& tb = out.add("-o", base + "_tb.v");
  OutputFile& vec = out.add("-o", base + "_tb.vec");
  OutputFile& sdc = out.add("-o", base + "_lane.sdc");
  // tables=ram: the table writes the testbench loads through the write port.
  const RtlDesign d =
      make_rtl_design(spec, rtl_header(o.input), rtl_input_name(o.input), o.input.chip);
  OutputFile* cfg = d.lane.tables_ram ? &out.add("-o", base + "_tb.cfg") : nullptr;

  const std::vector<hdl::TbVector> v = tb_vectors(d, o);
  const std::string vec_name = "glint_" + spec.name + "_tb.vec";
  lane.stream() << d.lane_verilog;
  datapath.stream() << d.datapath_verilog;
  const std::string cfg_name = "glint_" + spec.name + "_tb.cfg";
  tb.stream() << hdl::testbench_module(d.lane, hdl::TbSink{o.sink_ready, o.seed}, v.size(),
                                       vec_name, cfg_name);
  vec.stream() << hdl::testbench_vectors(d.lane, v);
  if (cfg != nullptr) cfg->stream() << hdl::testbench_writes(d.lane);
  sdc.stream() << hdl::lane_sdc(d.lane, o.clock_period_ns);
  out.commit();

  const UnitTiming t = d.unit->timing();
  nlohmann::json files{lane.path(), datapath.path(), tb.path(), vec.path()};
  if (cfg != nullptr) files.push_back(cfg->path());
  files.push_back(sdc.path());
  nlohmann::json j{{"unit", d.unit->name()},
                   {"spec", d.unit->canonical_spec()},
                   {"files", files},
                   {"latency", t.latency},
                   {"ii", t.ii},
                   {"buffer_depth", t.buffer_depth},
                   {"slots", d.unit->slots()},
                   {"datapath_groups", d.unit->datapath_groups()},
                   {"tb_vectors", v.size()},
                   {"tb_cycles", v.back().retire + 1},
                   {"sink_ready", o.sink_ready},
                   {"seed", o.seed},
                   {"clock_period_ns", o.clock_period_ns}};
  if (o.json) {
    print_json(j);
  } else {
    std::cout << fmt::format(
        "{}: {} (L = {}, II = {}, B = {}; {} slots, {} datapath groups)\n  {}\n  {}\n  {}\n  {} "
        "({} requests, {} cycles)\n",
        d.unit->name(), d.unit->canonical_spec(), t.latency, t.ii, t.buffer_depth, d.unit->slots(),
        d.unit->datapath_groups(), lane.path(), datapath.path(), tb.path(), vec.path(), v.size(),
        v.back().retire + 1);
    if (cfg != nullptr)
      std::cout << fmt::format("  {} ({} table writes)\n", cfg->path(),
                               hdl::testbench_write_count(d.lane));
    std::cout << fmt::format("  {} (clock {:g} ns)\n", sdc.path(), o.clock_period_ns);
  }
  return kExitOk;
}

}  // namespace

void add_rtl_command(CLI::App& app, int& status) {
  auto o = std::make_shared<RtlOptions>();
  CLI::App* sub = app.add_subcommand(
      "rtl",
      "Write synthesizable Verilog of one lane of a unit, a self-checking testbench and its "
      "vectors");
  sub->add_option("SPEC", o->spec, "Unit SPEC NAME[:key=value,...] (keys: glint units)")
      ->required();
  add_rtl_input_options(sub, o->input);
  sub->add_option("-o,--out", o->out_dir, "Folder to write into (made if missing)")->required();
  sub->add_option("--sink-ready", o->sink_ready,
                  "The testbench's sink is ready in a cycle with this probability (backpressure)");
  add_seed_option(sub, o->seed, o->seed_given);
  sub->add_flag("--no-sweep", o->no_sweep,
                "Leave out the sweep of every input code of every slot (test only the rows)");
  add_clock_period_option(sub, o->clock_period_ns);
  sub->add_flag("--json", o->json, "Print one JSON document on stdout");
  sub->callback([o, &status] { status = guarded([&] { return run_rtl(*o); }); });
}

}  // namespace glint::cli
