// schlick in Verilog: each group's n' is its SchlickUnit::n_raw; D, the numerator and the
// restoring division are SchlickUnit::run's (and record_divider's partial remainders).
#include "units/schlick/rtl.h"

#include <fmt/format.h>

#include "hdl/verilog.h"
#include "units/stage_rtl.h"

namespace glint {
namespace {

// One restoring step: X = 2 R + next numerator bit (`x`, rw bits), quotient bit X >= D, the new
// partial remainder. Wires <p>_d, <p>_b and <p>_r. One subtractor one bit wider than X: its borrow
// is the comparison (no comparator beside it, which Yosys would not share with the subtractor:
// 27-32 % more area a row).
std::string divider_step(const std::string& p, const std::string& x, const std::string& den, int dw,
                         int rw) {
  std::string s;
  s += fmt::format("  wire {} {}_d = {} - {};  // X - D, the top bit its borrow\n",
                   hdl::range(rw + 1), p, hdl::ext(x, rw, rw + 1), hdl::ext(den, dw, rw + 1));
  s += fmt::format("  wire {}_b = ~{}_d[{}];  // quotient bit: X >= D\n", p, p, rw);
  s +=
      fmt::format("  wire {} {}_r = {}_b ? {}_d[{}:0] : {};\n", hdl::range(rw), p, p, p, rw - 1, x);
  return s;
}

}  // namespace

std::string schlick_rtl(const hdl::DatapathPorts& p, const std::vector<SchlickUnit>& groups,
                        bool iterative, const StageLayout& layout) {
  using hdl::ext;
  using hdl::lit;
  using hdl::range;
  const SchlickConfig& c = groups.front().config();
  const int wi = c.in.width(), wo = c.out.width();
  const int q = c.out.frac_bits + 2;  // quotient bits: Q = floor(2 num / D)
  const int nf = c.n_format.frac_bits, wn = c.n_format.width();
  const int num_shift = nf + c.out.frac_bits;  // num = t 2^(Fn + Fo)
  const Stage& mac = rtl_stage(layout, "mac");
  const int dw = mac.registers[0].format.width();
  const int rw = dw + 1;               // partial remainder < 2 D
  const int n2w = wi + num_shift + 1;  // 2 num
  std::vector<std::int64_t> n;
  for (const SchlickUnit& u : groups) n.push_back(u.n_raw());

  std::string s = hdl::datapath_header(
      p,
      fmt::format("{}: schlick, Schlick 1994 S(t) = t / (n - n t + t) with an exact, correctly "
                  "rounded divider\n"
                  "(SchlickUnit::run in units/schlick/datapath.h): D = n (1 - t) + t exactly, "
                  "then Q = floor(2 t 2^(Fn + Fo) / D)\n"
                  "by a restoring radix-2 divider of {} quotient bits ({}), and S = (Q + 1) / "
                  "2 rounded half up, clamped to 1.0.",
                  p.module, q,
                  iterative ? "iterative: one bit a cycle, II = q" : "pipelined: a bit a stage"));
  s += hdl::datapath_input_stage(p);
  // ---- stage mac: D.
  s += rtl_stage_registers(mac, "D = n (1 - t) + t, exact (one multiplier, one adder)");
  s += fmt::format("  reg {} mac_t;  // t clamped, carried for the numerator\n", range(wi));
  s += hdl::group_table(p, "n", "in_group", wn, n,
                        fmt::format("n', {} (SchlickUnit::n_raw)", c.n_format.name()));
  const std::int64_t one = c.in.raw_one();
  s += fmt::format("  wire {} mac_tc = (in_t > {}) ? {} : in_t;\n", range(wi), lit(wi, one),
                   lit(wi, one));
  s += fmt::format("  wire {} mac_1t = {} - mac_tc;  // 1 - t\n", range(wi), lit(wi, one));
  const int pw = std::max(dw, wn + wi) + 1;
  s += fmt::format("  wire {} mac_d = {} * {} + ({} << {});\n", range(pw), ext("n", wn, pw),
                   ext("mac_1t", wi, pw), ext("mac_tc", wi, pw), nf);
  if (pw > dw) s += fmt::format("  wire unused_d = ^mac_d[{}:{}];  // D < max(n, 1)\n", pw - 1, dw);
  s += "  always @(posedge clk) begin\n";
  s += fmt::format("    {} <= {};\n", rtl_reg(mac, 0), ext("mac_d", pw, dw));
  s += "    mac_t <= mac_tc;\n  end\n";
  // 2 num = t 2^(Fn + Fo + 1): bit j of it.
  const auto n2_bit = [&](const std::string& t, int j) {
    const int tb = j - num_shift - 1;
    return tb >= 0 && tb < wi ? fmt::format("{}[{}]", t, tb) : std::string("1'b0");
  };
  // X_1 = floor(2 num / 2^(q - 1)) (< 2 D: the quotient fits q bits).
  const auto first_x = [&](const std::string& t, const std::string& name) {
    std::string out = fmt::format("  wire {} {}_n2 = {} << {};\n", range(n2w), name,
                                  ext(t, wi, n2w), num_shift + 1);
    out += fmt::format("  wire {} {}_hi = {}_n2 >> {};\n", range(n2w), name, name, q - 1);
    if (n2w > rw)
      out +=
          fmt::format("  wire unused_{}_hi = ^{}_hi[{}:{}];  // < 2 D\n", name, name, n2w - 1, rw);
    out += fmt::format("  wire {} {}_x = {};\n", range(rw), name, ext(name + "_hi", n2w, rw));
    if (q > 1)
      out += fmt::format("  wire unused_{}_lo = ^{}_n2[{}:0];  // read bit by bit\n", name, name,
                         q - 2);
    return out;
  };

  if (!iterative) {
    std::string r_prev, q_prev, d_prev = rtl_reg(mac, 0), t_prev = "mac_t";
    for (int k = 1; k <= q; ++k) {
      const Stage& st = rtl_stage(layout, fmt::format("q{}", k - 1));
      s += rtl_stage_registers(st, fmt::format("quotient bit {} of {}: R = 2 R + bit, subtract D "
                                               "when R >= D",
                                               k, q));
      const bool last = k == q;
      // 2 num has num_shift + 1 zero bits at the bottom: stage k brings down a bit of t only while
      // q - k > num_shift, so t is carried only as far as such a stage follows.
      const bool carry_t = q - (k + 1) >= num_shift + 1;
      if (!last) s += fmt::format("  reg {} {}_den;  // D carried\n", range(dw), st.name);
      if (carry_t) s += fmt::format("  reg {} {}_t;  // t carried\n", range(wi), st.name);
      if (k == 1) {
        s += first_x(t_prev, st.name);
      } else {
        s += fmt::format("  wire {} {}_x = {{{}, {}}};\n", range(rw), st.name,
                         fmt::format("{}[{}:0]", r_prev, rw - 2), n2_bit(t_prev, q - k));
        s += fmt::format("  wire unused_{} = {}[{}];  // R < D: its top bit is 0\n", st.name,
                         r_prev, rw - 1);
      }
      s += divider_step(st.name, st.name + "_x", d_prev, dw, rw);
      s += "  always @(posedge clk) begin\n";
      s += fmt::format("    {} <= {}_r;\n", rtl_reg(st, 0), st.name);
      s += fmt::format("    {} <= {};\n", rtl_reg(st, 1),
                       k == 1 ? st.name + "_b" : fmt::format("{{{}, {}_b}}", q_prev, st.name));
      if (!last) s += fmt::format("    {}_den <= {};\n", st.name, d_prev);
      if (carry_t) s += fmt::format("    {}_t <= {};\n", st.name, t_prev);
      s += "  end\n";
      r_prev = rtl_reg(st, 0);
      q_prev = rtl_reg(st, 1);
      d_prev = st.name + "_den";
      if (carry_t) t_prev = st.name + "_t";
    }
    s += fmt::format("  wire unused_rem = ^{};  // the last remainder is not needed\n", r_prev);
    // round: (Q + 1) >> 1, clamped.
    const Stage& rnd = rtl_stage(layout, "round");
    s += rtl_stage_registers(rnd, "S = (Q + 1) >> 1 (round half up), clamped to 1.0");
    s += fmt::format("  wire {} rnd_s = ({} + {}) >> 1;\n", range(q + 1), ext(q_prev, q, q + 1),
                     lit(q + 1, 1));
    s += fmt::format("  always @(posedge clk) {} <= (rnd_s > {}) ? {} : {};\n", rtl_reg(rnd, 0),
                     lit(q + 1, c.out.raw_one()), lit(wo, c.out.raw_one()),
                     q + 1 >= wo ? ext("rnd_s", q + 1, wo) : ext("rnd_s", q + 1, wo));
    if (q + 1 > wo) s += fmt::format("  wire unused_s = ^rnd_s[{}:{}];\n", q, wo);
    s += fmt::format("  assign result = {};\n", rtl_reg(rnd, 0));
    s += hdl::datapath_footer(p);
    return s;
  }

  // Iterative: one stage held q cycles (II = q); position 0 and mac mark a new request with a
  // valid bit, the stage counts its steps.
  const Stage& div = rtl_stage(layout, "div");
  const int kb = hdl::value_bits(static_cast<std::uint64_t>(q));
  s += "  reg in_v, mac_v;  // a new request at position 0, at mac\n";
  s += "  always @(posedge clk) begin\n    in_v <= start;\n    mac_v <= in_v;\n  end\n";
  s += rtl_stage_registers(div, fmt::format("the radix-2 divider, one quotient bit a cycle for {} "
                                            "cycles (II = {})",
                                            q, q));
  s += fmt::format("  reg {} div_k;  // quotient bits done\n", range(kb));
  s += fmt::format("  reg {} div_den;  // D\n", range(dw));
  s += fmt::format("  reg {} div_bits;  // numerator bits still to bring down, top first\n",
                   range(q - 1));
  s += first_x("mac_t", "div0");
  s += divider_step("div0", "div0_x", rtl_reg(mac, 0), dw, rw);
  s += fmt::format("  wire {} div_x = {{{}, div_bits[{}]}};\n", range(rw),
                   fmt::format("{}[{}:0]", rtl_reg(div, 0), rw - 2), q - 2);
  s += fmt::format("  wire unused_div = {}[{}];  // R < D: its top bit is 0\n", rtl_reg(div, 0),
                   rw - 1);
  s += divider_step("div", "div_x", "div_den", dw, rw);
  s += "  always @(posedge clk) begin\n";
  s += "    if (mac_v) begin  // first bit\n";
  s += fmt::format("      div_k <= {};\n", lit(kb, 1));
  s += fmt::format("      div_den <= {};\n", rtl_reg(mac, 0));
  s += fmt::format("      div_bits <= div0_n2[{}:0];\n", q - 2);
  s += fmt::format("      {} <= div0_r;\n", rtl_reg(div, 0));
  s += fmt::format("      {} <= {};\n", rtl_reg(div, 1), ext("div0_b", 1, q));
  s += fmt::format("    end else if (div_k != {} && div_k != {}) begin\n", lit(kb, 0), lit(kb, q));
  s += fmt::format("      div_k <= div_k + {};\n", lit(kb, 1));
  s += fmt::format("      div_bits <= div_bits << 1;\n");
  s += fmt::format("      {} <= div_r;\n", rtl_reg(div, 0));
  s += fmt::format("      {} <= {{{}[{}:0], div_b}};\n", rtl_reg(div, 1), rtl_reg(div, 1), q - 2);
  s += "    end\n  end\n";
  const Stage& rnd = rtl_stage(layout, "round");
  s += rtl_stage_registers(rnd, "S = (Q + 1) >> 1 (round half up), clamped to 1.0");
  s += fmt::format("  wire {} rnd_s = ({} + {}) >> 1;\n", range(q + 1),
                   ext(rtl_reg(div, 1), q, q + 1), lit(q + 1, 1));
  s += fmt::format("  always @(posedge clk) {} <= (rnd_s > {}) ? {} : {};\n", rtl_reg(rnd, 0),
                   lit(q + 1, c.out.raw_one()), lit(wo, c.out.raw_one()), ext("rnd_s", q + 1, wo));
  if (q + 1 > wo) s += fmt::format("  wire unused_s = ^rnd_s[{}:{}];\n", q, wo);
  s += fmt::format("  assign result = {};\n", rtl_reg(rnd, 0));
  s += hdl::datapath_footer(p);
  return s;
}

}  // namespace glint
