// glint units: every unit with each key, its meaning and its default.
#include <fmt/format.h>

#include <iostream>

#include "cli/cli.h"
#include "units/catalogue.h"

namespace glint::cli {

void add_units_command(CLI::App& app, int& status) {
  auto json = std::make_shared<bool>(false);
  CLI::App* sub = app.add_subcommand("units", "List the units and the keys of a unit SPEC");
  sub->add_flag("--json", *json, "Print one JSON document on stdout");
  sub->callback([json, &status] {
    status = guarded([&] {
      if (*json) {
        nlohmann::json j = nlohmann::json::array();
        for (const auto& u : unit_catalog()) {
          nlohmann::json keys = nlohmann::json::array();
          for (const auto& k : u.keys)
            keys.push_back({{"key", k.key}, {"meaning", k.meaning}, {"default", k.default_value}});
          j.push_back({{"name", u.name},
                       {"summary", u.summary},
                       {"default_set", u.default_set},
                       {"keys", keys}});
        }
        print_json({{"units", j}, {"spec_syntax", "NAME[:key=value,...]"}});
        return kExitOk;
      }
      std::cout << "A unit SPEC is NAME[:key=value,...], e.g. horner:degree=5,method=ls\n";
      for (const auto& u : unit_catalog()) {
        std::cout << fmt::format("\n{}  {}\n", u.name, u.summary);
        if (!u.default_set)
          std::cout << fmt::format("  (not in the default set: only with --unit {})\n", u.name);
        for (const auto& k : u.keys)
          std::cout << fmt::format("  {:<11} {:<10} {}\n", k.key, k.default_value, k.meaning);
      }
      return kExitOk;
    });
  });
}

}  // namespace glint::cli
