// The columns of a sweep's results (the CSV's, in order) and the measures budgets and plots name.
//
// A report row is a JSON object (report.h); each column is one scalar in it, named as the CSV
// names it: "area_ge", "throughput", "max_lsb", "weighted.max_lsb", "parts.input.max_abs",
// "image.max_lsb", ... Every numeric column is a measure. Measures in display LSBs may name
// another depth by a suffix: "max_lsb10" is max_abs x (2^10 - 1), whatever --display-bits was,
// and "lsb8" is an alias of "max_lsb8" (issue 9's "lsb8<=1"; measure_aliases lists every alias).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace glint {

enum class ColumnKind { kInteger, kNumber, kText, kFlag };

struct SweepColumn {
  std::string name;     // CSV header and measure name
  std::string pointer;  // JSON pointer into a report row
  ColumnKind kind = ColumnKind::kNumber;
  bool scene_only = false;  // image-level columns: only when the input is a scene
  bool node_only = false;   // the node's and the energy's: only in a sweep with --node
};

// Every column in CSV order (the image-level ones among them, flagged scene_only).
const std::vector<SweepColumn>& sweep_columns();

// Operation kinds of the energy proxy (cost/cost_model.h), the CSV's ops_<kind> columns. Fixed,
// so that every shard of a sweep writes the same columns.
const std::vector<std::string>& operation_kinds();

// A measure a budget or --error-measure names, resolved against the columns.
struct MeasureRef {
  std::string name;  // as written
  std::string pointer;
  // LSB measures at an explicit depth: the value is the pointer's absolute error x (2^bits - 1).
  int bits = 0;
};

// Other names of measures: the short headings the text tables had before they took the measures'
// names, and the --objective words. An alias of an LSB measure takes a depth suffix as the measure
// does ("wlsb8" is "weighted.max_lsb8"). src/cli/guide/size.md lists them ("Measure names").
struct MeasureAlias {
  const char* alias;
  const char* measure;
  const char* origin;  // where the alias comes from
};
const std::vector<MeasureAlias>& measure_aliases();

// Resolves a measure name or alias; nullopt if no column (or LSB measure with a depth suffix) has
// it. The reference keeps the name as written.
// `scene`: image-level columns exist.
std::optional<MeasureRef> find_measure(std::string_view name, bool scene);
// The same, throwing std::invalid_argument naming `option` and listing the measures.
MeasureRef measure_or_throw(std::string_view name, bool scene, const std::string& option);

// The measure's value in a row; nullopt when absent or null (an infinite PSNR, a missing part).
std::optional<double> measure_value(const nlohmann::json& row, const MeasureRef& m);

// The measures --error-measure accepts: error columns where lower is better (not t_at_*, counts,
// PSNR or the highlight ratios).
bool is_error_measure(const MeasureRef& m);

// A measure of the contract's stated bounds (bound_lsb, weighted.bound_lsb, parts.*.bound, ...):
// its value is an estimate in a row whose bounds are (row_bounds_exact).
bool is_bound_measure(const MeasureRef& m);
// Whether a row's stated bounds are bounds: false when some slot's are estimates (its "exact":
// sampled codes of an input finer than 2^-20 that the enclosure could not certify,
// eval/contract.md). A row without slots (refused) states none: true.
bool row_bounds_exact(const nlohmann::json& row);

// A comma-separated list of conditions MEASURE OP VALUE (OP one of <=, <, >=, >), all of which
// must hold: "max_lsb8<=1,mismatch_fraction<0.01". Errors name `option` (a golden's budgets name
// their field instead: glint regress).
struct Budget {
  std::string text;  // one condition, as written
  MeasureRef measure;
  std::string op;
  double limit = 0;
};
std::vector<Budget> parse_budgets(std::string_view text, bool scene,
                                  const std::string& option = "--budget");
// Whether a row meets one condition (an absent value never does).
bool meets(const nlohmann::json& row, const Budget& b);

}  // namespace glint
