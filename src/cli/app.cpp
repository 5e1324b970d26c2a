// The glint command line as a function: every subcommand on one CLI11 app, the exit status
// returned. main.cpp calls it; tests/fuzz/fuzz_options.cpp feeds it argument vectors.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/cli.h"
#include "io/output_set.h"
#include "io/standard_output.h"

#ifndef GLINT_VERSION
#error "GLINT_VERSION must be defined by the build (CMakeLists.txt: the project version)"
#endif

namespace glint::cli {

namespace {

bool g_options_only = false;
std::vector<std::string> g_command_line;

// The first word after `glint` names a subcommand unless it is an option. CLI11 would report an
// unknown one as "The following argument was not expected: WORD" (or only "A subcommand is
// required"), which does not say that WORD was taken for a subcommand; name it and the valid ones.
bool check_subcommand(CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return true;
  const std::string word = argv[1];
  std::string known;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (sub->check_name(word)) return true;
    known += (known.empty() ? "" : ", ") + sub->get_name();
  }
  std::fprintf(stderr, "glint: unknown subcommand '%s' (expected one of: %s; see glint --help)\n",
               word.c_str(), known.c_str());
  return false;
}

}  // namespace

void set_options_only(bool on) {
  g_options_only = on;
}

bool options_only() {
  return g_options_only;
}

HtmlRunInfo html_run_info() {
  HtmlRunInfo info;
  info.argv = g_command_line;
  std::error_code ec;  // a folder removed under the run: the command alone
  info.cwd = std::filesystem::current_path(ec).string();
  info.version = GLINT_VERSION;
  return info;
}

namespace {

int run_command(int argc, char** argv) {
  CLI::App app{"glint: simulator of fixed-point specular shading units (max(0,t)^n)"};
  app.set_version_flag("--version", std::string("glint ") + GLINT_VERSION);
  app.require_subcommand(1);
  int status = kExitOk;
  add_tau_command(app, status);
  add_fit_command(app, status);
  add_eval_command(app, status);
  add_units_command(app, status);
  add_sim_command(app, status);
  add_regress_command(app, status);
  add_render_command(app, status);
  add_sweep_command(app, status);
  add_size_command(app, status);
  add_merge_command(app, status);
  add_rtl_command(app, status);
  add_synth_command(app, status);
  add_help_command(app, status);
  if (!check_subcommand(app, argc, argv)) return kExitBadInput;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version: printed, exit 0
    // One line in glint's own form, naming the subcommand, rather than CLI11's two ("MESSAGE",
    // then "Run with --help for more information.").
    std::string where = "glint";
    if (argc >= 2 && argv[1][0] != '-') where += std::string(" ") + argv[1];
    std::fprintf(stderr, "%s: %s (see %s --help)\n", where.c_str(), e.what(), where.c_str());
    return kExitBadInput;
  }
  return status;
}

}  // namespace

int run(int argc, char** argv) {
  g_command_line.assign(argv, argv + argc);
  const int status = run_command(argc, argv);
  // Every command's standard output (text, --json, help) is whole or the run fails: a write
  // error there is a failed output, as for a file (exit 2; an internal error keeps its 3).
  try {
    finish_standard_output();
  } catch (const OutputError& e) {
    std::fprintf(stderr, "glint: %s\n", e.what());
    return status > kExitBadInput ? status : kExitBadInput;
  }
  return status;
}

}  // namespace glint::cli
