// glint regress's inputs (cmd_regress.cpp): the goldens to check, each read and checked against
// its schema and its budgets' grammar before any child runs, and the child `glint sim` (a trace)
// or `glint render` (a scene) that re-runs one with the golden's settings.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eval/golden.h"
#include "sweep/golden_budgets.h"

namespace glint::cli {

struct RegressOptions {
  std::string traces = "traces";
  std::vector<std::string> units;  // with --update: the specs every updated golden records
  bool update = false;
  double tolerance = 1e-9;
  bool json = false;
};

// One golden to check: where its input and it are, and how the output names it.
struct RegressCheck {
  std::filesystem::path input;
  std::filesystem::path golden_path;
  std::string name;  // "phong_basic.vec", "scenes/small.json"
  Golden golden;
  std::vector<LaneBudget> budgets;
  bool make = false;  // --update: a trace without a golden, whose golden is made
};

// --update --unit replaces the lanes; the budgets must still name lanes that exist (else an
// InputError naming the golden and the budget).
void check_budget_lanes(const RegressCheck& c);

// Every DIR/*.vec and its golden DIR/golden/NAME.json (make: none yet). A golden whose trace is
// gone, or that is a scene's, is an InputError.
std::vector<RegressCheck> trace_checks(const RegressOptions& o, const std::filesystem::path& dir,
                                       const std::filesystem::path& golden_dir);
// Every DIR/golden/scenes/*.json and the scene it names in DIR/scenes/.
std::vector<RegressCheck> scene_checks(const RegressOptions& o, const std::filesystem::path& dir,
                                       const std::filesystem::path& golden_dir);

// The fresh report of a trace (`glint sim --json`) or of a scene (`glint render --json`, its
// images in a temporary folder removed again) with the golden's settings.
nlohmann::json run_sim(const std::string& trace, const Golden& setup);
nlohmann::json run_render(const std::string& scene, const Golden& setup);

}  // namespace glint::cli
