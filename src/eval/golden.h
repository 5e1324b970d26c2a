// The goldens of `glint regress`: a trace's (traces/golden/NAME.json: the settings it was recorded
// with and the `glint sim` report it gave) and a scene's (traces/golden/scenes/NAME.json: the
// render settings and the `glint render` report). Either may hold budgets, conditions per lane in
// `glint size`'s grammar, besides or instead of the report (src/eval/golden.md).
//
// A golden is read defensively (size and nesting limits, duplicate keys refused: io/json_text.h)
// and checked against its schema before anything is compared, so that a stripped or edited golden
// cannot pass a tampered trace: regress used to compare only the fields a golden held. The
// envelope (trace or scene, units, sink settings, chip, budgets, report) and the report's fixed
// part (its top level and each unit's keys, with their types) are checked statically by
// parse_golden; the nested parts whose keys depend on the unit (config, elaboration, errors,
// operations, inventory) are checked against the report this build writes for the same input and
// settings (check_report_shape). Every violation is an InputError naming the golden file and the
// field ("report.units[2].digest"), exit 2 in the CLI. The budgets' grammar is the sweep layer's
// (sweep/golden_budgets.h), above this one; here only their shape and lanes are checked.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace glint {

// Goldens are ~0.1-0.6 MB and nest 8 levels deep; the limits keep a hostile file from exhausting
// memory or the stack (nlohmann's dump() and destructor recurse once per level).
inline constexpr std::size_t kGoldenMaxFileBytes = std::size_t{64} << 20;
inline constexpr int kGoldenMaxJsonDepth = 32;
// Lanes a golden may record (each one is a unit built and simulated by the child `glint sim`).
inline constexpr std::size_t kGoldenMaxUnits = 64;

// What a golden re-runs: a vector file through `glint sim`, or a scene through `glint render`.
enum class GoldenKind { kTrace, kScene };

struct Golden {
  GoldenKind kind = GoldenKind::kTrace;
  std::string trace;               // kTrace: the trace's file name, NAME.vec
  std::string scene;               // kScene: the scene's file name in the scenes folder, NAME.json
  std::vector<std::string> units;  // unit SPECs (each one parses), in lane order
  double sink_ready = 1.0;         // kTrace: in [kMinSinkReady, 1]
  std::uint64_t seed = 1;          // kTrace
  std::string chip;                // --chip (units/chip.h); empty: the default, rom
  // Conditions per lane: a spec of `units` (every lane with that spec) and the conditions it must
  // meet, as `glint size --budget` takes them ("image.max_lsb<=1,area_ge<=12000"), sorted by spec.
  std::vector<std::pair<std::string, std::string>> budgets;
  // The sim report (schema kSimReportVersion) or the render report; null for a golden of budgets
  // only ("report": null), and while --update makes it.
  nlohmann::json report;
  bool budgets_only = false;  // "report": null: --update leaves it so

  // The input's file name, trace or scene.
  const std::string& input() const { return kind == GoldenKind::kTrace ? trace : scene; }

  // The golden as written by `glint regress --update` (keys sorted by nlohmann).
  nlohmann::json to_json() const;
};

// What a golden is read for: comparing needs its report; --update replaces the report (which may
// be of an older schema, or missing) and needs only the settings.
enum class GoldenUse { kCompare, kUpdate };

// Parses and checks a golden; throws InputError(file, line, field, message).
Golden parse_golden(const std::string& text, const std::string& file,
                    GoldenUse use = GoldenUse::kCompare);
// The same from a file (at most kGoldenMaxFileBytes).
Golden read_golden(const std::string& path, GoldenUse use = GoldenUse::kCompare);

// Checks that a golden's report has exactly the shape of `fresh`, the report this build wrote for
// the golden's input and settings, and the same schema version: the same keys in every object, and
// values of the same JSON type (number, string, boolean, array, object) wherever both have them.
// Arrays are walked up to the shorter one's length (a different length is a difference in value,
// diff_sim_reports's to report). Throws InputError naming `file` and the first offending field,
// with the count of the others.
void check_report_shape(const nlohmann::json& golden_report, const nlohmann::json& fresh,
                        const std::string& file);

}  // namespace glint
