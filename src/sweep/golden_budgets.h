// A golden's budgets (`glint regress`, src/eval/golden.md): per lane, conditions in the grammar and
// with the measure names of `glint size --budget` (measures.h, parse_budgets: one parser), held
// against a lane of a sim or render report. The reports' lanes are mapped onto a sweep's row
// (report.h) so that a measure means the same figure here as in sweep and size.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eval/golden.h"
#include "sweep/measures.h"

namespace glint {

struct LaneBudget {
  std::string spec;  // the key in the golden's budgets: every lane with this spec
  std::string text;  // as written
  std::vector<Budget> conditions;
};

// Parses every lane's conditions of golden `g` read from `file`: an unknown measure, a bad operator
// or number, an image-level measure in a trace's golden, or a measure the golden's report has no
// figure for (a render has no cycles) is an InputError naming `file` and the field
// ("budgets.lut:bits=6").
std::vector<LaneBudget> parse_golden_budgets(const Golden& g, const std::string& file);

// A lane of a report as a sweep row holds it ("area_ge", "errors", "image", ...).
nlohmann::json budget_row(GoldenKind kind, const nlohmann::json& lane);

// One line per condition a lane of `report` breaks, in lane order: "lut: image.max_lsb<=1 does not
// hold: 3". Lanes are matched to specs through the golden's `units`, in order.
std::vector<std::string> broken_budgets(const Golden& g, const std::vector<LaneBudget>& budgets,
                                        const nlohmann::json& report);

}  // namespace glint
