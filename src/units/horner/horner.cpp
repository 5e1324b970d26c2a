// horner: keys, build (one fit per datapath group), timing, stage layout, cost inventory and
// description.
//
// Hardware (L = degree + 1, II 1): stage 1 the u scaler (tau domain; on the full domain u = t is
// wiring) beside the read of c_p; then p multiply-add stages, each a multiplier Wacc x (fh + 1)
// and an adder Wacc (Wacc = acc_int_bits + fh, signed) with its coefficient bank read beside the
// multiply; the coefficient tables are p + 1 banks x slots x coefficient width; the last stage
// clamps to [0, 1].
#include "units/horner/horner.h"

#include <fmt/format.h>

#include <algorithm>

#include "fit/monotone.h"
#include "units/horner/datapath.h"
#include "units/horner/fit_engine.h"
#include "units/horner/rtl.h"
#include "units/horner/slots.h"
#include "units/u_scaler_cost.h"
#include "units/unit_set.h"

namespace glint {
namespace {

// The datapath's config plus what the whole unit shares: the fit domain decides whether the u
// scaler (and the root in the comparator register) is built.
struct HornerSetup {
  HornerConfig datapath;
  bool tau_domain = true;
};

// c_k of every datapath group.
std::vector<std::int64_t> coefficients(const std::vector<HornerUnit>& units, int k) {
  std::vector<std::int64_t> v;
  for (const HornerUnit& u : units) v.push_back(u.coeff_raw()[static_cast<std::size_t>(k)]);
  return v;
}

// The first multiply-add's acc is the stage-1 register that holds c_p (cw bits, as the RTL's
// first product takes it, not the accumulator's width). When the scene fixes the coefficients,
// that register is loaded from a ROM: Yosys removes its flip-flops whose input is a constant
// (merging those of equal inputs), so a bit that is 0 in every group's c_p builds no partial
// products, and with every c_p non-negative the sign extension is zeros: an unsigned product of
// the bits some c_p sets (one c_p is a multiplier by a constant).
Seg first_multiply(CostBuilder& b, const std::vector<std::int64_t>& cp, bool known, int wu, int cw,
                   const std::string& what) {
  const bool non_negative =
      std::all_of(cp.begin(), cp.end(), [](std::int64_t v) { return v >= 0; });
  if (known && std::all_of(cp.begin(), cp.end(), [&](std::int64_t v) { return v == cp[0]; }))
    return b.const_multiplier(wu, cp.front(), what, true);
  if (known && non_negative) return b.table_multiplier(wu, cp, what);
  return b.multiplier(cw, wu, what, 1, true);
}

struct Horner : UnitKindDefaults {
  using Config = HornerSetup;
  using Datapath = HornerUnit;
  static constexpr const char* kName = "horner";
  static constexpr const char* kSummary =
      "fitted polynomial, Horner pipeline (Öztürk eq.12), one multiply-add per stage";

  using Keys = HornerKeys;
  static constexpr CosimCase kCosimCases[] = {
      {"default", "", "--vectors traces/phong_basic.vec --sink-ready 0.7"},
      {"full_ls", "degree=2,domain=full,method=ls", "--vectors traces/blinn_colored.vec"},
      {"wide", "degree=10,guard=12", "--vectors traces/phong_basic.vec --sink-ready 0.5"},
      {"deg6_lights", "degree=6,guard=8",
       "--vectors traces/eight_lights.vec --sink-ready 0.9 --seed 3"},
      {"ram", "tables=ram", "--vectors traces/phong_basic.vec --sink-ready 0.7"},
      {"ram_full", "tables=ram,degree=3,domain=full,in=uq1.12",
       "--vectors traces/multi_light.vec --sink-ready 0.5"}};

