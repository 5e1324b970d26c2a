// The files a sweep (or a merge of shards) writes, checked before anything runs and written at the
// end, each atomically; and the summary it prints.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace glint {

struct SweepOutputs {
  std::string json;      // the report (-o FILE.json)
  std::string csv;       // the CSV (-o FILE.csv or --csv FILE)
  std::string plot_dir;  // --plot DIR: error_vs_area.{svg,png}, error_vs_throughput.{svg,png}
};

// -o FILE: a .json file is the report, a .csv file the CSV. Throws std::invalid_argument naming
// -o for any other extension, or when the output it names is already given.
void add_output_by_extension(SweepOutputs& outputs, const std::string& path);

// Every output path is writable in principle (not a device, FIFO or folder; the plot folder not a
// file), none is an input and no two are the same file. Throws std::invalid_argument or
// OutputError naming the option.
void check_sweep_outputs(const SweepOutputs& outputs, const std::vector<std::string>& inputs);

// Writes every output given (JSON, CSV, plots).
void write_sweep_outputs(const nlohmann::json& report, const SweepOutputs& outputs);

// What `glint sweep` prints without --json: the input, the counts and the three fronts.
std::string format_sweep_summary(const nlohmann::json& report);

}  // namespace glint
