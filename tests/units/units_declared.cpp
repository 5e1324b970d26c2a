// units_declared: what the unit kinds declare, printed for the build's checks.
//   --keys-markdown  the keys reference, src/units/keys.md (ctest docs.unit_keys compares them)
//   --cosim-cases    the co-simulation cases, one UNIT.CASE|SPEC|INPUT a line, which
//                    tests/rtl/discover.cmake turns into the ctest entries rtl.UNIT.CASE
#include <cstring>
#include <iostream>
#include <regex>
#include <string>

#include "units/catalogue.h"
#include "units/keys.h"

namespace {

// A table cell: a '|' in a meaning or a list of values would end it.
std::string cell(const std::string& text) {
  return std::regex_replace(text, std::regex(R"(\|)"), R"(\|)");
}

void key_table(const std::vector<glint::UnitKey>& keys, std::size_t first) {
  std::cout << "| key | default | values | meaning |\n|---|---|---|---|\n";
  for (std::size_t i = first; i < keys.size(); ++i) {
    const glint::UnitKey& k = keys[i];
    std::cout << "| `" << k.key << "` | `" << k.default_value << "` | " << cell(k.values) << " | "
              << cell(k.meaning) << " |\n";
  }
}

void keys_markdown() {
  std::cout
      << "# Unit keys\n\n"
      << "Generated from the key tables (`src/units/key_table.h`, `src/units/<unit>/keys.h`) by\n"
      << "`build/tests/units_declared --keys-markdown > src/units/keys.md`: do not edit by hand\n"
      << "(ctest `docs.unit_keys` fails when this file and the tables differ). A unit SPEC is\n"
      << "`NAME[:key=value,...]` ([glint units](../cli/guide/units.md)); a key left out takes its\n"
      << "default.\n\n## Keys every unit takes\n\n";
  const std::size_t common = glint::common_keys().size();
  key_table(glint::common_keys(), 0);
  for (const glint::UnitInfo& u : glint::unit_catalog()) {
    std::cout << "\n## " << u.name << "\n\n" << u.summary << ".\n\n";
    key_table(u.keys, common);
  }
}

void cosim_cases() {
  for (const glint::UnitInfo& u : glint::unit_catalog())
    for (const glint::CosimCase& c : u.cosim_cases)
      std::cout << glint::cosim_name(u, c) << '|' << glint::cosim_spec(u, c) << '|' << c.input
                << '\n';
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && std::strcmp(argv[1], "--keys-markdown") == 0) {
    keys_markdown();
  } else if (argc == 2 && std::strcmp(argv[1], "--cosim-cases") == 0) {
    cosim_cases();
  } else {
    std::cerr << "usage: units_declared --keys-markdown | --cosim-cases\n";
    return 2;
  }
  return std::cout.flush() ? 0 : 1;
}
