// The glint command line as a function: every subcommand on one CLI11 app, the exit status
// returned. main.cpp calls it; tests/fuzz/fuzz_options.cpp feeds it argument vectors.
#include <cctype>
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

// The subcommand the command line names (its first word that is one), or null.
CLI::App* named_subcommand(CLI::App& app, int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--") break;
    if (argv[i][0] == '-') continue;
    for (CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
      if (sub->check_name(argv[i])) return sub;
    return nullptr;
  }
  return nullptr;
}

// CLI11 checks required arguments before it reports arguments it does not know: `glint render
// --frob` would say "SCENE is required" and hide the typo. The first word that looks like an
// option (not a negative number) and that neither glint nor the subcommand takes, or "".
std::string unknown_option(CLI::App& app, CLI::App* sub, int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word == "--") break;
    if (word.size() < 2 || word[0] != '-') continue;
    if (std::isdigit(static_cast<unsigned char>(word[1])) || word[1] == '.') continue;
    const std::string name = word[1] == '-' ? word.substr(0, word.find('=')) : word.substr(0, 2);
    if (app.get_option_no_throw(name) != nullptr) continue;
    if (sub != nullptr && sub->get_option_no_throw(name) != nullptr) continue;
    return word;
  }
  return "";
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
    CLI::App* sub = named_subcommand(app, argc, argv);
    const std::string where = sub != nullptr ? "glint " + sub->get_name() : "glint";
    std::string message = e.what();
    if (dynamic_cast<const CLI::RequiredError*>(&e) != nullptr) {
      const std::string unknown = unknown_option(app, sub, argc, argv);
      if (!unknown.empty()) message = "The following argument was not expected: " + unknown;
    }
    std::fprintf(stderr, "%s: %s (see %s --help)\n", where.c_str(), message.c_str(), where.c_str());
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
