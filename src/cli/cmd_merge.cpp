// glint merge: shard reports of one sweep (glint sweep --shard K/N -o shardK.json) joined into the
// report the unsharded sweep writes, byte for byte.
#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "cli/cli.h"
#include "image/image.h"
#include "sweep/outputs.h"
#include "sweep/report.h"
#include "sweep/sweep_html.h"

namespace glint::cli {
namespace {

struct MergeOptions {
  std::vector<std::string> shards;
  std::string out, csv, plot, html;
  bool json = false;
};

int run_merge(const MergeOptions& o) {
  const SweepOutputs outputs = sweep_outputs(o.out, o.csv, o.plot);
  if (outputs.json.empty() && outputs.csv.empty() && outputs.plot_dir.empty() && o.html.empty() &&
      !o.json)
    throw std::invalid_argument(
        "merge: nothing to write (give -o OUT.json, --csv, --plot, --html or --json)");
  if (options_only()) return kExitOk;
  // Plots (--plot, the page's) draw text: a bad font is refused before any work.
  if (!outputs.plot_dir.empty() || !o.html.empty()) load_text_font();
  OutputSet set;
  for (const std::string& path : o.shards) set.add_input("SHARD", path);
  if (o.json) set.claim_stdout("--json");
  const SweepOutputFiles files = declare_sweep_outputs(set, outputs);
  OutputFile* page = o.html.empty() ? nullptr : &set.add("--html", o.html);
  std::vector<std::pair<std::string, nlohmann::json>> shards;
  for (const std::string& path : o.shards) shards.emplace_back(path, read_sweep_report(path));
  const nlohmann::json report = merge_sweep_reports(shards);
  if (page) page->stream() << sweep_html(report, html_run_info());
  return emit_sweep_report(report, files, set, o.json);
}

}  // namespace

void add_merge_command(CLI::App& app, int& status) {
  auto o = std::make_shared<MergeOptions>();
  CLI::App* sub = app.add_subcommand(
      "merge", "Join the shard reports of one sweep into the report of the whole sweep");
  sub->add_option("SHARD", o->shards, "Shard reports (glint sweep --shard K/N -o FILE.json)")
      ->required();
  sub->add_option("-o,--out", o->out, "Write the merged report: FILE.json or FILE.csv");
  sub->add_option("--csv", o->csv, "Also write the CSV table here");
  sub->add_option("--plot", o->plot, "Write the plots of the merged sweep into this folder");
  sub->add_option("--html", o->html, "Write the merged sweep's page here (as glint sweep --html)");
  sub->add_flag("--json", o->json, "Print the merged report on stdout");
  sub->callback([o, &status] { status = guarded([&] { return run_merge(*o); }); });
}

}  // namespace glint::cli
