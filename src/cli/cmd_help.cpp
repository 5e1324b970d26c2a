// glint help: the help of the whole program or of one command, and with --markdown the option
// reference of every command (src/cli/reference.md is this output; ctest docs.reference fails
// when the two differ). Written from CLI11's own description of each option, so the reference
// cannot drift from what the parser accepts.
#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli.h"

namespace glint::cli {
namespace {

struct HelpOptions {
  std::string command;
  bool markdown = false;
};

// A description goes into a table cell: a '|' would end the cell.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

std::vector<const CLI::App*> commands(const CLI::App& app) {
  return app.get_subcommands([](const CLI::App*) { return true; });
}

bool is_help_flag(const CLI::Option* opt) {
  return opt->check_lname("help");
}

bool is_positional(const CLI::Option* opt) {
  return opt->get_positional() && !opt->nonpositional();
}

// `glint sim [OPTIONS] VECTORS`: the positionals in order, optional ones in brackets.
std::string usage(const CLI::App& sub) {
  std::string line = "glint " + sub.get_name() + " [OPTIONS]";
  for (const CLI::Option* opt : sub.get_options(is_positional)) {
    std::string name = opt->get_name();
    if (opt->get_items_expected_max() > 1) name += "...";
    line += opt->get_required() ? " " + name : " [" + name + "]";
  }
  return line;
}

// The value an option takes, as CLI11's help writes it: its text, or its type (with the
// validator's range or choices); repeatable options end in "...".
std::string value_text(const CLI::Option* opt) {
  if (!opt->get_option_text().empty()) return opt->get_option_text();
  if (opt->get_type_size() == 0) return "";  // a flag
  std::string text = opt->get_type_name();
  if (opt->get_expected_max() == CLI::detail::expected_max_vector_size) text += " ...";
  return text;
}

// What else the option needs or excludes; names sorted, since CLI11 keeps them in a set of
// pointers whose order is the allocator's.
std::string relations(const CLI::Option* opt) {
  auto names = [](const std::set<CLI::Option*>& set) {
    std::vector<std::string> out;
    for (const CLI::Option* o : set) out.push_back(o->get_name());
    std::sort(out.begin(), out.end());
    std::string joined;
    for (const auto& n : out) joined += (joined.empty() ? "" : ", ") + ("`" + n + "`");
    return joined;
  };
  std::string out;
  if (!opt->get_needs().empty()) out += " (needs " + names(opt->get_needs()) + ")";
  if (!opt->get_excludes().empty()) out += " (excludes " + names(opt->get_excludes()) + ")";
  return out;
}

std::string option_row(const CLI::Option* opt) {
  const bool positional = is_positional(opt);
  std::string name = positional ? opt->get_name() : opt->get_name(false, true);
  std::string flags;
  if (opt->get_required()) flags += "required";
  if (positional) flags += flags.empty() ? "positional" : ", positional";
  const std::string value = value_text(opt);
  return fmt::format("| `{}` | {} | {} | {} | {}{} |\n", cell(name),
                     value.empty() ? "" : "`" + cell(value) + "`",
                     opt->get_default_str().empty() ? "" : "`" + cell(opt->get_default_str()) + "`",
                     flags, cell(opt->get_description()), cell(relations(opt)));
}

std::string markdown(const CLI::App& app) {
  std::ostringstream out;
  out << "# glint command reference\n\n"
      << "Generated from the program by `glint help --markdown > src/cli/reference.md`: do not\n"
      << "edit by hand (ctest `docs.reference` fails when this file and the program differ).\n"
      << "The user guide, with examples and how to read each output, is `src/cli/README.md`.\n\n"
      << "`glint [--help] [--version] COMMAND [OPTIONS]`. Every command also takes `-h,--help`.\n\n"
      << "| command | what it does |\n|---|---|\n";
  for (const CLI::App* sub : commands(app))
    out << fmt::format("| [`{}`](#glint-{}) | {} |\n", sub->get_name(), sub->get_name(),
                       cell(sub->get_description()));
  for (const CLI::App* sub : commands(app)) {
    out << fmt::format("\n## glint {}\n\n{}\n\n```\n{}\n```\n", sub->get_name(),
                       sub->get_description(), usage(*sub));
    const auto options = sub->get_options([](const CLI::Option* o) { return !is_help_flag(o); });
    if (options.empty()) continue;
    out << "\n| option | value | default | kind | meaning |\n|---|---|---|---|---|\n";
    // Positionals first, as the usage line has them.
    for (const CLI::Option* opt : options)
      if (is_positional(opt)) out << option_row(opt);
    for (const CLI::Option* opt : options)
      if (opt->nonpositional()) out << option_row(opt);
  }
  return out.str();
}

}  // namespace

void add_help_command(CLI::App& app, int& status) {
  auto o = std::make_shared<HelpOptions>();
  CLI::App* sub = app.add_subcommand(
      "help", "Help of glint or of one command; --markdown: the option reference of every command");
  sub->add_option("COMMAND", o->command, "The command to describe (default: glint itself)");
  sub->add_flag("--markdown", o->markdown,
                "Print the option reference of every command as Markdown (src/cli/reference.md)");
  sub->callback([o, &app, &status] {
    status = guarded([&] {
      if (o->markdown) {
        if (!o->command.empty())
          throw std::invalid_argument("help --markdown: describes every command; give no COMMAND");
        std::cout << markdown(app);
        return kExitOk;
      }
      if (o->command.empty()) {
        // Not app.help(): with a subcommand parsed (this one) it describes that subcommand.
        std::cout << app.get_formatter()->make_help(&app, app.get_name(),
                                                    CLI::AppFormatMode::Normal);
        return kExitOk;
      }
      for (const CLI::App* cmd : commands(app))
        if (cmd->get_name() == o->command) {
          std::cout << cmd->help();
          return kExitOk;
        }
      throw std::invalid_argument(
          fmt::format("help: unknown command '{}' (see glint help)", o->command));
    });
  });
}

}  // namespace glint::cli
