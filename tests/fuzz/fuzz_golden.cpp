// The goldens `glint regress` reads (eval/golden.h): parse_golden and its schema check, then what
// regress does with an accepted golden: check_report_shape and diff_sim_reports against a fresh
// report (a shipped golden's, standing for the child `glint sim`'s) and against itself.
// InputError is a refusal (exit 2); anything else thrown is a finding, and so is an accepted golden
// that differs from itself.
#include <stdexcept>
#include <string>

#include "eval/golden.h"
#include "eval/sim_report.h"
#include "fuzz.h"
#include "io/input_error.h"

namespace glint::fuzz {

namespace {

const nlohmann::json& fresh_report() {
  static const nlohmann::json report =
      read_golden(GLINT_SOURCE_DIR "/traces/golden/phong_basic.json").report;
  return report;
}

}  // namespace

int golden(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  (void)fresh_report();  // read before any input, so that its own errors are not blamed on one
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
    if (use == GoldenUse::kUpdate) continue;
    try {
      check_report_shape(g.report, g.report, "fuzz.json");
      if (!diff_sim_reports(g.report, g.report, 0.0).empty()) fail("a golden differs from itself");
      try {
        check_report_shape(g.report, fresh_report(), "fuzz.json");
      } catch (const InputError&) {
        continue;  // refused: not the schema of this build's report
      }
      (void)diff_sim_reports(g.report, fresh_report(), 1e-9);
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
