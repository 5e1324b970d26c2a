// horner in Verilog: the u scaler's root and k and every quantized coefficient are read from the
// built HornerUnits (HornerUnit::coeff_raw, after the constraint repair), never refitted here.
#include "units/horner/rtl.h"

#include <fmt/format.h>

#include <algorithm>

#include "hdl/verilog.h"
#include "units/stage_rtl.h"
#include "units/u_scaler_rtl.h"

namespace glint {

std::string horner_rtl(const hdl::DatapathPorts& p, const std::vector<HornerUnit>& groups,
                       const StageLayout& layout) {
  using hdl::ext;
  using hdl::lit;
  using hdl::range;
  const HornerUnit& first = groups.front();
  const QFormat out = first.config().out;
  const int wo = out.width(), fo = out.frac_bits, wg = p.group_bits;
  const int fh = first.internal_frac(), w = fh + 1;
  const int degree = static_cast<int>(first.coeff_raw().size()) - 1;
  const Stage& scale = rtl_stage(layout, "scale");
  const int cw = scale.registers[1].format.width();  // coefficients, signed
  const int aw = degree > 1 ? rtl_stage(layout, "mac1").registers[1].format.width() : cw;
  std::vector<const UScaler*> scalers;
  for (const HornerUnit& u : groups) scalers.push_back(&u.scaler());
  const auto coeff = [&](int k) {
    std::vector<std::int64_t> v;
    for (const HornerUnit& u : groups) v.push_back(u.coeff_raw()[static_cast<std::size_t>(k)]);
    return v;
  };

  std::string s = hdl::datapath_header(
      p, fmt::format("{}: horner, a fitted polynomial of degree {} by Horner's rule (Öztürk et al. "
                     "2006, eq.12),\n"
                     "one multiply-add a stage (HornerUnit::run in units/horner/datapath.h): acc "
                     "= c_p; acc = round(acc u) + c_k,\n"
                     "k = p-1..1, rounding half up to {} fraction bits; the last stage forms acc "
                     "u + c_0 exactly, rounds once\n"
                     "to the output's {} fraction bits and clamps to [0, 1]. u = {}.",
                     p.module, degree, fh, fo,
                     first.coefficients().tau_domain ? "(t - tau_q) / (1 - tau_q) (the u scaler)"
                                                     : "t (full domain: root 0, k = 1)"));
  s += hdl::datapath_input_stage(p);
  s += rtl_stage_registers(scale, "u, and acc = c_p");
  s += u_scaler_rtl(p, scalers, first.config().in, fh, first.coefficients().tau_domain);
  s += hdl::group_table(p, "c" + std::to_string(degree), "in_group", cw, coeff(degree),
                        fmt::format("c_{}, sq{}.{} (HornerUnit::coeff_raw)", degree, cw - fh, fh),
                        true);
  // The group is carried down the pipeline as far as a stage reads a coefficient that differs
  // between groups (g<m> beside position m).
  // tables=ram: any stage's coefficient may differ once loaded, so it goes the whole way.
  int carry = p.ram != nullptr && p.groups > 1 ? degree : 0;
  for (int m = 1; m <= degree; ++m) {
    const std::vector<std::int64_t> v = coeff(degree - m);
    if (std::any_of(v.begin(), v.end(), [&](std::int64_t x) { return x != v.front(); }))
      carry = std::max(carry, m);
  }
  for (int m = 1; m <= carry; ++m)
    s += fmt::format("  reg {} g{};  // the group carried beside position {}\n", range(wg), m, m);
  s += "  always @(posedge clk) begin\n";
  s += fmt::format("    {} <= scaler_u;\n", rtl_reg(scale, 0));
  s += fmt::format("    {} <= c{};\n", rtl_reg(scale, 1), degree);
  if (carry >= 1) s += "    g1 <= in_group;\n";
  s += "  end\n";

  std::string u_prev = rtl_reg(scale, 0), acc_prev = rtl_reg(scale, 1);
  int acc_w = cw;
  for (int m = 1; m <= degree; ++m) {
    const Stage& st = rtl_stage(layout, fmt::format("mac{}", m));
    const int k = degree - m;  // the coefficient this stage adds
    const bool last = m == degree;
    const std::string g = m <= carry ? fmt::format("g{}", m) : std::string("in_group");
    s += rtl_stage_registers(
        st, last ? "acc u + c_0 exact, rounded once to the output, clamped to [0, 1]"
                 : fmt::format("u carried, acc = round(acc u) + c_{}", k));
    const std::string cname = st.name + "_c";
    s += hdl::group_table(p, cname, g, cw, coeff(k),
                          fmt::format("c_{}, sq{}.{} (HornerUnit::coeff_raw)", k, cw - fh, fh),
                          true);
    // acc (signed) times u (unsigned, a zero sign bit), in two's complement of pw bits.
    const int pw = std::max(acc_w + w + 1, cw + fh + 1) + 1;
    const std::string prod = st.name + "_p";
    s += fmt::format("  wire signed {} {} = {} * {};\n", range(pw), prod,
                     ext(acc_prev, acc_w, pw, true), ext(u_prev, w, pw));
    if (!last) {
      const std::string sh = st.name + "_s";
      s += fmt::format("  wire signed {} {} = ({} + {}) >>> {};  // round half up\n", range(pw), sh,
                       prod, hdl::slit(pw, fh > 0 ? std::int64_t{1} << (fh - 1) : 0), fh);
      s += fmt::format("  wire signed {} {}_c_ext = {};\n", range(aw), st.name,
                       ext(cname, cw, aw, true));
      if (pw > aw)
        s += fmt::format("  wire unused_{} = ^{}[{}:{}];  // |acc| < 2^{}: the layout's bound\n",
                         st.name, sh, pw - 1, aw, aw - 1);
      s += "  always @(posedge clk) begin\n";
      s += fmt::format("    {} <= {};\n", rtl_reg(st, 0), u_prev);
      s += fmt::format("    {} <= {} + {}_c_ext;\n", rtl_reg(st, 1), ext(sh, pw, aw), st.name);
      if (m + 1 <= carry) s += fmt::format("    g{} <= g{};\n", m + 1, m);
      s += "  end\n";
      u_prev = rtl_reg(st, 0);
      acc_prev = rtl_reg(st, 1);
      acc_w = aw;
      continue;
    }
    // Last: (acc u + c_0 2^fh + half) >> (2 fh - fo), then the clamp.
    const int shift = 2 * fh - fo;
    const std::string y = st.name + "_y";
    s +=
        fmt::format("  wire signed {} {}_c0 = {};\n", range(pw), st.name, ext(cname, cw, pw, true));
    s += fmt::format("  wire signed {} {} = ({} + ({}_c0 <<< {}) + {}) >>> {};\n", range(pw), y,
                     prod, st.name, fh,
                     hdl::slit(pw, shift > 0 ? std::int64_t{1} << (shift - 1) : 0), shift);
    const std::int64_t one = out.raw_one();
    s += "  always @(posedge clk)\n";
    s += fmt::format("    {} <= ({} < {}) ? {} : ({} > {}) ? {} : {};\n", rtl_reg(st, 0), y,
                     hdl::slit(pw, 0), lit(wo, 0), y, hdl::slit(pw, one), lit(wo, one),
                     ext(y, pw, wo));
    s += fmt::format("  assign result = {};\n", rtl_reg(st, 0));
  }
  s += hdl::datapath_footer(p);
  return s;
}

}  // namespace glint
