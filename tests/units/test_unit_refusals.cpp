// Every refusal of a unit spec names the unit, the key(s) and the value(s) that cause it, the
// derived-width ones included (a register too wide for a combination of keys names all of them).
//
// Each throw site under src/units/ carries a tag on the line above it: `// refusal: ID` when a
// spec can reach it, and then kRefusals below holds a spec that does and what its message must
// name; or `// not from a spec: WHY` when the key reader or the build already excludes it.
// Refusals.EveryThrowSiteIsTagged reads the sources, so a new refusal cannot be added without a
// case here naming its key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <regex>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "reference/reference.h"
#include "units/catalogue.h"

namespace glint {
namespace {

std::vector<MaterialParams> phong_materials() {
  const TauResult t = tau_power(50, 1e-3, 1.0);
  MaterialParams m{50, t.tau, false};
  m.name = "white";
  return {m};
}

// More distinct materials than lut:bits=16 may keep tables for (256 KiB each, 256 MiB a unit).
std::vector<MaterialParams> many_materials() {
  std::vector<MaterialParams> out;
  for (int i = 0; i < 1030; ++i) out.emplace_back(2.0 + i, 0.0, false);
  return out;
}

// n = 1.5 at eps 1e-6: tau 1e-4, next to t^n's branch point at 0.
std::vector<MaterialParams> low_shininess() {
  const TauResult t = tau_power(1.5, 1e-6, 1.0);
  MaterialParams m{1.5, t.tau, false};
  m.name = "dull";
  return {m};
}

std::vector<MaterialParams> zero_shininess() {
  return {MaterialParams{0.0, 0.0, false}};
}

struct Refusal {
  const char* id;    // the tag at the throw site
  const char* spec;  // a spec the site refuses
  std::vector<MaterialParams> (*materials)();
  std::vector<std::string> names;  // what the message must hold: unit, keys, values
};

const std::vector<Refusal> kRefusals = {
    {"spec.empty", "", phong_materials, {"empty unit spec"}},
    {"spec.no_keys", "pow:", phong_materials, {"unit spec 'pow:'", "no keys"}},
    {"spec.not_key_value", "pow:bits", phong_materials, {"unit spec 'pow:bits'", "'bits'"}},
    {"spec.twice", "lut:bits=4,bits=5", phong_materials, {"unit spec", "key 'bits'"}},
    {"spec.trailing_comma", "lut:bits=4,", phong_materials, {"unit spec 'lut:bits=4,'"}},
    {"spec.unknown_unit", "phong", phong_materials, {"unknown unit 'phong'"}},
    {"keys.unknown", "lut:bitz=3", phong_materials, {"unit 'lut'", "key 'bitz' = '3'"}},
    {"keys.format", "pow:n=uq14.x", phong_materials, {"unit 'pow'", "key 'n' = 'uq14.x'"}},
    {"keys.integer", "lut:bits=40", phong_materials, {"unit 'lut'", "key 'bits' = '40'"}},
    {"keys.real", "hast:root=1.5", phong_materials, {"unit 'hast'", "key 'root' = '1.5'"}},
    {"keys.flag",
     "horner:constrain=maybe",
     phong_materials,
     {"unit 'horner'", "key 'constrain' = 'maybe'"}},
    {"keys.choice",
     "horner:method=spline",
     phong_materials,
     {"unit 'horner'", "key 'method' = 'spline'"}},
    {"keys.fraction_bit", "pow:out=uq1.0", phong_materials, {"unit 'pow'", "key 'out' = 'uq1.0'"}},
    {"hast.match_shininess",
     "hast:match=minimax",
     zero_shininess,
     {"unit 'hast'", "key 'match' = 'minimax'"}},
    {"hast.root_match",
     "hast:root=0.5,match=width",
     phong_materials,
     {"unit 'hast'", "key 'root' = '0.5'", "match=width"}},
    {"hast.d_auto", "hast:d=auto", phong_materials, {"unit 'hast'", "key 'd' = 'auto'"}},
    {"hast.chain",
     "hast:out=uq1.40",
     phong_materials,
     {"unit 'hast'", "'out' = 'uq1.40'", "'guard' = 'auto' (4)", "45 bits"}},
    {"u_scaler.width",
     "hast:in=uq1.60",
     phong_materials,
     {"unit 'hast'", "u scaler", "'in' = 'uq1.60'", "'out' = 'uq1.15'", "'guard' = 'auto' (4)"}},
    {"u_scaler.k",
     "hast:in=uq1.30,root=0.999999999",
     phong_materials,
     {"unit 'hast'", "u scaler", "'in' = 'uq1.30'", "'out' = 'uq1.15'", "'root' = '0.999999999'"}},
    {"horner.accumulator",
     "horner:in=uq1.8,out=uq1.30,guard=20,degree=10,domain=full,method=ls,constrain=off",
     phong_materials,
     {"unit 'horner'", "'out' = 'uq1.30'", "'guard' = '20'", "'degree' = '10'"}},
    {"horner.monotone",
     "horner:guard=0,degree=10,in=uq1.20",
     phong_materials,
     {"unit 'horner'", "'guard' = '0'", "'in' = 'uq1.20'", "'degree' = '10'"}},
    {"horner.fit_sollya_spec",
     "horner:fit=sollya,domain=full,method=ls",
     phong_materials,
     {"unit 'horner'", "key 'fit' = 'sollya'", "domain=full", "method=ls"}},
    {"horner.fit_sollya",
     "horner:fit=sollya,degree=5",
     phong_materials,
     {"unit 'horner'", "key 'fit' = 'sollya'", "white", "not proven monotone"}},
    {"horner.fit_sollya_branch",
     "horner:fit=sollya",
     low_shininess,
     {"unit 'horner'", "key 'fit' = 'sollya'", "t^1.5", "branch point"}},
    {"lut.table_frac",
     "lut:out=uq1.39",
     phong_materials,
     {"unit 'lut'", "'table_frac' = 'auto' (41)", "'out' = 'uq1.39'"}},
    {"lut.interpolation",
     "lut:bits=16,table_frac=40",
     phong_materials,
     {"unit 'lut'", "'table_frac' = '40'", "'bits' = '16'", "'in' = 'uq1.15'"}},
    {"unit_set.tables",
     "lut:bits=16,in=uq1.16",
     many_materials,
     {"lut", "key 'bits' = '16'", "MiB"}},
    {"schlick.n", "schlick:n=uq4.2", phong_materials, {"unit 'schlick'", "key 'n' = 'uq4.2'"}},
    {"schlick.n_prime",
     "schlick:match=minimax,n=uq6.4",
     phong_materials,
     {"unit 'schlick'", "'match' = 'minimax'", "'n' = 'uq6.4'"}},
    {"schlick.divider",
     "schlick:in=uq1.40",
     phong_materials,
     {"unit 'schlick'", "'in' = 'uq1.40'", "'out' = 'uq1.15'", "'n' = 'uq14.4'"}},
    {"pow.exp_frac",
     "pow:exp_frac=4",
     phong_materials,
     {"unit 'pow'", "'exp_frac' = '4'", "'out' = 'uq1.15'"}},
    {"pow.n", "pow:n=uq2.4", phong_materials, {"unit 'pow'", "key 'n' = 'uq2.4'"}},
    {"sfu.in", "sfu:in=uq1.24", phong_materials, {"unit 'sfu'", "key 'in' = 'uq1.24'"}},
    {"pwp.in", "pwp:in=uq1.21", phong_materials, {"unit 'pwp'", "key 'in' = 'uq1.21'"}},
    {"pwp.coef_frac",
     "pwp:out=uq1.50",
     phong_materials,
     {"unit 'pwp'", "'coef_frac' = 'auto' (52)", "'out' = 'uq1.50'"}},
    {"pwp.guard",
     "pwp:guard=0",
     phong_materials,
     {"unit 'pwp'", "'guard' = '0'", "'coef_frac' = 'auto' (17)", "'out' = 'uq1.15'"}},
    {"pwp.width",
     "pwp:out=uq1.30,guard=24,skip=off",
     phong_materials,
     {"unit 'pwp'", "'out' = 'uq1.30'", "'guard' = '24'", "'in' = 'uq1.15'", "'segments' = '4'"}},
    {"pwp.monotone",
     "pwp:guard=0,coef_frac=15,degree=3,segments=1",
     phong_materials,
     {"unit 'pwp'", "white: pwp", "'guard' = '0'", "'degree' = '3'"}},
    {"pwp.n_domain", "pwp:n=uq12.4", phong_materials, {"unit 'pwp'", "key 'n' = 'uq12.4'"}},
    {"pwp.log_widths",
     "pwp:domain=log,guard=3",
     phong_materials,
     {"unit 'pwp'", "key 'guard' = '3'", "domain=log"}},
    {"pwp.log_in",
     "pwp:domain=log,in=uq1.30",
     phong_materials,
     {"pwp: keys 'domain' = 'log'", "'in' = 'uq1.30'"}},
    {"pwp.log_out",
     "pwp:domain=log,out=uq1.22",
     phong_materials,
     {"pwp: keys 'domain' = 'log'", "'out' = 'uq1.22'"}},
    {"pwp.log_width",
     "pwp:domain=log,in=uq1.20,out=uq1.21,n=uq24.8",
     phong_materials,
     {"pwp: keys 'domain' = 'log'", "'in' = 'uq1.20'", "'out' = 'uq1.21'", "'n' = 'uq24.8'",
      "'segments' = '4'"}},
    {"pwp.log_n",
     "pwp:domain=log,n=uq4.4",
     phong_materials,
     {"unit 'pwp'", "white: pwp", "'domain' = 'log'", "'n' = 'uq4.4'"}},
    {"pwp.fit_sollya_degree",
     "pwp:fit=sollya,degree=1",
     phong_materials,
     {"unit 'pwp'", "key 'fit' = 'sollya'", "degree 1"}},
    {"pwp.log_fit",
     "pwp:domain=log,fit=sollya",
     phong_materials,
     {"unit 'pwp'", "key 'fit' = 'sollya'", "domain=log"}},
    {"sfu.n_width", "sfu:n=uq20.5", phong_materials, {"unit 'sfu'", "key 'n' = 'uq20.5'"}},
    {"sfu.n", "sfu:n=uq2.4", phong_materials, {"unit 'sfu'", "key 'n' = 'uq2.4'"}},
    {"pow.y_frac",
     "pow:y_frac=30,log_frac=4",
     phong_materials,
     {"unit 'pow'", "'y_frac' = '30'", "'n' = 'uq14.4'", "'log_frac' = '4'"}},
    {"pow.log_interpolation",
     "pow:in=uq1.57",
     phong_materials,
     {"unit 'pow'", "'in' = 'uq1.57'", "'log_bits' = '8'", "'log_frac' = '24'"}},
    {"pow.n_log",
     "pow:n=uq30.28,log_frac=30",
     phong_materials,
     {"unit 'pow'", "'n' = 'uq30.28'", "'log_frac' = '30'"}},
};

// gtest prints a case by its id and spec, not its bytes.
void PrintTo(const Refusal& r, std::ostream* os) {
  *os << r.id << " '" << r.spec << "'";
}

class Refusals : public testing::TestWithParam<Refusal> {};

TEST_P(Refusals, NameTheUnitKeyAndValue) {
  const Refusal& r = GetParam();
  try {
    make_unit(parse_unit_spec(r.spec), r.materials());
    FAIL() << r.id << ": '" << r.spec << "' was built";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    for (const std::string& name : r.names)
      EXPECT_NE(what.find(name), std::string::npos) << r.id << ": " << name << " in: " << what;
  }
}

INSTANTIATE_TEST_SUITE_P(Units, Refusals, testing::ValuesIn(kRefusals),
                         [](const testing::TestParamInfo<Refusal>& info) {
                           std::string id = info.param.id;
                           for (char& c : id)
                             if (c == '.') c = '_';
                           return id;
                         });

// Every throw (and KeyReader::fail call) under src/units/ is tagged on the line above it, every
// `refusal:` tag is a case of kRefusals and every case is a tag.
TEST(RefusalSites, EveryThrowSiteIsTagged) {
  const std::regex site(R"(\bthrow\b(?!\s*;)|(^|[^\w:])fail\()");
  const std::regex definition(R"(void\s+(KeyReader::)?fail\()");
  const std::regex refusal(R"(^\s*// refusal: ([\w.]+)\s*$)");
  const std::regex excluded(R"(^\s*// not from a spec: \S)");
  std::map<std::string, int> tagged;
  int sites = 0;
  for (const auto& entry :
       std::filesystem::recursive_directory_iterator(GLINT_SOURCE_DIR "/src/units")) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".cpp" && ext != ".h") continue;
    std::ifstream in(entry.path());
    std::string previous, line;
    for (int number = 1; std::getline(in, line); ++number, previous = line) {
      const std::string code = line.substr(0, line.find("//"));
      if (!std::regex_search(code, site) || std::regex_search(code, definition)) continue;
      ++sites;
      std::smatch m;
      if (std::regex_match(previous, m, refusal))
        ++tagged[m[1]];
      else
        EXPECT_TRUE(std::regex_search(previous, excluded))
            << entry.path().string() << ":" << number << ": untagged refusal: " << line;
    }
  }
  EXPECT_GT(sites, static_cast<int>(kRefusals.size()));  // the scan found the sites
  std::set<std::string> cases;
  for (const Refusal& r : kRefusals) {
    EXPECT_TRUE(cases.insert(r.id).second) << r.id << " twice in kRefusals";
    EXPECT_EQ(tagged.count(r.id), 1u) << r.id << ": no throw site has this tag";
  }
  for (const auto& [id, count] : tagged) {
    EXPECT_EQ(count, 1) << id << " tags " << count << " sites";
    EXPECT_EQ(cases.count(id), 1u) << id << ": tagged in the sources but not in kRefusals";
  }
}

}  // namespace
}  // namespace glint