  static std::unique_ptr<SpecularUnit> build(const KeyReader& keys, const CommonKeys& common,
                                             const SlotPlan& plan) {
    const int degree = keys.read(Keys::degree);
    const std::string method = keys.read(Keys::method);
    const std::string domain = keys.read(Keys::domain);
    const bool constrain = keys.read(Keys::constrain);
    const std::string fit = keys.read(Keys::fit);
    HornerConfig c{common.in, common.out, keys.read(Keys::guard), common.skip};
    HornerFitSpec spec;
    spec.degree = degree;
    spec.method = parse_fit_method(method);
    spec.tau_domain = domain == "tau";
    spec.constrain = constrain;
    spec.engine = parse_horner_fit_engine(fit);
    if (spec.engine == HornerFitEngine::kSollya && !sollya_fits(spec))
      // refusal: horner.fit_sollya_spec
      keys.fail(std::string(Keys::fit.name), fit,
                fmt::format("Sollya fits method=minimax on domain=tau with a free coefficient "
                            "(degree >= 2 with constrain=on), not method={}, domain={}, degree "
                            "{}, constrain={}; use fit=best or fit=glint",
                            method, domain, degree, constrain ? "on" : "off"));
    // One fit per datapath group, on the group's [tau_q, 1]: the smallest tau of its slots, so
    // every input any of their comparators lets through lies in the fitted domain.
    std::vector<HornerUnit> units = build_horner_slots(spec, c, plan.groups);
    nlohmann::json config = common_config(common);
    put_key(config, Keys::degree, degree);
    put_key(config, Keys::method, method);
    put_key(config, Keys::domain, domain);
    put_key(config, Keys::constrain, constrain);
    put_key(config, Keys::fit, fit);
    put_key(config, Keys::guard, c.guard);
    // u scaler stage, then one multiply-add stage per degree.
    const UnitTiming timing{degree + 1, 1, 0};
    return make_unit_set<Horner>(common, std::move(config), HornerSetup{c, domain == "tau"},
                                 std::move(units), plan, timing);
  }

  // Widest coefficient and accumulator over the slots (the registers are shared).
  static std::pair<QFormat, QFormat> coefficient_and_acc(const Config& c,
                                                         const std::vector<Datapath>& units) {
    const int fh = c.datapath.out.frac_bits + c.datapath.guard;
    int cw = 1, acc = 1;
    for (const HornerUnit& u : units) {
      cw = std::max(cw, u.coeff_format().int_bits);
      acc = std::max(acc, u.acc_int_bits());
    }
    return {sq(cw, fh), sq(acc, fh)};
  }

  static std::vector<Stage> stages(const Config& c, const std::vector<Datapath>& units,
                                   UnitTiming timing) {
    const HornerConfig& d = c.datapath;
    const QFormat uf = uq(1, d.out.frac_bits + d.guard);
    const auto [cf, accf] = coefficient_and_acc(c, units);
    const int p = timing.latency - 1;
    std::vector<Stage> s{input_stage(), {"scale", 1, 1, {{"u", uf}, {"acc", cf}}}};
    for (int k = 1; k <= p; ++k) {
      Stage m{"mac" + std::to_string(k), k + 1, k + 1, {{"u", uf}, {"acc", accf}}};
      if (k == p) m.registers = {{"result", d.out}};
      s.push_back(std::move(m));
    }
    return s;
  }

