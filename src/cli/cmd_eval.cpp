// glint eval: untimed datapaths over a vector file.
#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <memory>

#include "cli/cli.h"
#include "eval/chip_report.h"
#include "eval/evaluate.h"
#include "eval/parallel.h"
#include "io/input_error.h"
#include "io/output_set.h"
#include "io/vectors.h"

namespace glint::cli {
namespace {

constexpr std::size_t kEvalBlockRows = 262144;

struct EvalOptions {
  std::string vectors;
  std::vector<std::string> units;
  std::string dump;
  int display_bits = 8;
  Chip chip;  // --chip
  EpsMeasure eps_measure = EpsMeasure::kLuminance;
  int threads = 0;  // --threads N; 0: every core
  bool json = false;
};

int run_eval(const EvalOptions& o) {
  const std::vector<UnitSpec> specs = specs_for_chip(parse_unit_options(o.units), o.chip);
  if (options_only()) return kExitOk;
  // Outputs first, before any work: checked, their temporaries made (output_set.h).
  OutputSet outputs;
  outputs.add_input("VECTORS", o.vectors);
  if (o.json) outputs.claim_stdout("--json");
  OutputFile* dump = o.dump.empty() ? nullptr : &outputs.add("--dump", o.dump, true);
  VectorReader reader(o.vectors);
  std::unique_ptr<Evaluator> evaluator;
  try {
    evaluator = std::make_unique<Evaluator>(with_eps_measure(reader.header(), o.eps_measure), specs,
                                            o.display_bits, o.chip);
  } catch (const SlotCapacityError& e) {
    refuse_chip(o.chip, e);  // the stream needs more than the chip holds
  } catch (const ResourceLimitError& e) {
    refuse_size(o.vectors, e);  // more slots or contract work than a run may take
  }
  Evaluator& ev = *evaluator;

  if (dump)
    dump->stream() << "line,material,light,x,y,t,t_raw,unit,reference,model,fixed,fixed_raw,"
                      "skipped\n";
  const auto& materials = reader.header().materials;
  auto write = [&](const EvalRecord& r) {
    dump->stream() << fmt::format("{},{},{},{},{},{:.17g},{},{},{:.17g},{:.17g},{:.17g},{},{}\n",
                                  r.row->line, materials[r.row->material].name, r.row->light,
                                  r.row->x, r.row->y, r.row->t, r.t_raw, ev.label(r.unit),
                                  r.reference, r.model, r.fixed, r.fixed_raw, r.skipped ? 1 : 0);
  };
  const bool progress = isatty(STDERR_FILENO);
  const int threads = o.threads > 0 ? o.threads : default_threads();
  if (dump) {
    VectorRow row;
    while (reader.next(row)) ev.add(row, write);
  } else {
    // Blocks of rows through the evaluation engine (eval/engine.h): memory stays flat.
    std::vector<VectorRow> rows, next;
    const auto shown = [&] {
      if (progress && reader.rows_read() >= 0x100000)
        std::fprintf(stderr, "\r%llu vectors", static_cast<unsigned long long>(reader.rows_read()));
    };
    if (ev.overlaps_side_work(threads)) {
      // The next rows are parsed on one thread beside the lanes' work on these (the engine's side
      // work), a block of input per step: no thread waits for the parse or for the last lane.
      bool ended = false;
      const auto read = [&](int parse_threads) {
        ended = ended || !reader.append_block(next, parse_threads);
        return !ended && next.size() < kEvalBlockRows;
      };
      while (read(threads)) {
      }
      while (!next.empty()) {
        std::swap(rows, next);
        next.clear();
        ev.add_rows(rows.data(), rows.size(), threads, [&] { return read(1); });
        shown();
      }
    } else {
      // Blocks parsed on the threads, then evaluated on them.
      while (reader.append_block(rows, threads)) {
        if (rows.size() < kEvalBlockRows) continue;
        ev.add_rows(rows.data(), rows.size(), threads);
        rows.clear();
        shown();
      }
      if (!rows.empty()) ev.add_rows(rows.data(), rows.size(), threads);
      shown();
    }
  }
  if (progress && reader.rows_read() >= 0x100000) std::fprintf(stderr, "\n");
  outputs.commit();

  if (o.json) {
    nlohmann::json j = ev.to_json();
    j["vectors_file"] = o.vectors;
    j["rows"] = reader.rows_read();
    print_json(j);
  } else {
    // With an output on standard output ("-"), the summary goes to stderr.
    std::ostream& out = outputs.writes_stdout() ? std::cerr : std::cout;
    const SlotMap& slots = ev.slots();
    out << fmt::format("{}: {} vectors, {} slots{}, {} datapath groups; {}\n", o.vectors,
                       reader.rows_read(), slots.params.size(),
                       slots.per_light ? " (lights change some materials' tau)" : "",
                       slots.groups.size(), pixel_measure_line(slots))
        << chip_line(chip_json(ev.chip(), slots)) << format_eval_table(ev.stats())
        << format_parts_table(ev.stats()) << "elaboration (what the scene built):\n"
        << format_elaboration(ev.stats());
    for (const auto& s : ev.stats()) out << fmt::format("  {}: {}\n", s.name, s.spec);
  }
  return kExitOk;
}

}  // namespace

void add_eval_command(CLI::App& app, int& status) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* sub =
      app.add_subcommand("eval", "Run the untimed bit-accurate datapaths over a vector file");
  sub->add_option("VECTORS", o->vectors, "Vector file (see traces/README.md); - for stdin")
      ->required();
  sub->add_option("--unit", o->units,
                  fmt::format("Unit SPEC NAME[:key=value,...] (repeatable, at most {}; default: "
                              "the default set, which glint units marks; keys: glint units)",
                              kMaxUnitOptions));
  sub->add_option("--dump", o->dump,
                  "Per-vector CSV (written atomically; - for stdout, then the summary goes to "
                  "stderr)");
  add_threads_option(sub, o->threads);
  add_display_bits_option(sub, o->display_bits);
  add_chip_option(sub, o->chip);
  add_eps_measure_option(sub, o->eps_measure);
  sub->add_flag("--json", o->json, "Print one JSON document on stdout");
  sub->callback([o, &status] { status = guarded([&] { return run_eval(*o); }); });
}

}  // namespace glint::cli
