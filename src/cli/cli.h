// Shared plumbing of the glint subcommands (each lives in its own cmd_*.cpp).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/html.h"
#include "reference/pixel_error.h"
#include "units/catalogue.h"
#include "units/chip.h"

namespace glint {
class OutputSet;
struct SweepOutputFiles;
}  // namespace glint

namespace glint::cli {

// Exit statuses: 0 success, 1 a check failed (e.g. regression), 2 bad input or usage.
inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 2;

// The whole command line: parses argv (argv[0] is the program) and runs the subcommand it names;
// returns the exit status. Messages go to stderr, results to stdout, which is flushed and checked
// at the end: a failed write there is reported and makes the status 2 (io/standard_output.h).
int run(int argc, char** argv);

// The run as a report page states it (--html): the command line run() was given, the working
// folder and glint's version.
HtmlRunInfo html_run_info();

// Options only (the options fuzzer, tests/fuzz/fuzz_options.cpp): every subcommand checks its
// option values as in a real run and stops before it reads an input file or writes anything;
// tau and fit, which read and write no file, run in full.
void set_options_only(bool on);
bool options_only();

// At most this many --unit options (lanes) in one run: each builds and simulates a unit.
inline constexpr std::size_t kMaxUnitOptions = 64;
// The unit specs of --unit (default: every unit), parsed; throws std::invalid_argument naming the
// spec, or the option when more than kMaxUnitOptions are given.
std::vector<UnitSpec> parse_unit_options(const std::vector<std::string>& units);

// Runs `body` and turns glint's exceptions into a message on stderr and an exit status:
// InputError, OutputError and std::invalid_argument are bad input (2); anything else is an
// internal error (3).
int guarded(const std::function<int()>& body);

// Prints a JSON document on stdout (one document, newline-terminated).
void print_json(const nlohmann::json& j);

// --display-bits N: the display depth errors are counted in (LSBs of an N-bit output), 1..16.
void add_display_bits_option(CLI::App* sub, int& bits);

// --threads N: 1..256 threads (0, absent: every core); results do not depend on it.
void add_threads_option(CLI::App* sub, int& threads);

// --seed S: the sink's backpressure pattern (0..2^64-1; default 1), `given` set when it is on the
// command line. require_backpressure_for_seed refuses a seed given while the sink is always ready
// (--sink-ready 1): the pattern would be ignored in silence.
void add_seed_option(CLI::App* sub, std::uint64_t& seed, bool& given);
void require_backpressure_for_seed(bool seed_given, double sink_ready);

// --chip CHIP (units/chip.h): rom (the default), ram, ram:materials=M,slots=S.
void add_chip_option(CLI::App* sub, Chip& chip);
// make_slots' refusal of a stream beyond the chip's capacity, or specs_on_chip's of a unit whose
// tables key contradicts the chip, rethrown naming the option.
[[noreturn]] void refuse_chip(const Chip& chip, const std::exception& e);
// specs_on_chip, its refusal named by refuse_chip: called before any output is made.
std::vector<UnitSpec> specs_for_chip(std::vector<UnitSpec> specs, const Chip& chip);
// --node NAME (cost/node.h): also state each lane's area in um2 and its critical path in ns and
// MHz at that node, from the proxy's constants calibrated against its library. Empty: not asked.
void add_node_option(CLI::App* sub, std::string& node);
// --eps-measure luminance|channel: what eps is a threshold of (reference/pixel_error.h).
void add_eps_measure_option(CLI::App* sub, EpsMeasure& measure);

// Throws std::invalid_argument naming the option unless v is finite and > 0 (NaN is refused).
void require_finite_positive(double v, const std::string& option);

// A stream or scene beyond a run's resource limits (eval/evaluate.h: slots, units x slots,
// contract work), rethrown as an InputError of `file` (field "slots").
[[noreturn]] void refuse_size(const std::string& file, const std::exception& e);

// Parses "r,g,b" into three doubles; throws std::invalid_argument naming the option.
std::array<double, 3> parse_rgb(const std::string& text, const std::string& option);

void add_tau_command(CLI::App& app, int& status);
void add_fit_command(CLI::App& app, int& status);
void add_eval_command(CLI::App& app, int& status);
void add_units_command(CLI::App& app, int& status);
void add_sim_command(CLI::App& app, int& status);
void add_regress_command(CLI::App& app, int& status);
void add_render_command(CLI::App& app, int& status);
void add_sweep_command(CLI::App& app, int& status);
// The end of a sweep or a merge: its files written and committed, then the report (--json) or the
// summary on stdout. Returns the exit status.
int emit_sweep_report(const nlohmann::json& report, const SweepOutputFiles& files, OutputSet& set,
                      bool json);
void add_size_command(CLI::App& app, int& status);
void add_merge_command(CLI::App& app, int& status);
void add_rtl_command(CLI::App& app, int& status);
void add_synth_command(CLI::App& app, int& status);
// glint help [COMMAND] [--markdown]: needs `app` whole, so it is added last.
void add_help_command(CLI::App& app, int& status);

}  // namespace glint::cli
