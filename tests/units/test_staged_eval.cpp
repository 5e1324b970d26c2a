// The staged evaluation is the datapath itself, not a second model: for every unit, at its
// default spec and at non-default specs, on every input code of its input format and for several
// materials, the result register of the staged evaluation equals eval(), and every register value
// fits the width and signedness its stage layout declares (what the VCD traces it as).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "reference/reference.h"
#include "units/catalogue.h"

namespace glint {
namespace {

MaterialParams material(double n, double eps = 1e-3) {
  const TauResult t = tau_power(n, eps, 1.0);
  return MaterialParams{n, t.never_skip ? -1.0 : t.tau, t.always_skip};
}

std::vector<MaterialParams> materials() {
  // A sharp and a broad highlight, the default one, a lobe visible at every angle (Gaussian-like,
  // tau < 0) and one that is always skipped (c_y <= eps).
  return {material(50), material(5), material(300), MaterialParams{8, -1.0, false},
          MaterialParams{20, 1.0, true}};
}

void check_spec(const std::string& spec) {
  SCOPED_TRACE(spec);
  const auto unit = make_unit(parse_unit_spec(spec), materials());
  const StageLayout& layout = unit->stages();
  ASSERT_EQ(layout.latency(), unit->timing().latency);
  // The format of every flat value: position p's registers are its stage's.
  std::vector<const StageRegister*> reg;
  for (int p = 1; p <= layout.latency(); ++p)
    for (const StageRegister& r : layout.stage_at(p).registers) reg.push_back(&r);
  ASSERT_EQ(reg.size(), layout.size());
  std::vector<std::int64_t> values(layout.size());
  const QFormat in = unit->in_format();
  for (std::size_t slot = 0; slot < unit->slots(); ++slot) {
    std::uint64_t mismatches = 0, out_of_format = 0;
    for (std::int64_t t = 0; t <= in.raw_max(); ++t) {
      unit->eval_staged(slot, t, values.data());
      mismatches += values[layout.result_index()] != unit->eval(slot, t);
      for (std::size_t k = 0; k < values.size(); ++k) {
        const QFormat& f = reg[k]->format;
        if (values[k] < f.raw_min() || values[k] > f.raw_max()) {
          if (out_of_format++ == 0)
            ADD_FAILURE() << "slot " << slot << " t_raw " << t << ": " << reg[k]->name << " = "
                          << values[k] << " outside " << f.name();
        }
      }
    }
    EXPECT_EQ(mismatches, 0u) << "slot " << slot;
    EXPECT_EQ(out_of_format, 0u) << "slot " << slot;
  }
}

TEST(StagedEval, Pow) {
  for (const char* spec : {"pow", "pow:log_bits=6,exp_bits=5,y_frac=16",
                           "pow:in=uq1.12,out=uq1.10,n=uq12.6,log_frac=20,exp_frac=18"})
    check_spec(spec);
}

TEST(StagedEval, Schlick) {
  for (const char* spec :
       {"schlick", "schlick:divider=iterative,out=uq1.11", "schlick:in=uq1.12,n=uq10.6,out=uq1.13"})
    check_spec(spec);
}

TEST(StagedEval, Hast) {
  for (const char* spec : {"hast", "hast:d=2", "hast:d=7,guard=6,out=uq1.12", "hast:d=1"})
    check_spec(spec);
}

TEST(StagedEval, Horner) {
  for (const char* spec : {"horner", "horner:degree=2,method=ls",
                           "horner:degree=6,domain=full,constrain=off,in=uq1.13"})
    check_spec(spec);
}

TEST(StagedEval, Lut) {
  for (const char* spec : {"lut", "lut:bits=4", "lut:bits=9,table_frac=20,in=uq1.13"})
    check_spec(spec);
}

TEST(StagedEval, Pwp) {
  for (const char* spec : {"pwp", "pwp:degree=1", "pwp:degree=3,segments=6,in=uq1.13",
                           "pwp:segments=0,degree=3,skip=off,out=uq1.12"})
    check_spec(spec);
}

// The specs each unit declares it is co-simulated with (kCosimCases): a new unit is covered here
// by declaring them.
TEST(StagedEval, EveryDeclaredCase) {
  for (const UnitInfo& u : unit_catalog())
    for (const CosimCase& c : u.cosim_cases) check_spec(cosim_spec(u, c));
}

// The layout names what the hardware holds, in pipeline order.
TEST(StagedEval, LayoutsNameTheRegisters) {
  const auto hast = make_unit(parse_unit_spec("hast:d=3"), materials());
  const auto& s = hast->stages().stages();
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s[1].registers[0].name, "u");
  EXPECT_EQ(s[2].registers[1].name, "power");
  EXPECT_EQ(s[3].registers.back().name, "result");
  const auto schlick = make_unit(parse_unit_spec("schlick:divider=iterative"), materials());
  const Stage& div = schlick->stages().stage_at(2);
  EXPECT_EQ(div.name, "div");
  EXPECT_EQ(div.last - div.first + 1, schlick->timing().ii);
  // The divider converges: after the last quotient bit the quotient is the unrounded result.
  std::vector<std::int64_t> v(schlick->stages().size());
  schlick->eval_staged(0, 30000, v.data());
  const int q = schlick->timing().ii;
  const std::int64_t quotient = v[schlick->stages().offset(q + 1) + 1];
  EXPECT_EQ((quotient + 1) >> 1, schlick->eval(0, 30000));
}

}  // namespace
}  // namespace glint
