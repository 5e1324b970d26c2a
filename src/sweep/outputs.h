// The files a sweep (or a merge of shards) writes, declared in an OutputSet before anything runs
// (checked, temporaries made, the plot folder created) and committed together at the end; and the
// summary it prints.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "io/output_set.h"

namespace glint {

struct SweepOutputs {
  std::string json;      // the report (-o FILE.json)
  std::string csv;       // the CSV (-o FILE.csv or --csv FILE)
  std::string plot_dir;  // --plot DIR: error_vs_area.{svg,png}, error_vs_throughput.{svg,png}
};

// The outputs of -o FILE (by extension), --csv FILE and --plot DIR (each may be empty). Throws
// std::invalid_argument when -o and --csv both name the CSV.
SweepOutputs sweep_outputs(const std::string& out, const std::string& csv, const std::string& plot);

// -o FILE: a .json file is the report, a .csv file the CSV. Throws std::invalid_argument naming
// -o for any other extension, or when the output it names is already given.
void add_output_by_extension(SweepOutputs& outputs, const std::string& path);

// The declared files of a sweep's outputs (null / empty: not asked for).
struct SweepOutputFiles {
  OutputFile* json = nullptr;
  OutputFile* csv = nullptr;
  std::vector<std::pair<std::string, OutputFile*>> plots;  // file name in the folder, file
};

// Declares every output given in `set` (io/output_set.h: refusals name the option; the plot folder
// is made, and removed again if the run fails).
SweepOutputFiles declare_sweep_outputs(OutputSet& set, const SweepOutputs& outputs);

// Writes the report, the CSV and the plots into their declared files; the caller commits the set.
void write_sweep_outputs(const nlohmann::json& report, const SweepOutputFiles& files);

// What `glint sweep` prints without --json: the input, the counts and the three fronts.
std::string format_sweep_summary(const nlohmann::json& report);

}  // namespace glint
