// Property-based tests of the accuracy contract (issue 7 item 6), in the manner of FloPoCo's and
// ac_math's random testing: RapidCheck generates materials, light sets and thresholds the way a
// vector file states them (the slots come from make_slots(), exactly as the CLI builds them),
// random accepted specs of every unit drawn from the ranges the catalogue advertises, and random
// real t. For every generated case, on every code of the unit's input grid (all 2^16 of uq1.15,
// all 2^(F+1) of uq1.F):
//  - the output (comparator then datapath) is monotone non-decreasing in t;
//  - f(1) = 1 exactly where promised (every unit except horner with constrain=off), and 0 for a
//    slot that is always skipped;
//  - every skipped code is imperceptible: the datapath's output there is <= eps_K / c_y;
//  - the skip set lies inside Källberg's float test on real t: (code + 1/2) 2^-F <= tau;
//  - |eval - model| <= datapath_bound_ulps on every 4th computed code (random phase; see below);
//  - eval == the staged evaluation's result register == eval_batch (the simulator's paths);
//  - |y(quantize(t)) - r(t)| <= slot_contract().bound.total() at every code, at both sides of
//    every rounding boundary between codes, and at random real t in [-1, 1 + 1e-3];
// and a refused spec throws std::invalid_argument naming the unit and the key or the material.
//
// Cases: GLINT_PROPERTY_CASES accepted cases per unit (default 1000: 11-22 s of CPU a unit in
// Release; each run draws new ones); ctest's `properties_long.*` (label long, only with
// `ctest -C long`) runs 100 000. RC_PARAMS="seed=..." replays a seed.
// Shrunk failures are kept below as named regression tests (RegressionCases.*).
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <initializer_list>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "eval/contract.h"
#include "eval/evaluate.h"
#include "io/vectors.h"
#include "units/catalogue.h"

