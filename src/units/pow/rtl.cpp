// pow in Verilog: the log2 and exp2 tables are the built PowTables' entries and each group's n is
// its PowUnit::n_raw; the shifts and roundings are PowUnit::run's.
#include "units/pow/rtl.h"

#include <fmt/format.h>

#include <algorithm>

#include "hdl/verilog.h"
#include "units/stage_rtl.h"

namespace glint {
namespace {

// A table of 2^bits + 2 entries (the last repeats 2^bits) read at the two ends of a segment, i
// and i + 1 (`bits` + 1-bit wires `i`, `i1`): one is even and the other odd, so the table is two
// case ROMs, the even entries j = 2h and the odd ones j = 2h + 1, each read once at h (the even
// bank at (i + 1) / 2, the odd at i / 2), and i's low bit puts their words in order as the wires
// `lo` and `hi`. Half the ROM of one table read at two addresses.
std::string banked_table(const std::string& name, const std::vector<std::int64_t>& words, int bits,
                         int width, const std::string& what, const std::string& i,
                         const std::string& i1, const std::string& lo, const std::string& hi) {
  using hdl::range;
  hdl::Rom even, odd;
  even.name = name + "_even";
  odd.name = name + "_odd";
  even.addr = fmt::format("{}[{}:1]", i1, bits);
  odd.addr = fmt::format("{}[{}:1]", i, bits);
  even.addr_bits = odd.addr_bits = bits;
  even.data_bits = odd.data_bits = width;
  for (std::size_t j = 0; j < words.size(); ++j)
    (j % 2 == 0 ? even : odd).words.push_back(words[j]);
  even.comment = what + "\nthe even entries j = 2h, at h";
  odd.comment = what + "\nthe odd entries j = 2h + 1, at h";
  std::string s = hdl::rom(even) + hdl::rom(odd);
  s += fmt::format("  wire {} {} = {}[0] ? {} : {};\n", range(width), lo, i, odd.name, even.name);
  s += fmt::format("  wire {} {} = {}[0] ? {} : {};\n", range(width), hi, i, even.name, odd.name);
  s += fmt::format("  wire unused_{} = {}[0];  // (i + 1)'s bank is the other one\n", name, i1);
  return s;
}

// (a + round(diff r 2^-rbits)): one table interpolation of PowUnit::run, as wires prefixed `p`.
// lo, hi: node registers of `nw` bits (unsigned); r: the remainder register (`rw` bits).
std::string interpolate(const std::string& p, const std::string& lo, const std::string& hi,
                        const std::string& r, int nw, int rw, int rbits) {
  using hdl::ext;
  const int dw = nw + 1, pw = dw + rw + 1, sw = pw + 1;
  std::string s;
  if (rbits == 0) {  // no bits below the address: the node itself
    s += fmt::format("  wire unused_{} = ^{{{}, {}}};\n", p, hi, r);
    s += fmt::format("  wire {} {}_v = {};\n", hdl::range(nw), p, lo);
    return s;
  }
  s += fmt::format("  wire signed {} {}_d = {} - {};\n", hdl::range(dw), p, ext(hi, nw, dw),
                   ext(lo, nw, dw));
  s += fmt::format("  wire signed {} {}_m = {} * $signed({});\n", hdl::range(pw), p,
                   ext(p + "_d", dw, pw, true), ext(r, rw, pw));
  s += fmt::format("  wire signed {} {}_t = ($signed({}) + {}) >>> {};  // round half up\n",
                   hdl::range(sw), p, ext(p + "_m", pw, sw, true),
                   hdl::slit(sw, std::int64_t{1} << (rbits - 1)), rbits);
  s += fmt::format("  wire {} {}_s = {} + {}_t;\n", hdl::range(sw), p, ext(lo, nw, sw), p);
  s +=
      fmt::format("  wire unused_{} = ^{}_s[{}:{}];  // between the two nodes\n", p, p, sw - 1, nw);
  s += fmt::format("  wire {} {}_v = {}_s[{}:0];\n", hdl::range(nw), p, p, nw - 1);
  return s;
}

}  // namespace

std::string pow_rtl(const hdl::DatapathPorts& p, const std::vector<PowUnit>& groups,
                    const StageLayout& layout) {
  using hdl::ext;
  using hdl::lit;
  using hdl::range;
  using hdl::slit;
  const PowUnit& first = groups.front();
  const PowConfig& c = first.config();
  const PowTables& tab = *first.tables();
  const int wi = c.in.width(), fi = c.in.frac_bits, wo = c.out.width(), wg = p.group_bits;
  const Stage& s1 = rtl_stage(layout, "log_table");
  const Stage& s2 = rtl_stage(layout, "log_interp");
  const Stage& s3 = rtl_stage(layout, "mul_n");
  const Stage& s4 = rtl_stage(layout, "exp_table");
  const Stage& s5 = rtl_stage(layout, "exp_interp");
  const int eb = s1.registers[0].format.width();   // normalisation shift
  const int lw = s1.registers[1].format.width();   // log2 node
  const int lrw = s1.registers[3].format.width();  // log2 remainder register
  const int tw = s2.registers[0].format.width();   // log2 t, signed
  const int nw = s2.registers[1].format.width();   // n
  const int yw = s3.registers[0].format.width();   // y, signed
  const int yiw = s4.registers[0].format.width();  // floor(y), signed
  const int xw = s4.registers[1].format.width();   // exp2 node
  const int erw = s4.registers[3].format.width();  // exp2 remainder register
  const int log_r = std::max(0, fi - c.log_bits), log_pad = std::max(0, c.log_bits - fi);
  const int exp_r = std::max(0, c.y_frac - c.exp_bits),
            exp_pad = std::max(0, c.exp_bits - c.y_frac);
  const int y_shift = c.n_format.frac_bits + c.log_frac - c.y_frac;
  const int out_shift = c.exp_frac - c.out.frac_bits;

  std::string s = hdl::datapath_header(
      p, fmt::format("{}: pow, t^n = exp2(n log2 t) the way a GPU special-function unit computes "
                     "it (PowUnit::run in\n"
                     "units/pow/datapath.h): leading-one normalisation and a log2 table of 2^{} + "
                     "1 entries with linear\n"
                     "interpolation, y = n log2 t rounded to {} fraction bits, an exp2 table of "
                     "2^{} + 1 entries with linear\n"
                     "interpolation, the shift by floor(y) and the final rounding (half up).",
                     p.module, c.log_bits, c.y_frac, c.exp_bits));
  s += hdl::datapath_input_stage(p);
  std::vector<std::int64_t> n;
  for (const PowUnit& u : groups) n.push_back(u.n_raw());

  // ---- stage 1: normalise t = 2^e m, read log2(m) at both ends of its segment.
  s += rtl_stage_registers(s1,
                           "t = 2^-shift m, m in [1, 2); the log2 nodes around m; the "
                           "remainder below the table address");
  s += "  reg z1, z2, z3, z4;  // t = 0: the result is 0 (carried)\n";
  s += fmt::format("  reg {} g1;  // the group carried to its n\n", range(wg));
  s += "  wire unused_g1 = ^g1;  // (one n for every group: not read)\n";
  s += fmt::format("  wire {} lt_tc = (in_t > {}) ? {} : in_t;  // t clamped to 1.0\n", range(wi),
                   lit(wi, c.in.raw_one()), lit(wi, c.in.raw_one()));
  // Leading-one detector: shift = Fi - e for the highest set bit e of t <= 1.0.
  std::string lzd = lit(eb, 0);
  for (int b = 0; b <= fi; ++b)
    lzd = fmt::format("lt_tc[{}] ? {} : {}", b, lit(eb, fi - b),
                      b == 0 ? lit(eb, 0) : "(" + lzd + ")");
  s += fmt::format("  wire {} lt_shift = {};  // leading-one detector\n", range(eb), lzd);
  s += fmt::format("  wire {} lt_m = lt_tc << lt_shift;  // 1.m, the leading one at bit {}\n",
                   range(wi), fi);
  if (wi > fi) s += fmt::format("  wire unused_lt = ^lt_m[{}:{}];\n", wi - 1, fi);
  const int ab = c.log_bits + 1;
  const std::string idx = log_pad > 0 ? fmt::format("{{1'b0, lt_m[{}:0], {}'d0}}", fi - 1, log_pad)
                                      : fmt::format("{{1'b0, lt_m[{}:{}]}}", fi - 1, log_r);
  s += fmt::format("  wire {} lt_i = {};  // (m - 1) >> r << pad\n", range(ab), idx);
  s += fmt::format("  wire {} lt_i1 = lt_i + {};\n", range(ab), lit(ab, 1));
  s += banked_table("log2_table", tab.log_table, c.log_bits, lw,
                    fmt::format("log2(1 + j 2^-{}) rounded to {} fraction bits, j = 0..2^{} + 1 "
                                "(PowTables::log_table; the last repeats 1.0)",
                                c.log_bits, c.log_frac, c.log_bits),
                    "lt_i", "lt_i1", "lt_lo", "lt_hi");
  s += "  always @(posedge clk) begin\n";
  s += "    z1 <= in_t == " + lit(wi, 0) + ";\n";
  s += "    g1 <= in_group;\n";
  s += fmt::format("    {} <= lt_shift;\n", rtl_reg(s1, 0));
  s += fmt::format("    {} <= lt_lo;\n", rtl_reg(s1, 1));
  s += fmt::format("    {} <= lt_hi;\n", rtl_reg(s1, 2));
  s += fmt::format("    {} <= {};\n", rtl_reg(s1, 3),
                   log_r > 0 ? fmt::format("lt_m[{}:0]", log_r - 1) : lit(lrw, 0));
  s += "  end\n";

  // ---- stage 2: log2 t = log2(m) - shift.
  s += rtl_stage_registers(s2,
                           "log2 t = log2 m - shift (interpolated, rounded half up); the "
                           "group's n");
  s += interpolate("li", rtl_reg(s1, 1), rtl_reg(s1, 2), rtl_reg(s1, 3), lw, lrw, log_r);
  s += hdl::group_table(p, "n", "g1", nw, n,
                        fmt::format("n, {} (PowUnit::n_raw)", c.n_format.name()));
  s += fmt::format("  wire {} li_sh = {};\n", range(eb), rtl_reg(s1, 0));
  s += "  always @(posedge clk) begin\n";
  s += "    z2 <= z1;\n";
  s += fmt::format("    {} <= {} - ({} <<< {});\n", rtl_reg(s2, 0), ext("li_v", lw, tw),
                   ext("li_sh", eb, tw), c.log_frac);
  s += fmt::format("    {} <= n;\n", rtl_reg(s2, 1));
  s += "  end\n";

  // ---- stage 3: y = n log2 t.
  s += rtl_stage_registers(s3, fmt::format("y = n log2 t rounded half up to {} fraction bits "
                                           "(<= 0)",
                                           c.y_frac));
  const int mw = nw + tw + 2;
  s += fmt::format("  wire signed {} mn_p = {} * {};\n", range(mw), ext(rtl_reg(s2, 1), nw, mw),
                   ext(rtl_reg(s2, 0), tw, mw, true));
  s += fmt::format("  wire signed {} mn_y = {};\n", range(mw),
                   y_shift > 0 ? fmt::format("(mn_p + {}) >>> {}",
                                             slit(mw, std::int64_t{1} << (y_shift - 1)), y_shift)
                               : std::string("mn_p"));
  if (mw > yw) s += fmt::format("  wire unused_mn = ^mn_y[{}:{}];\n", mw - 1, yw);
  s += "  always @(posedge clk) begin\n    z3 <= z2;\n";
  s += fmt::format("    {} <= {};\n  end\n", rtl_reg(s3, 0), ext("mn_y", mw, yw));

  // ---- stage 4: y = yi + yf, read exp2(yf) at both ends of its segment.
  s += rtl_stage_registers(s4, "floor(y); the exp2 nodes around its fraction; the remainder");
  const std::string y = rtl_reg(s3, 0);
  const int eab = c.exp_bits + 1;
  s += fmt::format("  wire {} et_yf = {}[{}:0];  // y - floor(y) 2^yfrac\n", range(c.y_frac), y,
                   c.y_frac - 1);
  const std::string eidx = exp_pad > 0 ? fmt::format("{{1'b0, et_yf, {}'d0}}", exp_pad)
                                       : fmt::format("{{1'b0, et_yf[{}:{}]}}", c.y_frac - 1, exp_r);
  s += fmt::format("  wire {} et_i = {};\n", range(eab), eidx);
  s += fmt::format("  wire {} et_i1 = et_i + {};\n", range(eab), lit(eab, 1));
  s += banked_table("exp2_table", tab.exp_table, c.exp_bits, xw,
                    fmt::format("exp2(j 2^-{}) rounded to {} fraction bits, j = 0..2^{} + 1 "
                                "(PowTables::exp_table; the last repeats 2.0)",
                                c.exp_bits, c.exp_frac, c.exp_bits),
                    "et_i", "et_i1", "et_lo", "et_hi");
  s += fmt::format("  wire signed {} et_y = {};\n", range(yw), y);
  s += fmt::format("  wire signed {} et_yi = et_y >>> {};  // floor(y)\n", range(yw), c.y_frac);
  if (yw > yiw) s += fmt::format("  wire unused_et = ^et_yi[{}:{}];\n", yw - 1, yiw);
  s += "  always @(posedge clk) begin\n    z4 <= z3;\n";
  s += fmt::format("    {} <= {};\n", rtl_reg(s4, 0), ext("et_yi", yw, yiw));
  s += fmt::format("    {} <= et_lo;\n", rtl_reg(s4, 1));
  s += fmt::format("    {} <= et_hi;\n", rtl_reg(s4, 2));
  s += fmt::format("    {} <= {};\n", rtl_reg(s4, 3),
                   exp_r > 0 ? fmt::format("et_yf[{}:0]", exp_r - 1) : lit(erw, 0));
  s += "  end\n";

  // ---- stage 5: exp2 interpolated, shifted right by shift = out_shift - floor(y), rounded.
  s += rtl_stage_registers(
      s5,
      "exp2(yf) interpolated; the result: its shift right by floor(-y) rounded half up, "
      "clamped to 1.0");
  s += interpolate("ei", rtl_reg(s4, 1), rtl_reg(s4, 2), rtl_reg(s4, 3), xw, erw, exp_r);
  const int shw = yiw + 8;  // out_shift - yi, signed
  s += fmt::format("  wire signed {} ei_shift = {} - {};\n", range(shw), slit(shw, out_shift),
                   ext(rtl_reg(s4, 0), yiw, shw, true));
  s += "  wire [63:0] ei_x = " + ext("ei_v", xw, 64) + ";\n";
  s += fmt::format("  wire [5:0] ei_k = ei_shift[5:0];\n");
  s += "  wire [63:0] ei_r = (ei_x + ((64'd1 << ei_k) >> 1)) >> ei_k;  // round half up\n";
  s += fmt::format(
      "  wire [63:0] ei_q = (ei_shift >= {}) ? 64'd0 : (ei_shift <= {}) ? ei_x : ei_r;\n",
      slit(shw, 62), slit(shw, 0));
  const std::int64_t one = c.out.raw_one();
  s += "  always @(posedge clk) begin\n";
  s += fmt::format("    {} <= ei_v;\n", rtl_reg(s5, 0));
  s += fmt::format("    {} <= z4 ? {} : (ei_q > {}) ? {} : {};\n", rtl_reg(s5, 1), lit(wo, 0),
                   lit(64, one), lit(wo, one), ext("ei_q", 64, wo));
  s += "  end\n";
  s += fmt::format("  wire unused_exp2 = ^{};  // shows exp2(yf) beside the result\n",
                   rtl_reg(s5, 0));
  s += fmt::format("  assign result = {};\n", rtl_reg(s5, 1));
  s += hdl::datapath_footer(p);
  return s;
}

}  // namespace glint
