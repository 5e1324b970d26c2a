// Shared plumbing of the glint subcommands (each lives in its own cmd_*.cpp).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

namespace glint {
class OutputSet;
struct SweepOutputFiles;
}  // namespace glint

namespace glint::cli {

// Exit statuses: 0 success, 1 a check failed (e.g. regression), 2 bad input or usage.
inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 2;

// Runs `body` and turns glint's exceptions into a message on stderr and an exit status:
// InputError, OutputError and std::invalid_argument are bad input (2); anything else is an
// internal error (3).
int guarded(const std::function<int()>& body);

// Prints a JSON document on stdout (one document, newline-terminated).
void print_json(const nlohmann::json& j);

// --display-bits N: the display depth errors are counted in (LSBs of an N-bit output), 1..16.
void add_display_bits_option(CLI::App* sub, int& bits);

// --slots N: a chip of fixed capacity N (1..kMaxSlotCapacity); 0 (absent): sized to the stream.
void add_slots_option(CLI::App* sub, std::size_t& slots);
// make_slots' refusal of a stream that needs more slots than --slots N, rethrown naming the option.
[[noreturn]] void refuse_slots(std::size_t slots, const std::exception& e);

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

}  // namespace glint::cli