  static void cost(CostBuilder& b, const LaneShape& L, const Config& c,
                   const std::vector<Datapath>& units) {
    const int p = L.latency - 1;
    const int fh = L.out.frac_bits + c.datapath.guard;
    const bool tau_domain = c.tau_domain;
    const int wo = L.out.width();
    int cw = 0, wk = 0, acc_int = 0;
    for (const HornerUnit& u : units) {
      cw = std::max(cw, u.coeff_format().width());
      wk = std::max(wk, u.scaler().k_int_bits() + u.scaler().k_frac());
      acc_int = std::max(acc_int, u.acc_int_bits());
    }
    const int wacc = acc_int + fh;  // signed accumulator

    // One coefficient bank per stage, every bank holding all datapath groups.
    // Their contents (bank k: c_k of every group) are known unless the chip loads them; a
    // coefficient every group shares is a constant (the RTL's group_table writes a wire).
    const bool known = !L.tables_ram && L.groups == static_cast<int>(units.size());
    std::vector<std::int64_t> words;
    for (int k = 0; k <= p; ++k)
      for (const HornerUnit& u : units) words.push_back(u.coeff_raw()[static_cast<std::size_t>(k)]);
    const Seg coef = b.slot_table(L.groups, cw, p + 1, false,
                                  "coefficient tables (per datapath group, one bank per stage)",
                                  known ? &words : nullptr);
    b.op("table_read", p + 1);
    // Stage 1: the u scaler (tau domain; on the full domain u = t is wiring), c_p read beside it.
    // k from a ROM of known contents (u_scaler_cost.h); c_p's register feeds the first
    // multiply-add (first_multiply).
    std::vector<std::int64_t> ks;
    for (const HornerUnit& u : units) ks.push_back(u.scaler().k_raw());
    const std::vector<std::int64_t> cp = coefficients(units, p);
    const Seg first =
        tau_domain ? parallel(coef, series(u_scaler_cost(b, L, wk, fh, known ? &ks : nullptr)))
                   : coef;
    b.reg((fh + 1) + cw + L.group_bits, "stage 1: u, c_p, group id");
    b.stage("stage 1", {first});
    for (int s = 2; s <= p + 1; ++s) {
      const bool last = s == p + 1;
      const int k = p + 1 - s;  // the coefficient this stage adds
      const std::string what = fmt::format("stage {}: acc u", s);
      // On the full domain u = t: below the input's fraction bits its bits are zeros, and Yosys
      // builds no partial products for them.
      const int wu = tau_domain ? fh + 1 : std::min(fh + 1, L.in.frac_bits + 1);
      const Seg mul = s == 2 ? first_multiply(b, cp, known, wu, cw, what)
                             : b.multiplier(wacc, wu, what, 1, true);
      b.op("mul");
      std::vector<Seg> sp{parallel(mul, coef)};
      // c_k = 0 in every group (c_0 of a fit held to 0 at u = 0): the RTL adds a constant zero
      // and Yosys builds no adder.
      const std::vector<std::int64_t> ck = coefficients(units, k);
      if (!known || std::any_of(ck.begin(), ck.end(), [](std::int64_t v) { return v != 0; })) {
        // The + c_k adder's carries run while the product's high bits settle: on the calibration
        // set's stages it adds about half an adder's depth to the multiplier's (horner's full
        // domain: 44-46 gates against 36 for the product alone).
        Seg add = b.adder(wacc, fmt::format("stage {}: + c_{}", s, k));
        add.delay /= 2;
        add.ns /= 2;
        sp.push_back(add);
        b.op("add");
      }
      if (last) {
        sp.push_back(b.mux(wo, 3, fmt::format("stage {}: clamp to [0, 1]", s)));
        b.reg(wo, fmt::format("stage {}: result", s));
      } else {
        b.reg((fh + 1) + wacc + L.group_bits, fmt::format("stage {}: u, acc, group id", s));
      }
      b.stage(fmt::format("stage {}", s), sp);
    }
  }

  static std::string rtl(const hdl::DatapathPorts& p, const Config&,
                         const std::vector<Datapath>& units, const StageLayout& layout) {
    return horner_rtl(p, units, layout);
  }
  static nlohmann::json describe_slot(const Datapath& u) {
    nlohmann::json slot{{"root_raw", u.scaler().root_raw()},
                        {"k", u.scaler().k_value()},
                        {"k_int_bits", u.scaler().k_int_bits()},
                        {"k_frac_bits", u.scaler().k_frac()},
                        {"coefficients", u.coefficients().c},
                        {"coefficients_raw", u.coeff_raw()},
                        {"coefficient_format", u.coeff_format().name()},
                        {"acc_int_bits", u.acc_int_bits()},
                        {"fit_engine", u.coefficients().engine}};
    if (u.coefficients().sup_certified)
      slot["sup_norm"] = {{"lo", u.coefficients().sup_lo}, {"hi", u.coefficients().sup_hi}};
    return slot;
  }
  static bool carries_root(const Config& c) { return c.tau_domain; }
  // clamp(P, 0, 1) of the quantized (model) and fitted (float_model) coefficients, in u
  // non-decreasing in t, each proven non-decreasing on [0, 1] by Bernstein bounds.
  static bool models_monotone(const Datapath& u) {
    return u.polynomial_monotone() && check_monotone(u.coefficients().c) == Monotonicity::kProven;
  }
};

}  // namespace

const UnitDescription& horner_unit() {
  static const DescriptionOf<Horner> description;
  return description;
}

}  // namespace glint
