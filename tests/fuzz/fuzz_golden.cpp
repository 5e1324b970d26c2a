// The goldens `glint regress` reads (eval/golden.h): parse_golden and its schema check, then what
// regress does with an accepted golden: check_report_shape and the comparison (diff_sim_reports
// for a trace's, diff_render_reports for a scene's) and what a failure says first
// (hardware_changes, largest_changes: eval/golden_diff.h), against a fresh report (a shipped
// golden's, standing for the child's) and against itself. InputError is a refusal (exit 2);
// anything else thrown is a finding, and so is an accepted golden that differs from itself.
#include <stdexcept>
#include <string>

#include "eval/golden.h"
#include "eval/golden_diff.h"
#include "eval/sim_report.h"
#include "fuzz.h"
#include "io/input_error.h"

namespace glint::fuzz {

namespace {

const nlohmann::json& fresh_report(GoldenKind kind) {
  static const nlohmann::json sim =
      read_golden(GLINT_SOURCE_DIR "/traces/golden/phong_basic.json").report;
  static const nlohmann::json render =
      read_golden(GLINT_SOURCE_DIR "/traces/golden/scenes/small.json").report;
  return kind == GoldenKind::kTrace ? sim : render;
}

std::vector<std::string> differences(GoldenKind kind, const nlohmann::json& golden,
                                     const nlohmann::json& fresh, double tolerance) {
  return kind == GoldenKind::kTrace ? diff_sim_reports(golden, fresh, tolerance)
                                    : diff_render_reports(golden, fresh, tolerance);
}

}  // namespace

int golden(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  // Read before any input, so that their own errors are not blamed on one.
  (void)fresh_report(GoldenKind::kTrace);
  (void)fresh_report(GoldenKind::kScene);
  for (const GoldenUse use : {GoldenUse::kUpdate, GoldenUse::kCompare}) {
    Golden g;
    try {
      g = parse_golden(text, "fuzz.json", use);
    } catch (const InputError&) {
      continue;
    } catch (const std::exception& e) {
      fail(std::string("parse_golden threw something other than InputError: ") + e.what());
    }
    (void)g.to_json().dump();
    // A golden of budgets only has no report to compare (regress checks only its budgets).
    if (use == GoldenUse::kUpdate || g.budgets_only) continue;
    try {
      check_report_shape(g.report, g.report, "fuzz.json");
      if (!differences(g.kind, g.report, g.report, 0.0).empty())
        fail("a golden differs from itself");
      if (!hardware_changes(g.kind, g.report, g.report).empty() ||
          !largest_changes(g.kind, g.report, g.report, 0.0).empty())
        fail("a golden's hardware or figures changed against itself");
      const nlohmann::json& fresh = fresh_report(g.kind);
      try {
        check_report_shape(g.report, fresh, "fuzz.json");
      } catch (const InputError&) {
        continue;  // refused: not the schema of this build's report
      }
      (void)differences(g.kind, g.report, fresh, 1e-9);
      (void)hardware_changes(g.kind, g.report, fresh);
      (void)largest_changes(g.kind, g.report, fresh, 1e-9);
    } catch (const InputError& e) {
      fail(std::string("an accepted golden is refused against itself: ") + e.what());
    } catch (const std::exception& e) {
      fail(std::string("comparing an accepted golden threw: ") + e.what());
    }
  }
  return 0;
}

}  // namespace glint::fuzz

GLINT_FUZZ_TARGET(golden)