namespace glint {
namespace {

// ---------------------------------------------------------------------------------------------
// Running a property with this suite's case count.

int property_cases() {
  const char* env = std::getenv("GLINT_PROPERTY_CASES");
  return env ? std::max(1, std::atoi(env)) : 1000;
}

// RC_GTEST_PROP with the case count above instead of RapidCheck's default 100 (max_success in
// RC_PARAMS is replaced; its seed and the other parameters are kept), divided by `divisor` for a
// unit with few keys to draw whose cases cost more.
template <class Testable>
void check_property(Testable&& testable, int divisor = 1) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  rc::detail::TestMetadata metadata;
  metadata.id = std::string(info->test_suite_name()) + "/" + info->name();
  metadata.description = info->name();
  rc::detail::TestParams params = rc::detail::configuration().testParams;
  params.maxSuccess = std::max(1, property_cases() / divisor);
  const auto result = rc::detail::checkTestable(std::forward<Testable>(testable), metadata, params);
  std::ostringstream ss;
  rc::detail::printResultMessage(result, ss);
  if (result.template is<rc::detail::SuccessResult>()) {
    std::cout << ss.str() << std::endl;
  } else {
    FAIL() << ss.str();
  }
}

// ---------------------------------------------------------------------------------------------
// Generators.

// An integer in [lo, hi), uniform whatever RapidCheck's current size (gen::inRange scales its
// range by the size, which starts at 0: every early case would sit at lo); shrinks towards lo.
int pick(int lo, int hi) {
  return *rc::gen::resize(100, rc::gen::inRange(lo, hi));
}
template <class T>
T element(std::initializer_list<T> items) {
  return *(items.begin() + pick(0, static_cast<int>(items.size())));
}

// Log-uniform in [lo, hi] on a grid of 2^24 steps (an integer generator underneath, so a failure
// shrinks towards lo).
double log_uniform(double lo, double hi) {
  constexpr int kSteps = 1 << 24;
  const int k = pick(0, kSteps + 1);
  return lo * std::pow(hi / lo, static_cast<double>(k) / kSteps);
}
double uniform(double lo, double hi) {
  constexpr int kSteps = 1 << 24;
  const int k = pick(0, kSteps + 1);
  return lo + (hi - lo) * static_cast<double>(k) / kSteps;
}
bool one_in(int n) {
  return pick(0, n) == 0;
}

// A vector file's header: eps in [1e-6, 1e-1], 1..1024 lights (white, or coloured: then the
// slots are light x material), 1..3 materials of n in [0.3, 1e4] or Gaussian roughness in [1e-3,
// 1] (narrower than one input step of uq1.20: acos(1 - 2^-20) = 1.4e-3), and specular colours
// whose luminance ranges from a quarter of eps/K (always skipped) across eps/K up to 1.
VectorHeader gen_header() {
  VectorHeader h;
  h.eps = log_uniform(1e-6, 1e-1);
  h.lights = static_cast<int>(std::lround(log_uniform(1, 1024)));
  if (one_in(4)) {
    for (int l = 0; l < h.lights; ++l)
      h.light_intensity.push_back({uniform(0, 1), uniform(0, 1), uniform(0, 1)});
  } else {
    h.light_intensity.assign(static_cast<std::size_t>(h.lights), {1.0, 1.0, 1.0});
  }
  const double eps_k = h.eps / h.lights;
  const int materials = pick(1, 4);
  for (int i = 0; i < materials; ++i) {
    VectorMaterial m;
    m.name = fmt::format("m{}", i);
    m.lobe = element({Lobe::kPhong, Lobe::kBlinn, Lobe::kGaussian});
    if (m.lobe == Lobe::kGaussian) {
      m.roughness = log_uniform(1e-3, 1.0);
      if (one_in(4)) m.shininess = log_uniform(0.3, 1e4);  // else 2/omega^2
    } else {
      m.shininess = log_uniform(0.3, 1e4);
    }
    const double scale = log_uniform(std::min(eps_k / 4, 0.5), 1.0);
    std::array<double, 3> hue{uniform(0, 1), uniform(0, 1), uniform(0, 1)};
    hue[static_cast<std::size_t>(pick(0, 3))] = 1.0;
    for (auto& c : hue) c *= scale;
    m.specular = hue;
    h.materials.push_back(m);
  }
  validate(h);  // what the generator makes is a legal vector file header
  return h;
}

std::string describe_header(const VectorHeader& h) {
  std::string s = fmt::format("eps {} lights {}", h.eps, h.lights);
  bool white = true;
  for (const auto& i : h.light_intensity) white = white && i == std::array<double, 3>{1, 1, 1};
  if (!white) s += " coloured";
  for (const auto& m : h.materials)
    s += fmt::format(" | {} {} n={} omega={} specular={},{},{}", m.name, to_string(m.lobe),
                     m.shininess, m.roughness, m.specular[0], m.specular[1], m.specular[2]);
  return s;
}

// At most this many slots per case: coloured lights give a material a slot per distinct c_y (up
// to 3072 here), and every slot is checked on the whole input grid. A random subset of the slots
// make_slots() gives is kept, each slot's parameters exactly as the CLI makes them, and each served
// by its material's datapath group, built from the group's params as the CLI builds it (shared by
// the kept slots of one material). (Horner's shared guard is the largest any built group needs:
// over the subset's groups, not the whole file's.)
constexpr std::size_t kMaxSlots = 4;

SlotMap subset(const SlotMap& all) {
  if (all.params.size() <= kMaxSlots) return all;
  std::set<std::size_t> chosen;
  const int hi = static_cast<int>(all.params.size());
  while (chosen.size() < kMaxSlots) chosen.insert(static_cast<std::size_t>(pick(0, hi)));
  SlotMap s;
  s.per_light = all.per_light;
  s.materials = all.materials;
  s.display = all.display;
  s.eps_measure = all.eps_measure;
  s.skip_ratio = all.skip_ratio;
  std::map<std::uint32_t, std::uint32_t> regroup;  // the full map's group -> the subset's
  for (std::size_t i : chosen) {
    s.params.push_back(all.params[i]);
    s.lobe.push_back(all.lobe[i]);
    s.roughness.push_back(all.roughness[i]);
    s.c_y.push_back(all.c_y[i]);
    s.pixel_weight.push_back(all.pixel_weight[i]);
    s.pixel_weight_max.push_back(all.pixel_weight_max[i]);
    s.origin.push_back(all.origin[i]);
    const auto [it, fresh] =
        regroup.emplace(all.group[i], static_cast<std::uint32_t>(s.groups.size()));
    if (fresh) s.groups.push_back(all.groups[all.group[i]]);
    s.group.push_back(it->second);
  }
  return s;
}

// uq1.F formats: mostly the default 16-bit uq1.15, otherwise F in 8..20.
std::string gen_format() {
  return fmt::format("uq1.{}", one_in(2) ? 15 : pick(8, 21));
}
// Input formats likewise, but F in 17..20 only one case in 20: a case costs its whole input grid
// (2^(F+1) codes, 32 times uq1.15's at F = 20), and drawn as often as the narrow ones the wide
// formats took ~80 % of the run's time.
std::string gen_in_format() {
  if (one_in(20)) return fmt::format("uq1.{}", pick(17, 21));
  return fmt::format("uq1.{}", one_in(2) ? 15 : pick(8, 17));
}

// A spec of `unit` with each key present or left at its default at random, values drawn from
// the ranges the catalogue and the datapath headers advertise.
std::string gen_spec(const std::string& unit) {
  std::vector<std::pair<std::string, std::string>> keys;
  const auto maybe = [&](const std::string& key, const std::string& value) {
    if (one_in(2)) keys.emplace_back(key, value);
  };
  const auto integer = [](int lo, int hi) { return std::to_string(pick(lo, hi + 1)); };
  const auto n_format = [] { return fmt::format("uq{}.{}", pick(4, 17), pick(0, 9)); };
  maybe("in", gen_in_format());
  maybe("out", gen_format());
  if (one_in(8)) keys.emplace_back("skip", "off");
  if (unit == "pow") {
    maybe("n", n_format());
    maybe("log_bits", integer(1, 16));
    maybe("log_frac", integer(4, 30));
    maybe("y_frac", integer(4, 30));
    maybe("exp_bits", integer(1, 16));
    maybe("exp_frac", integer(4, 30));
  } else if (unit == "schlick") {
    maybe("n", n_format());
    maybe("divider", element<std::string>({"pipelined", "iterative"}));
  } else if (unit == "hast") {
    maybe("d", integer(1, 16));
    maybe("guard", one_in(3) ? std::string("auto") : integer(0, 20));
  } else if (unit == "horner") {
    maybe("degree", integer(1, 10));
    maybe("method", element<std::string>({"ls", "robust", "minimax"}));
    maybe("domain", element<std::string>({"tau", "full"}));
    maybe("constrain", element<std::string>({"on", "off"}));
    maybe("guard", one_in(3) ? std::string("auto") : integer(0, 20));
  } else if (unit == "lut") {
    maybe("bits", integer(1, 16));
    maybe("table_frac", one_in(3) ? std::string("auto") : integer(0, 40));
  } else if (unit == "sfu") {
    maybe("n", n_format());
  } else if (unit == "pwp") {
    // At most 2^6 segments: each is a Remez fit (and, where its quantized form is not monotone, a
    // monotone refit) when the case builds, and the catalogue's 2^10 only adds fits, not paths.
    maybe("segments", integer(0, 6));
    maybe("degree", integer(1, 3));
    maybe("coef_frac", one_in(3) ? std::string("auto") : integer(8, 30));
    maybe("guard", one_in(3) ? std::string("auto") : integer(0, 12));
  }
  // Every generated key is one the catalogue lists for the unit (the generator follows it).
  const UnitInfo& info = unit_info(unit);
  for (const auto& kv : keys) {
    const bool listed = std::any_of(info.keys.begin(), info.keys.end(),
                                    [&](const UnitKey& k) { return k.key == kv.first; });
    if (!listed) throw std::logic_error("generator key not in the catalogue: " + kv.first);
  }
  std::string spec = unit;
  char sep = ':';
  for (const auto& [k, v] : keys) {
    spec += fmt::format("{}{}={}", sep, k, v);
    sep = ',';
  }
  return spec;
}

// ---------------------------------------------------------------------------------------------
// The checks.

// Fails the case (RapidCheck then shrinks it) with what was found.
void fail(const std::string& what) {
  RC_FAIL(what);
}

// A refusal names the unit, and the key it refuses or the material (or light) it cannot serve.
void check_refusal(const std::string& unit, const UnitSpec& spec, const std::string& what) {
  RC_LOG() << "refused: " << what << "\n";
  const bool names_unit = what.find(unit) != std::string::npos;
  bool names_key =
      what.find("material '") != std::string::npos || what.find("light ") != std::string::npos;
  for (const auto& kv : spec.keys)
    names_key = names_key || what.find("'" + kv.first + "'") != std::string::npos;
  if (!names_unit || !names_key)
    fail(fmt::format("refusal names neither the unit and a key nor the material: \"{}\"", what));
}

std::string hex(double v) {
  return fmt::format("{:.17g}", v);
}

// Every property of one slot on the unit's whole input grid (see the file comment).
void check_slot(const SpecularUnit& u, const SlotMap& slots, std::size_t s, bool promises_one) {
  const MaterialParams& m = slots.params[s];
  const QFormat in = u.in_format(), out = u.out_format();
  const std::int64_t one = in.raw_one(), top = in.raw_max();
  const double h = in.ulp(), ulp_out = out.ulp();
  const std::int64_t tau_raw = u.tau_raw(s);
  const SlotContract c = slot_contract(u, s, slots);
  const double total = c.bound.total();
  const double dp_ulps = u.datapath_bound_ulps(s);
  RC_LOG() << "slot " << s << " " << m.name << ": n=" << m.shininess << " tau=" << m.tau
           << " level=" << m.level << " c_y=" << slots.c_y[s] << " always_skip=" << m.always_skip
           << " threshold_raw=" << tau_raw << " bound=" << total << " (input " << c.bound.input
           << ", parameter " << c.bound.parameter << ", approximation " << c.bound.approximation
           << ", datapath " << c.bound.datapath << ", skip " << c.bound.skip
           << ") contract=" << to_string(c.kind) << "\n";

  // The skip set inside the float test on real t: the real t that round to a skipped code all lie
  // below (tau_raw + 1/2) h, which must not exceed tau. Never-skip materials (tau < 0) skip none.
  if (u.comparator_enabled() && !m.always_skip) {
    if (m.tau < 0) {
      if (tau_raw != -1) fail(fmt::format("never-skip slot has threshold {}", tau_raw));
    } else if (tau_raw >= 0 && (static_cast<double>(tau_raw) + 0.5) * h > m.tau) {
      fail(fmt::format("threshold {} skips real t up to {} above tau {}", tau_raw,
                       (static_cast<double>(tau_raw) + 0.5) * h, m.tau));
    }
  }

  // The simulator's paths over the whole grid at once.
  const std::size_t codes = static_cast<std::size_t>(top + 1);
  std::vector<std::int64_t> t_raw(codes), batch(codes);
  std::vector<std::uint8_t> batch_skip(codes);
  for (std::size_t i = 0; i < codes; ++i) t_raw[i] = static_cast<std::int64_t>(i);
  u.eval_batch(s, t_raw.data(), batch.data(), batch_skip.data(), codes);
  std::vector<std::int64_t> staged(u.stages().size());
  const std::size_t result = u.stages().result_index();

  // model() (a long double pow or Horner per code) is most of a case's time, and slot_contract()
  // already evaluates it at every kept code: the datapath budget is checked at every 4th code (a
  // random phase per slot, so the cases cover every residue) and at 1.0. Everything else,
  // monotonicity and the total bound included, is checked at every code.
  constexpr std::int64_t kModelStride = 4;
  const std::int64_t model_phase = pick(0, kModelStride);
  std::int64_t prev = 0;
  std::vector<double> y(codes);  // the comparator-then-datapath output per code, as a real
  for (std::int64_t code = 0; code <= top; ++code) {
    const auto i = static_cast<std::size_t>(code);
    const bool skipped = u.skip(s, code);
    const std::int64_t e = u.eval(s, code);
    const std::int64_t out_raw = skipped ? 0 : e;
    y[i] = static_cast<double>(out_raw) * ulp_out;
    if (batch[i] != out_raw || (batch_skip[i] != 0) != skipped)
      fail(fmt::format("code {}: eval_batch gives {} (skipped {}), eval {} (skipped {})", code,
                       batch[i], batch_skip[i], out_raw, skipped));
    u.eval_staged(s, code, staged.data());
    if (staged[result] != e)
      fail(fmt::format("code {}: staged result register {} != eval {}", code, staged[result], e));
    if (out_raw < prev)
      fail(fmt::format("not monotone: code {} gives {}, code {} gave {} (t = {})", code, out_raw,
                       code - 1, prev, static_cast<double>(code) * h));
    prev = out_raw;
    if (skipped) {
      // Imperceptible: what the datapath would have given, times c_y, is at most eps_K.
      if (static_cast<double>(e) * ulp_out > m.level)
        fail(fmt::format("skipped code {} would give {} > level eps_K/c_y = {}", code,
                         static_cast<double>(e) * ulp_out, m.level));
    } else if (code % kModelStride == model_phase || code == one) {
      // The datapath against the unit's own real-valued model. 1e-6 ulp covers the double
      // evaluation of the model (test_mpfr_oracle: within 1e-12 of the exact value).
      const double err_ulps = std::fabs(static_cast<double>(e) - u.model(s, code) / ulp_out);
      if (err_ulps > dp_ulps + 1e-6)
        fail(fmt::format("code {}: |eval - model| = {} ulp > datapath_bound_ulps {}", code,
                         err_ulps, dp_ulps));
    }
  }
  if (promises_one) {
    const std::int64_t want = (m.always_skip && u.comparator_enabled()) ? 0 : out.raw_one();
    if (batch[static_cast<std::size_t>(one)] != want)
      fail(fmt::format("f(1) = {} raw, promised {}", batch[static_cast<std::size_t>(one)], want));
  }

  // The total bound on real t. The tolerance (1e-12 relative) is the double measurement's own
  // rounding: the contract measures with the same doubles (test_mpfr_oracle bounds them).
  const auto check_t = [&](double t) {
    const std::int64_t code = quantize_input(t, in);
    const double r = reference_value(slots, s, t);
    const double err = std::fabs(y[static_cast<std::size_t>(code)] - r);
    if (err > total * (1 + 1e-12))
      fail(fmt::format("t = {} (code {}): |y - r(t)| = {} > bound {} (y {}, r {})", hex(t), code,
                       err, total, y[static_cast<std::size_t>(code)], r));
  };
  for (std::int64_t code = 0; code <= one; ++code) {
    const double t = static_cast<double>(code) * h;
    check_t(t);
    // Both sides of the rounding boundary above the code (the ends of its rounding cell).
    const double edge = t + 0.5 * h;
    check_t(std::nextafter(edge, -1.0));
    check_t(std::nextafter(edge, 2.0));
  }
  for (int k = 0; k < 64; ++k) check_t(uniform(-1.0, kVectorTMax));
  for (int k = 0; k < 8; ++k) check_t(uniform(1.0, kVectorTMax));
  for (int k = 0; k < 8; ++k) check_t(-log_uniform(1e-9, 1.0));
}

// One accepted-or-refused case of `unit`: refused specs must name their reason (then the case is
// discarded, so the case count is of accepted cases); accepted ones hold every slot property.
void check_unit_case(const std::string& unit) {
  const VectorHeader header = gen_header();
  const SlotMap slots = subset(make_slots(header));
  const std::string spec_text = gen_spec(unit);
  RC_LOG() << "spec " << spec_text << "\nheader " << describe_header(header) << "\n";
  const UnitSpec spec = parse_unit_spec(spec_text);
  std::unique_ptr<SpecularUnit> u;
  try {
    u = make_unit(spec, slots);
  } catch (const std::invalid_argument& e) {
    check_refusal(unit, spec, e.what());
    RC_TAG("refused");
    RC_DISCARD("refused spec (its message checked)");
  }
  RC_TAG(u->in_format().name() == "uq1.15" ? "in=uq1.15" : "other input format");
  const bool promises_one = !(unit == "horner" && u->describe()["config"]["constrain"] == "off");
  for (std::size_t s = 0; s < slots.params.size(); ++s) check_slot(*u, slots, s, promises_one);
}

TEST(ContractProperties, pow) {
  check_property([] { check_unit_case("pow"); });
}
TEST(ContractProperties, schlick) {
  check_property([] { check_unit_case("schlick"); });
}
TEST(ContractProperties, hast) {
  check_property([] { check_unit_case("hast"); });
}
TEST(ContractProperties, horner) {
  check_property([] { check_unit_case("horner"); });
}
TEST(ContractProperties, lut) {
  check_property([] { check_unit_case("lut"); });
}
// Half the cases: sfu draws one key of its own (n; pow draws six), and each case costs about twice
// a pow case (its build sweeps every input code for the bound, then the case sweeps them again).
TEST(ContractProperties, sfu) {
  check_property([] { check_unit_case("sfu"); }, 2);
}
// Half the cases: a pwp case's build fits up to 2^6 segments per group and sweeps every code of
// the span for monotonicity (2000 cases: 27 s CPU in Release, lut's 32 s); its specs are held
// exhaustively over 2^16 codes by ExhaustiveUnits.PwpWithinBudgetMonotone.
TEST(ContractProperties, pwp) {
  check_property([] { check_unit_case("pwp"); }, 2);
}

// Every unit in the catalogue has its property above.
TEST(ContractProperties, EveryUnitCovered) {
  EXPECT_EQ(unit_names(),
            (std::vector<std::string>{"pow", "schlick", "hast", "horner", "lut", "sfu", "pwp"}));
  // sfu and pwp are one --unit away: the default set, and every default output, are as before
  // them.
  EXPECT_EQ(default_unit_names(),
            (std::vector<std::string>{"pow", "schlick", "hast", "horner", "lut"}));
}

// ---------------------------------------------------------------------------------------------
// Regression cases: failures the properties found, shrunk by RapidCheck, each kept as a plain test
// of the property it broke (each fails until the unit is fixed; see the comment of each).

// A one-material header as the generator makes it (white light).
VectorHeader one_material(double eps, Lobe lobe, double n, std::array<double, 3> specular) {
  VectorHeader h;
  h.eps = eps;
  h.lights = 1;
  h.light_intensity.assign(1, {1.0, 1.0, 1.0});
  VectorMaterial m;
  m.name = "m0";
  m.lobe = lobe;
  m.shininess = n;
  m.specular = specular;
  h.materials.push_back(m);
  validate(h);
  return h;
}

// Found by ContractProperties.hast (and .horner, the same class): with skip=off a material whose
// lobe never reaches eps (c_y <= eps, always skipped by Källberg's test) is still computed, but
// the u scaler's root is put at the top of the input format (root_threshold_raw of an
// always-skip material), so u = 0 and the output is 0 everywhere: f(1) = 0 where the unit
// promises exactly 1.0.
TEST(RegressionCases, HastSkipOffAlwaysSkippedMaterialGivesZeroAtOne) {
  const SlotMap slots = make_slots(one_material(1e-6, Lobe::kPhong, 0.3, {2.5e-7, 0, 0}));
  ASSERT_TRUE(slots.params[0].always_skip);
  const auto u = make_unit(parse_unit_spec("hast:in=uq1.8,out=uq1.8,skip=off,d=1"), slots);
  EXPECT_EQ(u->eval_with_skip(0, u->in_format().raw_one()), u->out_format().raw_one());
}
TEST(RegressionCases, HornerSkipOffAlwaysSkippedMaterialGivesZeroAtOne) {
  const SlotMap slots = make_slots(one_material(1e-6, Lobe::kPhong, 0.3, {2.5e-7, 0, 0}));
  const auto u = make_unit(
      parse_unit_spec("horner:in=uq1.15,out=uq1.8,skip=off,degree=1,method=ls,domain=tau"), slots);
  EXPECT_EQ(u->eval_with_skip(0, u->in_format().raw_one()), u->out_format().raw_one());
}

// Found by ContractProperties.horner: a full-domain least-squares fit (degree 2, constrained to
// P(1) = 1 only) of the Gaussian material's equivalent t^(2e6) starts at P(0) > P(2^-8): the
// output steps back from 171 to 166 (ulps of uq1.9). Horner's fits are not monotone by
// construction (issue 7 item 3).
TEST(RegressionCases, HornerFullDomainFitOfLowShininessNotMonotone) {
  // The shrunk header: one black light (coloured, so slots are light x material, c_y = 0), a
  // Gaussian material of omega = 1e-3 (n = 2e6) beside two of n = 0.3; the guard is shared.
  VectorHeader h = one_material(1e-6, Lobe::kPhong, 0.3, {2.5e-7, 0, 0});
  h.light_intensity = {{0.0, 0.0, 0.0}};
  VectorMaterial g = h.materials[0];
  g.name = "m1";
  g.lobe = Lobe::kGaussian;
  g.shininess = 0;
  g.roughness = 1e-3;
  VectorMaterial m2 = h.materials[0];
  m2.name = "m2";
  h.materials.push_back(g);
  h.materials.push_back(m2);
  validate(h);
  const SlotMap slots = make_slots(h);
  const auto u = make_unit(parse_unit_spec("horner:in=uq1.8,out=uq1.9,skip=off,degree=2,method=ls,"
                                           "domain=full,constrain=on"),
                           slots);
  // Slot 1, the Gaussian material's, steps back from 171 to 166 at code 1.
  for (std::size_t s = 0; s < slots.params.size(); ++s) {
    for (std::int64_t c = 1; c <= u->in_format().raw_max(); ++c)
      ASSERT_GE(u->eval_with_skip(s, c), u->eval_with_skip(s, c - 1))
          << "slot " << s << " code " << c;
  }
}

// Found by ContractProperties.horner: the same non-monotone full-domain fit makes the comparator
// threshold wrong. unit_threshold_raw bisects for the last code whose output is <= eps_K / c_y,
// assuming a monotone output; P(0) = 2^-12 (the robust fit is not pinned to 0 at t = 0 on the full
// domain) lies above the level 1.92e-4 while a code higher up does not, so code 0 is skipped
// though its output would be visible.
TEST(RegressionCases, HornerFullDomainSkipsAPerceptibleOutput) {
  const SlotMap slots = make_slots(one_material(1e-6, Lobe::kPhong, 4.039463786052832,
                                                {0.022039981081057602, 0.0007242517524803346, 0}));
  const auto u = make_unit(
      parse_unit_spec("horner:in=uq1.15,out=uq1.12,method=robust,domain=full,constrain=on"), slots);
  const double level = slots.params[0].level;
  for (std::int64_t c = 0; c <= u->tau_raw(0); ++c)
    EXPECT_LE(std::ldexp(static_cast<double>(u->eval(0, c)), -12), level) << "skipped code " << c;
}

// Found by ContractProperties.horner: on the full domain horner's budget takes u = t as exact
// (src/units/horner/datapath.cpp, datapath_bound_ulps and horner_required_guard drop the u
// rounding term when !tau_domain), but the u scaler still rounds t to fh = out + guard fraction
// bits: with in = uq1.16 and fh = 15 (guard=0) u loses a bit, and |eval - model| reaches 0.5045 ulp
// against a stated 0.5 (correctly rounded).
TEST(RegressionCases, HornerFullDomainInputWiderThanChainBreaksTheBudget) {
  const SlotMap slots = make_slots(one_material(1e-6, Lobe::kPhong, 0.3, {2.5e-7, 0, 0}));
  const auto u = make_unit(parse_unit_spec("horner:in=uq1.16,out=uq1.15,skip=off,degree=1,"
                                           "method=ls,domain=full,constrain=on,guard=0"),
                           slots);
  const double ulp = u->out_format().ulp();
  double worst = 0;
  std::int64_t at = -1;
  for (std::int64_t c = 0; c <= u->in_format().raw_one(); ++c) {
    const double err = std::fabs(static_cast<double>(u->eval(0, c)) - u->model(0, c) / ulp);
    if (err > worst) worst = err, at = c;
  }
  EXPECT_LE(worst, u->datapath_bound_ulps(0) + 1e-6) << "at code " << at;
}

// Found by ContractProperties.horner: the total bound fails off the grid, |y - r(t)| = 0.170574 >
// bound 0.170393 at t = 0.56980895996093761, with in = uq1.15 and the auto guard on the full
// domain (fh < 15: u = t rounded, the same unbudgeted rounding as the case above; the datapath
// part of the bound is the understated budget).
TEST(RegressionCases, HornerFullDomainTotalBoundFailsOffTheGrid) {
  const SlotMap slots = make_slots(
      one_material(1e-6, Lobe::kPhong, 1.9742106482820814,
                   {0.0006879454873745698, 0.0001308486060465273, 0.0002238208818150863}));
  const auto u = make_unit(parse_unit_spec("horner:in=uq1.15,out=uq1.8,skip=off,degree=1,"
                                           "domain=full,constrain=on,guard=auto"),
                           slots);
  const SlotContract c = slot_contract(*u, 0, slots);
  const double t = 0.56980895996093761;
  const std::int64_t code = quantize_input(t, u->in_format());
  const double y = std::ldexp(static_cast<double>(u->eval_with_skip(0, code)), -8);
  EXPECT_LE(std::fabs(y - reference_value(slots, 0, t)), c.bound.total());
}

// Found by the long run (100 000 cases, horner): a uq1.20 input has 2^20 + 1 codes in [0, 1], one
// more than the contract's exact sweep took, so it was sampled every 2nd code and missed the code
// where a narrow Gaussian lobe's approximation error peaks (bound 0.61910 < error 0.61932).
TEST(RegressionCases, HornerUq1p20InputIsSweptOnEveryCode) {
  VectorHeader h;
  h.eps = 0.004333502902454338;
  h.lights = 1;
  h.light_intensity.assign(1, {1.0, 1.0, 1.0});
  VectorMaterial m;
  m.name = "m0";
  m.lobe = Lobe::kGaussian;
  m.roughness = 0.016023964309972386;
  m.specular = {0.017105809785302215, 0.003403634055102151, 0.012111084691804403};
  h.materials.push_back(m);
  validate(h);
  const SlotMap slots = make_slots(h);
  const auto u = make_unit(parse_unit_spec("horner:in=uq1.20,out=uq1.8,skip=off,degree=1,"
                                           "method=ls,domain=tau,constrain=on"),
                           slots);
  const SlotContract c = slot_contract(*u, 0, slots);
  EXPECT_TRUE(c.exact);
  const double t = 0.99993848800659169;
  const std::int64_t code = quantize_input(t, u->in_format());
  const double y = std::ldexp(static_cast<double>(u->eval_with_skip(0, code)), -8);
  EXPECT_LE(std::fabs(y - reference_value(slots, 0, t)), c.bound.total());
}

}  // namespace
}  // namespace glint
